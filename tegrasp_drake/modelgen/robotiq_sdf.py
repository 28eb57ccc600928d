"""Writes models/robotiq_2f85/robotiq_2f85_tactile.sdf: a 2F-85-like gripper with prismatic fingers
(`gripper.model: prismatic`), the right mimicking the left so an off-centre object is pushed to the
centre. Frames: `base` at the mounting face (+z the approach, y the stroke), `grasp_frame` (G) at
the pads' centre, `<f>_pad` at each pad face (+z inward, +y toward the fingertip), in which
rig/taxel_layout.py is given. Pads are compliant hydroelastic boxes on rigid aluminium fingers."""

import numpy as np

from tegrasp_drake.rig import materials
from tegrasp_drake.robotiq.dimensions import HALF_STROKE, PAD_CENTER_Z, PALM_Z
from tegrasp_drake.modelgen.sdf_text import (box_inertia, friction_text, inertial_text, pose_text,
                                             translation)
from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH, PAD_THICKNESS, PAD_WIDTH

BASE_RADIUS = 0.0375  # m, the datasheet's body about 75 mm across
# [m] beyond the stroke, so full opening never strikes the limit (a false RA event)
JOINT_LIMIT_MARGIN = 0.001
BASE_MASS, FINGER_MASS = 0.80, 0.05  # kg, the datasheet's 0.9 kg in all
# Pad E and Hunt-Crossley dissipation: grasp, lift and place the objects stably with SAP at
# a 1 ms step (measured on this scene).
PAD_MODULUS = 2.0e6  # Pa
PAD_DISSIPATION = 5.0  # s/m
# [s] Read only by `plant_config.discrete_contact_approximation: sap`: SAP damps contact with a
# linear Kelvin-Voigt term d = tau k, tau the sum of the pair's relaxation times (Drake's
# default 0.1 s for a geometry that sets none, as the objects); `lagged` (the default),
# `similar` and `tamsi` use PAD_DISSIPATION instead (Drake, DiscreteContactApproximation).
# A linear damper has one loss factor a frequency, tan(delta) = 2 pi f tau: 0.02 s gives 0.13
# at 1 Hz, a silicone or urethane elastomer's 0.05-0.3, on the grasp's slow load changes
# (grip, lift). At the touch it is no restitution: on k = E A / (t / 2) = 4.8e5 N/m and the
# 0.06-0.2 kg objects (w = 1.5-2.8e3 rad/s) zeta = tau w / 2 = 15-28 overdamps it (e = 0);
# an elastomer's e of 0.5-0.8 (zeta 0.07-0.22) needs tau 0.05-0.3 ms, as PAD_DISSIPATION's
# Hunt-Crossley term, whose tau at the touch is d x: 0.26 ms at 25 N (e 0.92 at 25 mm/s).
PAD_RELAXATION_TIME_S = 0.02
PAD_FRICTION = materials.PAD_COVER
FINGER_FRICTION = materials.ALUMINIUM  # the finger behind the pad and the palm
FINGER_LINK_THICKNESS = 0.010  # m, rigid finger behind the pad


def pad_text(sign: float, relative_to: str | None = None, mesh_uri: str | None = None) -> str:
    """The pad's collision (or the tetrahedral mesh at `mesh_uri`) and visual boxes, its
    contact face at the frame's origin (sign +1: the finger on +y)."""
    center = pose_text(translation((0, sign * PAD_THICKNESS / 2, 0)), relative_to)
    box = f"<box><size>{PAD_WIDTH} {PAD_THICKNESS} {PAD_LENGTH}</size></box>"
    shape = f"<mesh><uri>{mesh_uri}</uri></mesh>" if mesh_uri else box
    # (Drake meshes a compliant box from its medial axis whatever the resolution hint.)
    return (f'<collision name="pad">{center}'
            f"<geometry>{shape}"
            "</geometry><drake:proximity_properties><drake:compliant_hydroelastic/>"
            f"<drake:hydroelastic_modulus>{PAD_MODULUS:g}</drake:hydroelastic_modulus>"
            "<drake:mesh_resolution_hint>0.004</drake:mesh_resolution_hint>"
            f"<drake:hunt_crossley_dissipation>{PAD_DISSIPATION:g}"
            "</drake:hunt_crossley_dissipation>"
            f"<drake:relaxation_time>{PAD_RELAXATION_TIME_S:g}</drake:relaxation_time>"
            f"{friction_text(PAD_FRICTION)}</drake:proximity_properties></collision>"
            f'<visual name="pad">{center}<geometry>{box}</geometry>'
            "<material><diffuse>0.1 0.1 0.1 1</diffuse></material></visual>")


