"""The simulated station through its exported ports."""

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator

from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.control.scripted_grasp import gripper_command
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.scenario import MakeSimulatedStation
from tegrasp_drake.simulation.station import initial_arm_positions
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.taxel_layout import taxel_centers

GRIP_FORCE = 30.0


def _open_station_at_rest(scenario):
    """(station, context, gripper command port) of the scenario's simulated station, the arm
    held at its start pose and the gripper told to open at 50 mm/s."""
    station = MakeSimulatedStation(scenario)
    context = station.CreateDefaultContext()
    q0 = initial_arm_positions(scenario.arm)
    station.GetInputPort(ports.ARM_DESIRED_STATE).FixValue(context,
                                                            np.concatenate([q0, np.zeros(6)]))
    command = station.GetInputPort(ports.GRIPPER_COMMAND)
    command.FixValue(context, gripper_command(ru.STROKE_M, 0.05, GRIP_FORCE))
    return station, context, command


def _squeeze(offset_x=0.0, close_at=0.3, until=2.2, object_name="box"):
    """Starts with the open pads around the object, closes at GRIP_FORCE; returns samples.
    On the prismatic hand: these check the taxels' integration of the pressure field, which
    needs pads that stay exactly parallel (the linkage's constraints tilt a pressed pad by
    a few hundredths of a degree, a 3 % gradient across a 4 mm elastomer); read by the
    ideal force taxels, since the capacitive pad's 4-count noise and nonlinear reading
    would hide the integration's percent (tests/simulation/test_capacitive_taxels.py
    checks that reading)."""
    scenario = LoadScenario(overrides=["gripper.model=prismatic", "tactile.transducer=force",
        "arm.initial_gripper_xyz=[0.72, 0.0, 0.055]", f"placement.offset=[{offset_x}, 0.0]",
        f"object.name={object_name}"])
    station, context, command = _open_station_at_rest(scenario)
    simulator = Simulator(station, context)
    simulator.AdvanceTo(close_at)
    before = {name: station.GetOutputPort(ports.taxel_forces(name)).Eval(context).copy()
              for name in ("left", "right")}
    command.FixValue(context, gripper_command(0.0, 0.05, GRIP_FORCE))
    simulator.AdvanceTo(until)
    after = {name: station.GetOutputPort(ports.taxel_forces(name)).Eval(context).copy()
             for name in ("left", "right")}
    contacts = station.GetOutputPort(ports.CONTACT_RESULTS).Eval(context)
    return station, context, before, after, contacts


@pytest.fixture(scope="module")
def centred_squeeze():
    return _squeeze()


@pytest.fixture(scope="module")
def fingertip_squeeze():
    """The thin cylinder 1 cm further from the palm (the paper's misplacement normal to the
    palm): its contact line lies in the fingertip row of the 24 mm pads (rows 6 mm long)."""
    return _squeeze(offset_x=0.01, object_name="thin_cylinder")


def test_exported_ports_match_the_hardware_interface():
    station = MakeSimulatedStation(LoadScenario())
    sizes = {station.get_output_port(i).get_name(): station.get_output_port(i).size()
             for i in range(station.num_output_ports())
             if station.get_output_port(i).get_data_type().name == "kVectorValued"}
    for name, size in ports.CONTROLLER_OUTPUTS.items():
        assert sizes[name] == size, name
    assert station.num_input_ports() == len(ports.CONTROLLER_INPUTS)
    for name, size in ports.CONTROLLER_INPUTS.items():
        assert station.GetInputPort(name).size() == size, name
    for name in (ports.OBJECT_STATE, ports.TRUE_TAXEL_FORCES, ports.CONTACT_RESULTS,
                 ports.BODY_POSES, ports.QUERY_OBJECT, ports.GRIPPER_STATE,
                 ports.GRIPPER_PLANT_DESIRED_STATE):
        assert station.HasOutputPort(name), name


def test_sa_is_zero_to_noise_without_contact(centred_squeeze):
    _, _, before, _, _ = centred_squeeze
    for forces in before.values():
        assert abs(forces.sum()) < 0.1  # 12 taxels x 0.005 N noise


def test_sa_equals_the_grip_force_while_holding(centred_squeeze):
    station, context, _, after, contacts = centred_squeeze
    for forces in after.values():
        assert forces.sum() == pytest.approx(GRIP_FORCE, rel=0.05)
    status = station.GetOutputPort(ports.GRIPPER_STATUS).Eval(context)
    assert status[ru.STATUS_OBJ] == ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING


# Under an even press each taxel should carry 1/12 of the pad's force. The expected
# deviations: the pressure falls to zero over the last ~0.04 mm at the pad's rim (edge
# taxels -0.25 %, corner taxels -0.45 %), noise of 0.005 N per taxel (0.2 % of 2.5 N; the
# largest of 24 draws about 0.6 %) and the 0.001 N quantisation: about 1.1 % together.
EVEN_PATTERN_RTOL = 0.02


def test_even_press_gives_an_even_pattern_over_all_taxels(centred_squeeze):
    _, _, _, after, _ = centred_squeeze
    for forces in after.values():
        np.testing.assert_allclose(forces, forces.mean(), rtol=EVEN_PATTERN_RTOL)
        centroid = forces @ taxel_centers() / forces.sum()
        assert np.linalg.norm(centroid[:2]) < 0.0002  # m; a taxel cell is 6.7 x 6.0 mm


def test_even_press_gives_a_mirror_symmetric_pattern(centred_squeeze):
    _, _, _, after, _ = centred_squeeze
    for forces in after.values():
        grid = forces.reshape(4, 3)  # rows along the pad's length, columns across its width
        np.testing.assert_allclose(grid, grid[:, ::-1], rtol=EVEN_PATTERN_RTOL)
        np.testing.assert_allclose(grid, grid[::-1, :], rtol=EVEN_PATTERN_RTOL)


