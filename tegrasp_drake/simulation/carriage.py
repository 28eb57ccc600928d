"""The Cartesian carriage: the gripper on six actuated joints that reproduce the JACO2's
end-point impedance at the grasp frame G, for sweeps (`station.arm: carriage`). Three
prismatic joints along the principal axes of the arm's translational mobility at G, then
yaw, pitch and roll about world z, y, x; each on the plant's implicit PD (stable under SAP at
1 ms for any gains). docs/model.md, "The carriage". Frames: world W; G between the pads'
centres, z the approach; wrenches [Mx, My, Mz, Fx, Fy, Fz] [N m, N] at G, in W."""

import dataclasses

import numpy as np
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix
from pydrake.multibody.tree import (JacobianWrtVariable, PdControllerGains, PrismaticJoint,
                                    RevoluteJoint, RotationalInertia, SpatialInertia)

from tegrasp_drake.rig.arm_kinematics import (R_WG_SIDE_GRASP, make_arm_control_plant,
                                              solve_grasp_frame_ik)

AXES = np.eye(3)
ROTATION_AXES = (2, 1, 0)  # the gimbal: yaw about z, then pitch about y, then roll about x
# Each gimbal body's own mass [kg]: a body needs some; 10 g at G's origin adds no moment.
GIMBAL_BODY_MASS_KG = 0.01
MIN_INERTIA_KG_M2 = 1e-6  # floor of a gimbal body's inertia step (a body needs some)


@dataclasses.dataclass(frozen=True)
class EndpointImpedance:
    """End-point impedance at G, [rotation about world x, y, z; translation along
    translation_axes' columns]: stiffness [N m/rad; N/m], damping [N m s/rad; N s/m],
    inertia [kg m^2; kg]. translation_axes: 3 x 3, unit axes in world, heaviest first."""
    stiffness: np.ndarray
    damping: np.ndarray
    inertia: np.ndarray
    translation_axes: np.ndarray


def _along(inverse: np.ndarray, axes: np.ndarray) -> np.ndarray:
    """1 / (a^T X a) for each column a of `axes`: what a push along a alone meets."""
    return 1.0 / np.einsum("ij,ik,kj->j", axes, inverse, axes)


def arm_endpoint_impedance(arm_config, X_WG: RigidTransform) -> EndpointImpedance:
    """The JACO2's end-point impedance at G when G is at X_WG: its joint PD `arm_config`
    (ArmDriverConfig) and its inertia as a push along each carriage axis alone meets them."""
    plant = make_arm_control_plant()
    context = plant.CreateDefaultContext()
    plant.SetPositions(context, solve_grasp_frame_ik(plant, X_WG))
    world = plant.world_frame()
    J = plant.CalcJacobianSpatialVelocity(context, JacobianWrtVariable.kV,
                                          plant.GetFrameByName("grasp_frame"), np.zeros(3),
                                          world, world)
    # The inverses of K_x, D_x and Lambda: J K_q^-1 J^T and so on, no inverse of J needed.
    joints = np.eye(plant.num_velocities())
    compliance = J @ (joints / arm_config.position_gain) @ J.T
    damping_inverse = J @ (joints / arm_config.damping_gain) @ J.T
    mobility = J @ np.linalg.inv(plant.CalcMassMatrix(context)) @ J.T
    inverse_masses, axes = np.linalg.eigh(mobility[3:, 3:])
    axes = axes[:, np.argsort(inverse_masses)]  # heaviest first
    axes *= np.sign(axes[np.argmax(np.abs(axes), axis=0), range(3)])  # mostly positive
    rotation, translation = slice(0, 3), slice(3, 6)
    return EndpointImpedance(
        np.concatenate([_along(compliance[rotation, rotation], AXES),
                        _along(compliance[translation, translation], axes)]),
        np.concatenate([_along(damping_inverse[rotation, rotation], AXES),
                        _along(damping_inverse[translation, translation], axes)]),
        np.concatenate([_along(mobility[rotation, rotation], AXES),
                        _along(mobility[translation, translation], axes)]),
        axes)


@dataclasses.dataclass(frozen=True)
class Carriage:
    """The carriage in a plant: its model instance, joints in actuator order, prismatic
    joints' unit axes in world (3 x 3, columns in joint order) and the body holding the gripper."""
    instance: object
    joints: tuple
    translation_axes: np.ndarray
    end_body: object


def _translation_masses(inertia: np.ndarray) -> list:
    """Each prismatic body's own mass [kg], heaviest axis first, so joint k moves the arm's mass."""
    masses = list(inertia[3:]) + [GIMBAL_BODY_MASS_KG * 3]
    return [max(masses[k] - masses[k + 1], GIMBAL_BODY_MASS_KG) for k in range(3)]


def _body_inertia(mass_kg: float, inertia_kg_m2: float) -> SpatialInertia:
    """A body's inertia about its origin: the mass there and an equal moment about any axis."""
    return SpatialInertia.MakeFromCentralInertia(
        mass_kg, np.zeros(3), RotationalInertia(inertia_kg_m2, inertia_kg_m2, inertia_kg_m2))


