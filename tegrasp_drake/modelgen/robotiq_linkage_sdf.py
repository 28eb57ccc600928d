"""Writes models/robotiq_2f85/robotiq_2f85_linkage.sdf: the 2F-85 with its real finger linkage.

Each finger is the 2F-85's underactuated five-bar (robotiq/linkage.py has the dimensions and
their sources): links `<f>_driver`, `<f>_coupler`, `<f>_finger` (the follower, carrying the
paper's tactile fingertip) and `<f>_spring_link`, for f in left (+y) and right (-y). The loop
is closed by a ball constraint at D between the follower and the spring link (the planar
loop makes one of its three rows redundant; SAP takes it). Both drivers are coupled as the
one motor drives them (the right driver joint mimics the left, a coupler constraint), and
one actuator drives the left driver, carrying the motor's rotor (its inertia and gear
ratio, robotiq/drive.py; Drake adds the reflected inertia to the driver's). The pin is the coupler joint's upper limit (0: on the
pin); the spring is a RevoluteSpring at the follower joint. Every link frame coincides with
the base frame in the open pose, so all-zero joint angles close the loop exactly.

Joint axes are +x for the finger on +y and -x for its mirror, so equal angles are mirror
poses: positive driver angles close the gripper, negative coupler angles curl the
fingertip toward the object.

Masses: the links' from MuJoCo Menagerie's `2f85.xml` inertials (driver 9.0 g, coupler
14.1 g, spring link 22.2 g, follower 12.5 g), each spread as a slender bar along its joints;
the paper's fingertip (its elastomer 20 x 24 x 4 mm of silicone at 1.1 g/cm^3, 2.1 g; its
circuit board 20 x 24 x 1.6 mm of FR-4 at 1.85 g/cm^3, 1.4 g; the aluminium backing behind
it, about 5 g) adds 8.5 g to the follower. Collision geometry: the pad (compliant
hydroelastic, as on the prismatic model) and a rigid backing plate behind it reaching down
the follower to D, so that an object cannot pass through the finger; the other links are
visual only (the object cannot reach them past the follower and the palm).
"""

import numpy as np

from tegrasp_drake.robotiq import drive, linkage
from tegrasp_drake.robotiq.dimensions import PAD_CENTER_Z
from tegrasp_drake.modelgen.robotiq_sdf import (FINGER_FRICTION, FINGER_LINK_THICKNESS,
                                                base_link_text, pad_frame_rotation, pad_text)
from tegrasp_drake.modelgen.sdf_text import (box_inertia, friction_text, inertial_text,
                                             number_text, pose_text, segment_pose,
                                             translation)
from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH, PAD_THICKNESS, PAD_WIDTH

# Link masses [kg] (Menagerie 2f85.xml) and the bar each is spread along (joint points).
DRIVER_MASS, COUPLER_MASS, SPRING_LINK_MASS, FOLLOWER_MASS = 0.0090, 0.0141, 0.0222, 0.0125
FINGERTIP_MASS = 0.0085  # kg, the paper's tactile fingertip (module docstring)
LINK_BAR_SIZE = 0.008  # m, side of the bars' square section (inertia and visuals): the
# 2F-85's links are stamped plates about 8 mm deep at the pins (Menagerie's meshes); with
# the links' masses set, it only spreads their inertia across the bar
# Effort limit of the driver joint [N m]: the screw and nut hold any load the fingers meet;
# this only bounds the implicit PD (twice the 26.9 N m that 235 N on both pads needs).
DRIVER_EFFORT_LIMIT_NM = 60.0


def _point(p2, sign: float) -> np.ndarray:
    """A five-bar point (y, z) of the finger on +y as 3D base coordinates of the finger
    on sign * y."""
    return np.array([0.0, sign * p2[0], p2[1]])


def _bar_inertia(p0, p1, mass: float) -> np.ndarray:
    """The inertia [kg m^2] about its centre of a bar of `mass` from p0 to p1."""
    X = segment_pose(p0, p1)
    size = (LINK_BAR_SIZE, LINK_BAR_SIZE, float(np.linalg.norm(np.subtract(p1, p0))))
    return X[:3, :3] @ box_inertia(mass, size) @ X[:3, :3].T


