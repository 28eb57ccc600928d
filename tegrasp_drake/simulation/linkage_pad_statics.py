"""The linkage fingers' pad normal forces from the joints' generalized contact forces
(`vibration.pad_force_source: joint_forces`). A contact wrench on the follower of the chain
base -A- driver -B- coupler -C- follower, in-plane force F and moment M_C about C, gives

    tau_C = M_C,   tau_B = M_C + (C - B) x F,   tau_A = M_C + (C - A) x F

so the last two give F, and the pad force is F . n, n the pad's outward normal."""

import dataclasses
import math
import operator

from pydrake.symbolic import cos as symbolic_cos
from pydrake.symbolic import sin as symbolic_sin

from tegrasp_drake.rig.channels import FINGER_NAMES

# VibrationSensorConfig.pad_force_source: PadNormalForces' walk over the contact results,
# or this module's statics on the joints' generalized contact forces.
PAD_FORCE_SOURCES = ("contact_results", "joint_forces")
JOINT_FORCES = PAD_FORCE_SOURCES[1]
# The chain's joints from the base, by their SDF names `<finger>_<link>_joint`.
CHAIN_LINKS = ("driver", "coupler", "follower")
# Each finger's side of the stroke (modelgen/robotiq_linkage_sdf.py: left on +y, its joint
# axes +x; right on -y, its axes -x).
FINGER_SIGNS = (1.0, -1.0)
# The finger's links other than the follower (the spring link hangs off the base).
OTHER_LINKS = ("driver", "coupler", "spring_link")


def _instance_index(plant, instance, joint, *, velocity: bool) -> int:
    """Where `joint`'s (single) velocity or position sits in the model instance's vector."""
    start = joint.velocity_start() if velocity else joint.position_start()
    size = plant.num_velocities() if velocity else plant.num_positions()
    marker = [0.0] * size
    marker[start] = 1.0
    select = plant.GetVelocitiesFromArray if velocity else plant.GetPositionsFromArray
    return int(select(instance, marker).argmax())


@dataclasses.dataclass(frozen=True)
class FingerChain:
    """One finger's planar chain in the open pose [m, base frame (+-y, z)]: B - A, C - B, normal."""
    ab: tuple[float, float]
    bc: tuple[float, float]
    normal: tuple[float, float]


def finger_pad_force(chain: FingerChain, tau, q, *, cos=math.cos, sin=math.sin) -> float:
    """The pad's normal contact force [N], positive pushing the pad open, from one finger's
    (driver, coupler, follower) generalized contact forces tau [N m] and angles q [rad];
    cos and sin: pydrake.symbolic's to write it on expressions."""
    theta, beta, gamma = q
    tau_a, tau_b, tau_c = tau
    (ab_y, ab_z), (bc_y, bc_z), (n_y, n_z) = chain.ab, chain.bc, chain.normal
    c1, s1 = cos(theta), sin(theta)
    c2, s2 = cos(theta + beta), sin(theta + beta)
    # C - B and C - A, turned with the links.
    cb_y, cb_z = c2 * bc_y - s2 * bc_z, s2 * bc_y + c2 * bc_z
    ca_y, ca_z = c1 * ab_y - s1 * ab_z + cb_y, s1 * ab_y + c1 * ab_z + cb_z
    # (C - J) x F = r_y F_z - r_z F_y = tau_J - tau_C for J = B, A; Cramer's rule.
    rhs_b, rhs_a = tau_b - tau_c, tau_a - tau_c
    determinant = cb_y * ca_z - cb_z * ca_y
    force_y = (ca_y * rhs_b - cb_y * rhs_a) / determinant
    force_z = (ca_z * rhs_b - cb_z * rhs_a) / determinant
    c3, s3 = cos(theta + beta + gamma), sin(theta + beta + gamma)
    return force_y * (c3 * n_y - s3 * n_z) + force_z * (s3 * n_y + c3 * n_z)


def finger_chain(plant, gripper, finger: str, sign: float) -> FingerChain:
    """The FingerChain of `finger` (on sign * y) as the plant's model has it."""
    def point(link):  # the joint's point, in the open pose's (+-y, z)
        joint = plant.GetJointByName(f"{finger}_{link}_joint", gripper)
        p = joint.frame_on_child().GetFixedPoseInBodyFrame().translation()
        return sign * float(p[1]), float(p[2])

    (a_y, a_z), (b_y, b_z), (c_y, c_z) = (point(link) for link in CHAIN_LINKS)
    pad = plant.GetFrameByName(f"{finger}_pad", gripper)
    z_BP = pad.GetFixedPoseInBodyFrame().rotation().matrix()[:, 2]
    return FingerChain(ab=(b_y - a_y, b_z - a_z), bc=(c_y - b_y, c_z - b_z),
                       normal=(-sign * float(z_BP[1]), -float(z_BP[2])))


class LinkagePadStatics:
    """Both linkage pads' normal forces from the gripper's generalized contact forces and state."""

    def __init__(self, plant, gripper):
        """plant: finalized, with the linkage hand as model instance `gripper`. Raises
        ValueError when a finger link other than the follower has collision geometry."""
        self.velocities = plant.num_velocities(gripper)  # generalized contact forces' size
        self.states = plant.num_multibody_states(gripper)  # the instance's state's size
        touching = [f"{finger}_{link}" for finger in FINGER_NAMES for link in OTHER_LINKS
                    if plant.GetCollisionGeometriesForBody(
                        plant.GetBodyByName(f"{finger}_{link}", gripper))]
        if touching:
            raise ValueError(f"the linkage pad statics need collision geometry on the "
                             f"followers only; {', '.join(touching)} can touch")
        joints = [[plant.GetJointByName(f"{finger}_{link}_joint", gripper)
                   for link in CHAIN_LINKS] for finger in FINGER_NAMES]
        chains = [finger_chain(plant, gripper, finger, sign)
                  for finger, sign in zip(FINGER_NAMES, FINGER_SIGNS)]
        # Per finger: its chain and getters of its joints' entries in the instance's
        # generalized forces and state.
        self._fingers = tuple(
            (chain, operator.itemgetter(*(_instance_index(plant, gripper, j, velocity=True)
                                          for j in joint_chain)),
             operator.itemgetter(*(_instance_index(plant, gripper, j, velocity=False)
                                   for j in joint_chain)))
            for chain, joint_chain in zip(chains, joints))

    def normal_forces(self, tau: list, state: list) -> tuple[float, float]:
        """(left, right) pad normal forces [N], positive pushing each pad open, from the gripper's
        generalized contact forces `tau` and state `state` (positions first)."""
        (left, left_tau, left_q), (right, right_tau, right_q) = self._fingers
        return (finger_pad_force(left, left_tau(tau), left_q(state)),
                finger_pad_force(right, right_tau(tau), right_q(state)))

    def normal_force_expressions(self, tau: list, state: list) -> tuple:
        """normal_forces on pydrake.symbolic variables (the entries of `tau` and `state`)."""
        (left, left_tau, left_q), (right, right_tau, right_q) = self._fingers
        functions = {"cos": symbolic_cos, "sin": symbolic_sin}
        return (finger_pad_force(left, left_tau(tau), left_q(state), **functions),
                finger_pad_force(right, right_tau(tau), right_q(state), **functions))