def AddCarriage(plant, impedance: EndpointImpedance, name: str = "carriage") -> Carriage:
    """Adds the six-joint carriage to the unfinalized `plant`, with implicit PD gains from
    `impedance` and gravity off; all joints at zero put G at W's origin, side-grasp oriented."""
    instance = plant.AddModelInstance(name)
    parent, joints = plant.world_body(), []
    axes = impedance.translation_axes
    for k, mass in enumerate(_translation_masses(impedance.inertia)):
        body = plant.AddRigidBody(f"{name}_slide_{k}", instance,
                                  _body_inertia(mass, MIN_INERTIA_KG_M2))
        joints.append(plant.AddJoint(PrismaticJoint(
            f"{name}_slide_{k}", parent.body_frame(), body.body_frame(), axes[:, k])))
        parent = body
    # Gimbal bodies: each one's rotational inertia is the step that makes the joints before
    # it see the arm's inertia about their axes (yaw sees all three bodies, roll one).
    inertias = [impedance.inertia[a] for a in ROTATION_AXES] + [0.0]
    for k, axis in enumerate(ROTATION_AXES):
        step = max(inertias[k] - inertias[k + 1], MIN_INERTIA_KG_M2)
        body = plant.AddRigidBody(
            f"{name}_{'xyz'[axis]}_turn", instance, _body_inertia(GIMBAL_BODY_MASS_KG, step))
        joints.append(plant.AddJoint(RevoluteJoint(
            f"{name}_{'xyz'[axis]}_rotation", parent.body_frame(), body.body_frame(),
            AXES[axis])))
        parent = body
    gains = ([(impedance.stiffness[3 + k], impedance.damping[3 + k]) for k in range(3)]
             + [(impedance.stiffness[a], impedance.damping[a]) for a in ROTATION_AXES])
    for joint, (kp, kd) in zip(joints, gains):
        actuator = plant.AddJointActuator(f"{joint.name()}_drive", joint)
        actuator.set_controller_gains(PdControllerGains(p=kp, d=kd))
    plant.set_gravity_enabled(instance, False)
    return Carriage(instance, tuple(joints), axes.copy(), parent)


def carriage_positions(carriage: Carriage, X_WG: RigidTransform) -> np.ndarray:
    """The carriage's joint positions [m, rad] (actuator order) that put G at X_WG."""
    rpy = RollPitchYaw(X_WG.rotation() @ R_WG_SIDE_GRASP.inverse()).vector()  # [r, p, y]
    return np.concatenate([carriage.translation_axes.T @ X_WG.translation(),
                           [rpy[2], rpy[1], rpy[0]]])


def carriage_state(carriage: Carriage, X_WG: RigidTransform, V_WG: np.ndarray) -> np.ndarray:
    """The carriage's joint positions and rates (actuator order) that put G at X_WG moving
    with spatial velocity V_WG = [w_WG; v_WG] (world)."""
    q = carriage_positions(carriage, X_WG)
    rpy = RollPitchYaw(q[5], q[4], q[3])
    rpy_dt = rpy.CalcRpyDtFromAngularVelocityInParent(V_WG[:3])  # [r, p, y] rates
    v = np.concatenate([carriage.translation_axes.T @ V_WG[3:],
                        [rpy_dt[2], rpy_dt[1], rpy_dt[0]]])
    return np.concatenate([q, v])


def carriage_displacement(carriage: Carriage, positions: np.ndarray,
                          deflection: np.ndarray) -> np.ndarray:
    """G's small displacement [dtheta; dp] [rad, m; world] for joint `deflection` at `positions`."""
    rpy = RollPitchYaw(positions[5], positions[4], positions[3])
    dtheta = rpy.CalcAngularVelocityInParentFromRpyDt(
        [deflection[5], deflection[4], deflection[3]])
    return np.concatenate([dtheta, carriage.translation_axes @ deflection[:3]])


class ArmGraspFrameKinematics:
    """G's pose, spatial velocity and Jacobian of the arm model at given joint angles: what
    the carriage needs of the arm to follow its commands and to report its torques."""

    def __init__(self):
        self._plant = make_arm_control_plant()
        self._context = self._plant.CreateDefaultContext()
        self._frame = self._plant.GetFrameByName("grasp_frame")

    def pose_and_jacobian(self, q: np.ndarray):
        """(X_WG, J_WG): G's pose and its 6 x 6 spatial-velocity Jacobian ([w; v], world)."""
        self._plant.SetPositions(self._context, q)
        world = self._plant.world_frame()
        X_WG = self._frame.CalcPoseInWorld(self._context)
        J = self._plant.CalcJacobianSpatialVelocity(self._context, JacobianWrtVariable.kV,
                                                    self._frame, np.zeros(3), world, world)
        return X_WG, J


def wrench_on_arm(F_GJ_G: np.ndarray, R_WG: RotationMatrix) -> np.ndarray:
    """The wrench the gripper puts on the arm at G, in world [Mx, My, Mz, Fx, Fy, Fz] [N m, N],
    from the weld's reaction F_GJ_G (Drake's, at the joint's child frame, in G)."""
    R = R_WG.matrix()
    return -np.concatenate([R @ F_GJ_G[:3], R @ F_GJ_G[3:]])