def _bar(name: str, p0, p1, mass: float, color: str) -> str:
    """Inertia and visual of a slender bar of `mass` from p0 to p1 (base coordinates, in
    the link frame, which is the base frame in the open pose)."""
    length = float(np.linalg.norm(np.subtract(p1, p0)))
    X = segment_pose(p0, p1)
    size = (LINK_BAR_SIZE, LINK_BAR_SIZE, length)
    com = (np.asarray(p0) + np.asarray(p1)) / 2
    return (inertial_text(mass, com, _bar_inertia(p0, p1, mass))
            + f'<visual name="{name}">{pose_text(X)}<geometry><box><size>'
            + " ".join(number_text(v) for v in size)
            + f"</size></box></geometry><material><diffuse>{color}</diffuse></material>"
            "</visual>")


def _follower(finger: str, sign: float, pad_mesh_uri: str | None) -> str:
    """The follower: its bar, the tactile fingertip (pad and rigid backing) and the pad
    frame `<finger>_pad` at the centre of the pad's contact face; the pad's collision
    geometry the mesh at pad_mesh_uri if given, else its box."""
    pad_face = _point(linkage.PAD_CENTER_OPEN, sign)
    c, d = _point(linkage.C, sign), _point(linkage.D, sign)
    # The bar along C-D and the fingertip, a box the size of the pad and its backing, put
    # together by the parallel-axis theorem.
    parts = ((FOLLOWER_MASS, (c + d) / 2, _bar_inertia(c, d, FOLLOWER_MASS)),
             (FINGERTIP_MASS, pad_face + [0, sign * PAD_THICKNESS, 0],
              box_inertia(FINGERTIP_MASS, (PAD_WIDTH, PAD_THICKNESS + FINGER_LINK_THICKNESS,
                                           PAD_LENGTH))))
    mass = sum(m for m, _, _ in parts)
    com = sum(m * np.asarray(p) for m, p, _ in parts) / mass
    inertia = sum(I + m * (np.dot(p - com, p - com) * np.eye(3) - np.outer(p - com, p - com))
                  for m, p, I in parts)
    frame = f"{finger}_pad_face"
    top = linkage.PAD_CENTER_OPEN[1] + PAD_LENGTH / 2
    bottom = linkage.D[1] - LINK_BAR_SIZE / 2
    backing_center = translation((0, sign * (PAD_THICKNESS + FINGER_LINK_THICKNESS / 2),
                                  (top + bottom) / 2 - linkage.PAD_CENTER_OPEN[1]))
    backing_box = (f"<geometry><box><size>{PAD_WIDTH} {FINGER_LINK_THICKNESS} "
                   f"{number_text(top - bottom)}</size></box></geometry>")
    link = (f'<link name="{finger}_finger">'
            + inertial_text(mass, com, inertia)
            + pad_text(sign, relative_to=frame, mesh_uri=pad_mesh_uri)
            + f'<collision name="backing">{pose_text(backing_center, frame)}{backing_box}'
            "<drake:proximity_properties><drake:rigid_hydroelastic/>"
            f"{friction_text(FINGER_FRICTION)}</drake:proximity_properties></collision>"
            f'<visual name="backing">{pose_text(backing_center, frame)}{backing_box}'
            "<material><diffuse>0.6 0.6 0.62 1</diffuse></material></visual>"
            f'<visual name="follower">{pose_text(segment_pose(c, d))}<geometry><box><size>'
            f"{LINK_BAR_SIZE} {LINK_BAR_SIZE} {number_text(np.linalg.norm(d - c))}</size>"
            "</box></geometry><material><diffuse>0.15 0.15 0.15 1</diffuse></material>"
            "</visual></link>")
    frames = (f'<frame name="{frame}" attached_to="{finger}_finger">'
              f"{pose_text(translation(pad_face), f'{finger}_finger')}</frame>"
              f'<frame name="{finger}_pad" attached_to="{finger}_finger">'
              f"{pose_text(pad_frame_rotation(sign), frame)}</frame>")
    return link + frames


def _revolute(name: str, parent: str, child: str, point, sign: float, limits=None,
              effort: float = 0.0, spring=None, mimic: str | None = None,
              motor: bool = False) -> str:
    """A revolute joint at `point` (base coordinates) about sign * x; with `motor`, its
    actuator carries the 2F-85's rotor behind its gear ratio (robotiq/drive.py)."""
    # No <limit> means an unlimited, actuated joint to Drake's parser: a free joint gets
    # infinite bounds and no actuator (effort 0).
    lower, upper = limits if limits is not None else (-np.inf, np.inf)
    limit = (f"<limit><lower>{number_text(lower)}</lower><upper>{number_text(upper)}</upper>"
             f"<effort>{number_text(effort)}</effort></limit>")
    dynamics = ""
    if spring is not None:
        dynamics = (f"<dynamics><spring_reference>{number_text(spring[0])}</spring_reference>"
                    f"<spring_stiffness>{number_text(spring[1])}</spring_stiffness>"
                    "</dynamics>")
    mimic_text = (f'<drake:mimic joint="{mimic}" multiplier="1" offset="0"/>'
                  if mimic else "")
    if motor:
        mimic_text += (f"<drake:rotor_inertia>{number_text(drive.ROTOR_INERTIA_KG_M2)}"
                       f"</drake:rotor_inertia><drake:gear_ratio>"
                       f"{number_text(drive.GEAR_RATIO)}</drake:gear_ratio>")
    return (f'<joint name="{name}" type="revolute"><parent>{parent}</parent>'
            f"<child>{child}</child>{pose_text(translation(point), child)}"
            f'<axis><xyz expressed_in="base">{number_text(sign)} 0 0</xyz>{limit}{dynamics}'
            f"</axis>{mimic_text}</joint>")


