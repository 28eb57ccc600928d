"""The finger-strike sense's numbers (FingerStrikeConfig): open-loop Reaches with and
without a finger's front striking the object, the wrench that the arm's joint torques
(arm.torque_measured) hold at the grasp frame, sampled every 1 ms.

    python analysis/measure_finger_strike.py

Prints, per scene: the largest force on the grasp frame during the Reach before any
contact (the Reach's own: accelerating the arm), the strike's onset (the force above
1 N), the force 1 ms in and its smallest value from 2 to 40 ms in, the side moment
(about world x plus z) every 2 ms over those 40 ms, and when the object first moved 1 mm.
"""

import dataclasses
import sys

import numpy as np
from pydrake.multibody.tree import JacobianWrtVariable
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import LogVectorOutput

from tegrasp_drake.commands.script_output import run_script, script_parser
from tegrasp_drake import AddScenarioController, LoadScenario, MakeSimulator, MakeStation
from tegrasp_drake.control.controller_config import OpenLoopControllerConfig
from tegrasp_drake.control.finger_strike import (grasp_wrench_from_torques, side_moment_nm,
                                                 strike_force_n)
from tegrasp_drake.scenario.scenario import resolve_object, validate
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.arm_kinematics import make_arm_control_plant
from tegrasp_drake.rig.objects import ObjectConfig

# (object, offset normal to the palm [m], along the stroke [m], yaw [deg]): scenes of
# the second grid (analysis/results_beyond/second_grid) that open loop knocked over.
SCENES = (("box", 0.0, 0.0, 5.4), ("box", 0.0, 0.025, -11.8), ("box", 0.0, -0.025, -12.5),
          ("thick_cylinder", -0.015, -0.025, -7.7))
END_S = 3.0  # past the Reach (settle 0.3 s + reach 2.5 s)
ONSET_N = 1.0  # twice the Reach's own force: a strike begins


def reach_log(object_name, dx, dy, yaw_deg):
    base = LoadScenario()
    scenario = validate(dataclasses.replace(
        base, object=resolve_object(ObjectConfig(name=object_name)), random_seed=700,
        placement=dataclasses.replace(base.placement, offset=[dx, dy], yaw_deg=yaw_deg),
        controller=OpenLoopControllerConfig()), "measure")
    builder = DiagramBuilder()
    station = builder.AddNamedSystem("station", MakeStation(scenario))
    AddScenarioController(builder, scenario, station=station)
    logs = {name: LogVectorOutput(station.GetOutputPort(port), builder, 1e-3)
            for name, port in (("q", ports.ARM_POSITION_MEASURED),
                               ("tau", ports.ARM_TORQUE_MEASURED), ("object", ports.OBJECT_STATE))}
    diagram = builder.Build()
    simulator = MakeSimulator(diagram, scenario)
    simulator.AdvanceTo(END_S)
    context = simulator.get_context()
    data = {name: log.FindLog(context).data() for name, log in logs.items()}
    data["t"] = logs["q"].FindLog(context).sample_times()
    return data


def wrenches(q, tau):
    plant = make_arm_control_plant()
    context = plant.CreateDefaultContext()
    frame, world = plant.GetFrameByName("grasp_frame"), plant.world_frame()
    out = []
    for q_k, tau_k in zip(q.T, tau.T):
        plant.SetPositions(context, q_k)
        J = plant.CalcJacobianSpatialVelocity(context, JacobianWrtVariable.kV, frame,
                                              np.zeros(3), world, world)
        out.append(grasp_wrench_from_torques(J, tau_k))
    return np.array(out)


def main(argv=None) -> int:
    script_parser("measure_finger_strike", __doc__).parse_args(argv)
    for scene in SCENES:
        data = reach_log(*scene)
        t, w = data["t"], wrenches(data["q"], data["tau"])
        baseline = w[0]
        force = np.array([strike_force_n(x, baseline) for x in w])
        position = data["object"][4:7]
        moved = np.linalg.norm(position - position[:, :1], axis=0)
        struck = np.flatnonzero(force > ONSET_N)
        print(f"{scene}:")
        if struck.size == 0:
            print(f"  no strike; the Reach's own force at most {force.max():.2f} N, side "
                  f"moment at most {max(abs(side_moment_nm(x, baseline)) for x in w):.3f} N m")
            continue
        k = struck[0]
        print(f"  Reach's own force before it at most {force[:k].max():.2f} N; onset "
              f"{t[k]:.3f} s; {force[k]:.1f} N 1 ms in, at least {force[k + 2:k + 40].min():.1f}"
              f" N from 2 to 40 ms; object moved 1 mm at "
              f"{t[np.argmax(moved > 1e-3)] if (moved > 1e-3).any() else float('nan'):.3f} s")
        moments = [side_moment_nm(w[i], baseline) for i in range(k, k + 40, 2)]
        print("  side moment every 2 ms [N m]: " + " ".join(f"{m:+.2f}" for m in moments))
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "measure_finger_strike"))