def test_every_taxel_carries_load_under_a_full_press(centred_squeeze):
    _, _, _, after, _ = centred_squeeze
    for forces in after.values():
        assert np.all(forces > 0.04 * GRIP_FORCE)


def test_off_centre_press_shifts_the_pattern_along_the_pad(centred_squeeze, fingertip_squeeze):
    _, _, _, centred, _ = centred_squeeze
    _, _, _, shifted, _ = fingertip_squeeze
    centre = centred["left"] @ taxel_centers() / centred["left"].sum()
    moved = shifted["left"] @ taxel_centers() / shifted["left"].sum()
    # A cylinder 1 cm further from the palm presses the pad's fingertip end. (The 45 mm box
    # would overhang the 24 mm pad at both ends and press it evenly.)
    assert moved[1] - centre[1] > 0.002


def test_an_object_toward_the_fingertip_loads_the_same_row_on_both_pads(fingertip_squeeze):
    _, _, _, after, _ = fingertip_squeeze
    for finger, forces in after.items():
        rows = forces.reshape(4, 3).sum(axis=1)  # row 0 nearest the palm
        assert rows[3] > 0.5 * rows.sum(), finger  # the fingertip row carries most


def _drive_vibration_peaks(close: bool) -> tuple[float, float]:
    """(largest |drive vibration| [m/s^2] over 0.1-0.2 s, over 0.2-0.4 s) of the default
    station (linkage hand, JACO2) with the arm held at its start; the gripper told to stay
    open, or (close) to close at 50 mm/s from 0.2 s."""
    scenario = LoadScenario()
    station, context, command = _open_station_at_rest(scenario)
    drive = station.GetSubsystemByName("pad_films_drive_vibration")
    drive_context = drive.GetMyContextFromRoot(context)
    simulator = Simulator(station, context)
    peaks = []
    for start, end in ((0.1, 0.2), (0.2, 0.4)):
        if close and start == 0.2:
            command.FixValue(context, gripper_command(0.0, 0.05, GRIP_FORCE))
        values = []
        for t in np.arange(start, end, 0.001):
            simulator.AdvanceTo(t)
            values.append(np.abs(drive.get_output_port().Eval(drive_context)).max())
        peaks.append(max(values))
    return peaks[0], peaks[1]


def test_drive_vibration_is_off_while_the_joints_stand_still_and_on_while_they_move():
    still, still_later = _drive_vibration_peaks(close=False)
    assert still < 1e-3 and still_later < 1e-3
    _, closing = _drive_vibration_peaks(close=True)
    # The fingers at 25 mm/s of half opening, a third of full speed: the pinion's mesh at
    # 400 Hz, on the fingertip's mode (gain 10), reads up to 0.3 / 3 x 10 = 1 m/s^2 once
    # the fingers are at speed (0.05 s of ramp at 0.5 m/s^2).
    assert closing > 0.1


def _start_of_grasp_frame(scenario) -> np.ndarray:
    """p_WG [m] of the built station's arm at t = 0 (the plant's default positions)."""
    from tegrasp_drake.simulation.carriage import ArmGraspFrameKinematics
    station = MakeSimulatedStation(scenario)
    context = station.CreateDefaultContext()
    q = station.GetOutputPort(ports.ARM_POSITION_MEASURED).Eval(context)
    return ArmGraspFrameKinematics().pose_and_jacobian(q)[0].translation()


def test_the_arm_starts_off_its_start_pose_by_the_seeds_draw_within_the_bound():
    from tegrasp_drake.simulation.station import start_offset_m
    nominal = LoadScenario(overrides=["random_seed=600"])
    np.testing.assert_allclose(_start_of_grasp_frame(nominal), nominal.arm.initial_gripper_xyz,
                               atol=1e-6)
    scenario = LoadScenario(overrides=["random_seed=600", "arm.start_position_bound_m=0.005"])
    offset = start_offset_m(scenario.arm, scenario.random_seed)
    assert np.all(np.abs(offset) <= 0.005) and np.linalg.norm(offset) > 0.001
    np.testing.assert_allclose(_start_of_grasp_frame(scenario),
                               np.add(scenario.arm.initial_gripper_xyz, offset), atol=1e-6)
    other_seed = LoadScenario(overrides=["random_seed=601", "arm.start_position_bound_m=0.005"])
    assert not np.allclose(start_offset_m(other_seed.arm, 601), offset)


def _film_impact_stiffness(scenario) -> float:
    """The built station's films' impact stiffness [N/m] (FilmLoads)."""
    station = MakeSimulatedStation(scenario)
    films = next(s for s in station.GetSystems() if s.get_name() == "pad_films")
    return films.GetSubsystemByName("film_loads").impact_stiffness_n_per_m


def test_the_films_impact_stiffness_follows_the_pad_modulus_set_alone():
    from tegrasp_drake.simulation.pad_vibration_sensor import pad_contact_stiffness
    default = _film_impact_stiffness(LoadScenario())
    stiffer = _film_impact_stiffness(LoadScenario(overrides=["tactile.pad_modulus_pa=4.0e6"]))
    assert default == pytest.approx(4.8e5) and stiffer == pytest.approx(9.6e5)
    assert stiffer == pad_contact_stiffness(4.0e6)
    overridden = LoadScenario(overrides=["tactile.pad_modulus_pa=4.0e6",
                                         "vibration.film.pad_contact_stiffness_n_per_m=3.0e5"])
    assert _film_impact_stiffness(overridden) == pytest.approx(3.0e5)