def _finger(finger: str, sign: float, pad_mesh_uri: str | None) -> str:
    a, b, c = (_point(p, sign) for p in (linkage.A, linkage.B, linkage.C))
    d, e = _point(linkage.D, sign), _point(linkage.E, sign)
    actuated = finger == "left"
    return "".join([
        f'<link name="{finger}_driver">{_bar("driver", a, b, DRIVER_MASS, "0.45 0.45 0.45 1")}'
        "</link>",
        f'<link name="{finger}_coupler">'
        f'{_bar("coupler", b, c, COUPLER_MASS, "0.15 0.15 0.15 1")}</link>',
        f'<link name="{finger}_spring_link">'
        f'{_bar("spring_link", e, d, SPRING_LINK_MASS, "0.15 0.15 0.15 1")}</link>',
        _follower(finger, sign, pad_mesh_uri),
        _revolute(f"{finger}_driver_joint", "base", f"{finger}_driver", a, sign,
                  limits=(0.0, linkage.DRIVER_RANGE_RAD),
                  effort=DRIVER_EFFORT_LIMIT_NM if actuated else 0.0,
                  mimic=None if actuated else "left_driver_joint", motor=actuated),
        _revolute(f"{finger}_coupler_joint", f"{finger}_driver", f"{finger}_coupler", b, sign,
                  limits=(-linkage.COUPLER_RANGE_RAD, 0.0)),
        _revolute(f"{finger}_follower_joint", f"{finger}_coupler", f"{finger}_finger", c,
                  sign, limits=(-linkage.FOLLOWER_RANGE_RAD, linkage.FOLLOWER_RANGE_RAD),
                  spring=(linkage.SPRING_REST_ANGLE_RAD,
                          linkage.SPRING_STIFFNESS_NM_PER_RAD)),
        _revolute(f"{finger}_spring_link_joint", "base", f"{finger}_spring_link", e, sign),
        "<drake:ball_constraint>"
        f"<drake:ball_constraint_body_A>{finger}_finger</drake:ball_constraint_body_A>"
        f"<drake:ball_constraint_body_B>{finger}_spring_link</drake:ball_constraint_body_B>"
        f"<drake:ball_constraint_p_AP>{' '.join(number_text(v) for v in d)}"
        "</drake:ball_constraint_p_AP>"
        f"<drake:ball_constraint_p_BQ>{' '.join(number_text(v) for v in d)}"
        "</drake:ball_constraint_p_BQ></drake:ball_constraint>"])


def pad_mesh_url(refinement: int) -> str:
    """The package URL of the pad's mesh split `refinement` times (modelgen/pad_mesh.py)."""
    return f"package://tegrasp/robotiq_2f85/pad_refined_{refinement}.vtk"


def robotiq_linkage_sdf(pad_refinement: int = 0) -> str:
    """The SDF text of the tactile 2F-85 with its finger linkage; with pad_refinement > 0
    the pads' collision geometry is their box's mesh split that many times (pad_mesh_url),
    else the box itself."""
    uri = pad_mesh_url(pad_refinement) if pad_refinement else None
    parts = ['<?xml version="1.0"?>', '<sdf version="1.9">', '<model name="robotiq_2f85">',
             base_link_text(),
             # The grasp frame where the prismatic hand has it, so that the arm's tool frame
             # does not depend on the hand; the linkage's pad centres pass through it at a
             # 54 mm opening (they move out along +z as they close: pad_travel).
             f'<frame name="grasp_frame" attached_to="base"><pose>0 0 {PAD_CENTER_Z} 0 0 0'
             "</pose></frame>",
             _finger("left", 1.0, uri), _finger("right", -1.0, uri), "</model></sdf>"]
    return "\n".join(parts) + "\n"