def _finger_link(sign: float) -> str:
    """The rigid hydroelastic finger behind the pad, reaching back to the palm."""
    length = PAD_CENTER_Z + PAD_LENGTH / 2 - PALM_Z
    center = pose_text(translation((0, sign * (PAD_THICKNESS + FINGER_LINK_THICKNESS / 2),
                                    PAD_LENGTH / 2 - length / 2)))
    box = (f"<geometry><box><size>{PAD_WIDTH} {FINGER_LINK_THICKNESS} {length:.6g}</size></box>"
           "</geometry>")
    return (f'<collision name="finger">{center}{box}<drake:proximity_properties>'
            f"<drake:rigid_hydroelastic/>{friction_text(FINGER_FRICTION)}"
            "</drake:proximity_properties></collision>"
            f'<visual name="finger">{center}{box}'
            "<material><diffuse>0.6 0.6 0.62 1</diffuse></material></visual>")


def _finger(name: str, sign: float) -> str:
    # Finger frame: origin at the pad's contact surface centre when q = 0.
    size = (PAD_WIDTH, PAD_THICKNESS + FINGER_LINK_THICKNESS, PAD_LENGTH)
    X_pad = pad_frame_rotation(sign)
    return (f'<link name="{name}_finger">'
            f"{pose_text(translation((0, 0, PAD_CENTER_Z)), 'base')}"
            f"{inertial_text(FINGER_MASS, (0, sign * 0.006, 0), box_inertia(FINGER_MASS, size))}"
            f"{pad_text(sign)}{_finger_link(sign)}</link>"
            f'<frame name="{name}_pad" attached_to="{name}_finger">'
            f"{pose_text(X_pad, f'{name}_finger')}</frame>")


def pad_frame_rotation(sign: float) -> np.ndarray:
    """The pad frame in its finger's frame (4x4, no translation): y toward the fingertip (z_G)
    on both pads, z the inward normal (-sign * y_G), x = y x z = sign * x_G."""
    X_pad = np.eye(4)
    X_pad[:3, :3] = np.array([[sign, 0, 0], [0, 0, -sign], [0, 1, 0]], dtype=float)
    return X_pad


def base_link_text() -> str:
    """The gripper body (link `base`): its inertia, visual and the palm's collision box."""
    base_size = (2 * BASE_RADIUS, 2 * BASE_RADIUS, PALM_Z)
    palm = (f'<collision name="palm"><pose>0 0 {PALM_Z - 0.005} 0 0 0</pose><geometry><box>'
            f"<size>0.03 0.07 0.01</size></box></geometry><drake:proximity_properties>"
            f"{friction_text(FINGER_FRICTION)}</drake:proximity_properties></collision>")
    return "\n".join([
        '<link name="base">',
        inertial_text(BASE_MASS, (0, 0, PALM_Z / 2), box_inertia(BASE_MASS, base_size)),
        f'<visual name="body"><pose>0 0 {PALM_Z / 2} 0 0 0</pose><geometry><cylinder>'
        f"<radius>{BASE_RADIUS}</radius><length>{PALM_Z}</length></cylinder></geometry>"
        "<material><diffuse>0.12 0.12 0.12 1</diffuse></material></visual>",
        palm, "</link>"])


def robotiq_sdf() -> str:
    """The SDF text of the tactile 2F-85-like gripper with prismatic fingers."""
    parts = [
        '<?xml version="1.0"?>', '<sdf version="1.9">', '<model name="robotiq_2f85">',
        base_link_text(),
        f'<frame name="grasp_frame" attached_to="base"><pose>0 0 {PAD_CENTER_Z} 0 0 0</pose>'
        "</frame>",
        _finger("left", +1.0), _finger("right", -1.0),
        # Left finger: +q moves its pad toward +y (opening).
        '<joint name="left_finger_joint" type="prismatic"><parent>base</parent>'
        '<child>left_finger</child><pose relative_to="left_finger">0 0 0 0 0 0</pose>'
        '<axis><xyz expressed_in="base">0 1 0</xyz><limit><lower>0</lower>'
        f"<upper>{HALF_STROKE + JOINT_LIMIT_MARGIN}</upper><effort>{2 * 235.0:g}</effort>"
        "<velocity>0.15</velocity>"
        "</limit><dynamics><damping>0.0</damping></dynamics></axis></joint>",
        '<joint name="right_finger_joint" type="prismatic"><parent>base</parent>'
        '<child>right_finger</child><pose relative_to="right_finger">0 0 0 0 0 0</pose>'
        '<axis><xyz expressed_in="base">0 -1 0</xyz><limit><lower>0</lower>'
        f"<upper>{HALF_STROKE + JOINT_LIMIT_MARGIN}</upper><effort>0</effort>"
        "<velocity>0.15</velocity></limit>"
        "</axis>"
        '<drake:mimic joint="left_finger_joint" multiplier="1" offset="0"/></joint>',
        "</model></sdf>"]
    return "\n".join(parts) + "\n"
