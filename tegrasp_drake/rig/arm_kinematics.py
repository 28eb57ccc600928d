"""The arm as the controller sees it: the JACO2's six joints (the gripper rigid) with
the grasp frame G (origin between the pads' centres, +z the approach, +y toward the left
finger), and IK on it."""

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import FixedOffsetFrame
from pydrake.solvers import Solve

from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.ranges import Range
from tegrasp_drake.rig import paths
from tegrasp_drake.robotiq.dimensions import PAD_CENTER_Z

ARM_URL = "package://tegrasp/jaco2/j2n6s300.sdf"
GRIPPER_URL = "package://tegrasp/robotiq_2f85/robotiq_2f85_tactile.sdf"
X_FLANGE_GRIPPER = RigidTransform()  # the gripper's mounting face on the Jaco's flange
# Side grasp: approach along world +x, stroke along world y, so G's x points down.
R_WG_SIDE_GRASP = RotationMatrix(np.array([[0.0, 0.0, 1.0],
                                           [0.0, 1.0, 0.0],
                                           [-1.0, 0.0, 0.0]]))
# The pad centre above the table [m], for the grasp script's setting and the station.
GRASP_HEIGHT_RANGE = Range(low=0.005, high=0.5, unit="m",
                           why="pad centre above the table, within the tallest object")
# A configuration near the side grasp in front of the robot, to seed IK [rad].
IK_SEED = np.array([3.324, 4.531, 1.126, 2.483, 2.31, 3.913])


def make_arm_control_plant() -> MultibodyPlant:
    """A continuous MultibodyPlant of the arm alone, with a `grasp_frame` on link_6."""
    plant = MultibodyPlant(0.0)
    parser = paths.make_parser(plant)
    (arm,) = parser.AddModels(url=ARM_URL)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", arm))
    flange = plant.GetFrameByName("flange", arm)
    X_FG = X_FLANGE_GRIPPER @ RigidTransform([0.0, 0.0, PAD_CENTER_Z])
    plant.AddFrame(FixedOffsetFrame("grasp_frame", flange, X_FG))
    plant.Finalize()
    return plant


class UnreachablePoseError(ValueError):
    """No arm configuration puts the grasp frame at the pose asked; the message says where."""


def solve_grasp_frame_ik(plant: MultibodyPlant, X_WG: RigidTransform, q_seed=IK_SEED,
                         position_tolerance=1e-7, angle_tolerance=1e-7) -> np.ndarray:
    """Joint angles [rad] that put the grasp frame at X_WG, near q_seed; UnreachablePoseError
    if none (a pose the caller took from settings: it names them)."""
    ik = InverseKinematics(plant)
    frame = plant.GetFrameByName("grasp_frame")
    p = X_WG.translation()
    ik.AddPositionConstraint(frame, [0, 0, 0], plant.world_frame(),
                             p - position_tolerance, p + position_tolerance)
    ik.AddOrientationConstraint(frame, RotationMatrix(), plant.world_frame(),
                                X_WG.rotation(), angle_tolerance)
    q = ik.q()
    ik.prog().AddQuadraticErrorCost(np.eye(len(q)), q_seed, q)
    ik.prog().SetInitialGuess(q, q_seed)
    result = Solve(ik.prog())
    if not result.is_success():
        raise UnreachablePoseError("no arm configuration puts the grasp frame at "
                                   f"{number_text(list(p))} m")
    return result.GetSolution(q)
