"""The two simulated 2F-85 hands, selected by `gripper.model`: what differs between them.

- `linkage` (default): the 2F-85's five-bar fingers (robotiq/linkage.py); actuated
  coordinate a, the left driver's angle [rad], behind it the drive (robotiq/drive.py).
- `prismatic`: two prismatic fingers (modelgen/robotiq_sdf.py); a is half the opening [m],
  with an idealised drive (no rotor, a stiff force-bounded PD, backdrivable).

A hand maps a to half the pad opening q [m], in which SimRobotiqDriver plans."""

import dataclasses

import numpy as np
from pydrake.multibody.tree import JointActuatorIndex, PdControllerGains
from pydrake.systems.primitives import MatrixGain

from tegrasp_drake.modelgen.robotiq_linkage_sdf import robotiq_linkage_sdf
from tegrasp_drake.rig.objects import PRISMATIC_HAND_EVENTS_FOLDER
from tegrasp_drake.robotiq import drive, linkage
from tegrasp_drake.robotiq.dimensions import HALF_STROKE, PAD_CENTER_Z, PALM_Z


@dataclasses.dataclass(frozen=True)
class PrismaticHand:
    """Two prismatic fingers; the actuated coordinate is half the opening [m]."""
    url: str = "package://tegrasp/robotiq_2f85/robotiq_2f85_tactile.sdf"
    actuated_joint: str = "left_finger_joint"
    non_backdrivable: bool = False
    events_folder: str = PRISMATIC_HAND_EVENTS_FOLDER  # its memorized events, in the package's
    # Eq. 3 [SA, RA], chosen on held-out runs (analysis/ensemble_thresholds_prismatic.md)
    ensemble_thresholds: tuple = (("reach_load", (0.44, 0.65)), ("load_lift", (0.94, 0.90)),
                                  ("place_unload", (0.98, 0.90)))

    def half_opening(self, a: float, f: linkage.Functions = linkage.FLOATS) -> float:
        return a

    def actuated(self, half_opening_m: float, f: linkage.Functions = linkage.FLOATS) -> float:
        return half_opening_m

    def half_opening_rate(self, a: float, f: linkage.Functions = linkage.FLOATS) -> float:
        """d(half opening)/da."""
        return 1.0

    def default_positions(self) -> list[float]:
        return [HALF_STROKE, HALF_STROKE]

    def pd_gains(self, config) -> tuple[float, float]:
        """(kp [N/m], kd [N s/m]) of the PD on half the opening (GripperDriverConfig)."""
        return config.position_gain, config.damping_gain

    def drive_inertia(self, config) -> float:
        """The inertia the drive moves [kg]: none modelled (the PD is stiff)."""
        return 0.0

    def pad_center_offset(self, opening_m: float) -> float:
        """The pads' centres' offset beyond the grasp frame [m]: 0 at any opening."""
        return 0.0

    def hooked_object_offset(self, opening_m: float, contact_offset_m: float,
                             object_width_m: float) -> float | None:
        """None: prismatic pads stay parallel, they cannot curl past an object."""
        return None


@dataclasses.dataclass(frozen=True)
class LinkageHand:
    """The 2F-85's five-bar fingers; the actuated coordinate is the left driver's angle."""
    url: str = "package://tegrasp/robotiq_2f85/robotiq_2f85_linkage.sdf"
    actuated_joint: str = "left_driver_joint"
    non_backdrivable: bool = True
    events_folder: str = ""  # its memorized events: the package's events themselves
    # Eq. 3 [SA, RA], chosen on held-out runs (analysis/ensemble_thresholds.md)
    ensemble_thresholds: tuple = (("reach_load", (0.88, 0.55)), ("load_lift", (0.48, 0.75)),
                                  ("place_unload", (0.98, 0.50)))

    def half_opening(self, a: float, f: linkage.Functions = linkage.FLOATS) -> float:
        return linkage.half_opening(a, f)

    def actuated(self, half_opening_m: float, f: linkage.Functions = linkage.FLOATS) -> float:
        return linkage.driver_angle(half_opening_m, f)

    def half_opening_rate(self, a: float, f: linkage.Functions = linkage.FLOATS) -> float:
        return linkage.half_opening_rate(a, f)

    def default_positions(self) -> list[float]:
        return [0.0] * 8  # every joint at zero is the open pose, the loops closed

    def pd_gains(self, config) -> tuple[float, float]:
        """(kp [N m/rad], kd [N m s/rad]): the firmware's position loop on the driver."""
        return drive.loop_gains(config.position_loop_hz, self.drive_inertia(config))

    def drive_inertia(self, config) -> float:
        """The drive's inertia about the driver [kg m^2] (linkage and rotor via the screw)."""
        return drive.drive_inertia(config.screw_efficiency)

    def pad_center_offset(self, opening_m: float) -> float:
        """The pads' centres' offset beyond the grasp frame along the approach axis [m] at
        opening_m apart (on the pin): -9.3 mm open, +4.0 mm at 25 mm."""
        return (float(linkage.PAD_CENTER_OPEN[1]) - PAD_CENTER_Z
                + linkage.pad_travel_at_opening(opening_m))

    def hooked_object_offset(self, opening_m: float, contact_offset_m: float,
                             object_width_m: float) -> float | None:
        """Where the centre of an object object_width_m [m] across lies along the approach axis
        [m] from the pads' centres at that width (on the pin), when the curled fingertips, the
        drive at opening_m [m] (its on-pin reading), touch it contact_offset_m [m] toward the
        fingertips from the pads' centres (linkage.hooked_object_z, the object taken round,
        centred between the fingers); not nearer the palm than the palm (PALM_Z) lets it be.
        None when the pads could touch it flat there. At 4.5 mm open on the distal row (+9 mm)
        a 25 mm cylinder lies 25.5 mm toward the palm."""
        radius = object_width_m / 2.0
        z = linkage.hooked_object_z(linkage.driver_angle(opening_m / 2.0), contact_offset_m,
                                    radius)
        if z is None:
            return None
        return max(z, PALM_Z + radius) - float(linkage.pad_center(
            linkage.driver_angle(radius))[1])


def add_gripper_model(parser, hand, pad_refinement: int = 0):
    """Adds `hand`'s model and returns its instance; pad_refinement > 0 (linkage hand only)
    splits the pads' collision box mesh that many times (modelgen/pad_mesh.py)."""
    if not pad_refinement:
        (gripper,) = parser.AddModels(url=hand.url)
        return gripper
    if not isinstance(hand, LinkageHand):
        raise ValueError("a refined pad mesh is for the linkage hand only")
    (gripper,) = parser.AddModelsFromString(robotiq_linkage_sdf(pad_refinement), "sdf")
    return gripper


PAD_COLLISION = "pad"  # the pads' collision geometries' name (modelgen/robotiq_sdf.py)


def set_pad_contact(plant, scene_graph, gripper, *, friction: float,
                    modulus_pa: float) -> None:
    """Gives the hand's pads (collision geometries named PAD_COLLISION) the Coulomb
    coefficient `friction`, static and dynamic, and the hydroelastic modulus `modulus_pa`
    [Pa], replacing the model file's; before Finalize. ValueError when the hand has no pad."""
    from pydrake.geometry import ProximityProperties, RoleAssign
    from pydrake.multibody.plant import CoulombFriction
    inspector = scene_graph.model_inspector()
    pads = [geometry for index in plant.GetBodyIndices(gripper)
            for geometry in plant.GetCollisionGeometriesForBody(plant.get_body(index))
            if inspector.GetName(geometry).split("::")[-1] == PAD_COLLISION]
    if not pads:
        raise ValueError(f"the gripper model has no '{PAD_COLLISION}' collision geometry")
    for geometry in pads:
        properties = ProximityProperties(inspector.GetProximityProperties(geometry))
        properties.UpdateProperty("material", "coulomb_friction",
                                  CoulombFriction(friction, friction))
        properties.UpdateProperty("hydroelastic", "hydroelastic_modulus", modulus_pa)
        scene_graph.AssignRole(plant.get_source_id(), geometry, properties,
                               RoleAssign.kReplace)


def gripper_hand(model: str):
    """The hand of a `gripper.model` name (GRIPPER_MODELS)."""
    return {"linkage": LinkageHand, "prismatic": PrismaticHand}[model]()


def configure_drive(plant, gripper, hand, config) -> None:
    """Sets the gripper actuator's PD gains before Finalize and scales a modelled rotor's
    inertia by the screw's efficiency (robotiq/drive.py)."""
    kp, kd = hand.pd_gains(config)
    # GetJointActuatorIndices(instance) is empty before Finalize(): walk all actuators.
    for i in range(plant.num_actuators()):
        actuator = plant.get_joint_actuator(JointActuatorIndex(i))
        if actuator.model_instance() != gripper:
            continue
        actuator.set_controller_gains(PdControllerGains(p=kp, d=kd))
        if actuator.default_rotor_inertia() > 0.0:
            actuator.set_default_rotor_inertia(config.screw_efficiency
                                               * drive.ROTOR_INERTIA_KG_M2)


def actuated_state_selector(plant, gripper, hand) -> MatrixGain:
    """A MatrixGain picking (a, da/dt) out of the gripper's state (driver's finger_state)."""
    joint = plant.GetJointByName(hand.actuated_joint, gripper)
    nq, nv = plant.num_positions(gripper), plant.num_velocities(gripper)
    q_marker = np.zeros(plant.num_positions())
    q_marker[joint.position_start()] = 1.0
    v_marker = np.zeros(plant.num_velocities())
    v_marker[joint.velocity_start()] = 1.0
    selection = np.zeros((2, nq + nv))
    selection[0, :nq] = plant.GetPositionsFromArray(gripper, q_marker)
    selection[1, nq:] = plant.GetVelocitiesFromArray(gripper, v_marker)
    return MatrixGain(selection)
