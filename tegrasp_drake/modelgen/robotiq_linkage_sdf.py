"""Writes models/robotiq_2f85/robotiq_2f85_linkage.sdf: the 2F-85 with its real finger linkage
(robotiq/linkage.py; docs/model.md, "The hand: the 2F-85 finger linkage"). Per finger a driver,
coupler, follower (with the fingertip) and spring link; a ball constraint closes each loop, the
right driver mimics the left, whose actuator carries the rotor (robotiq/drive.py). Link frames are
the base frame in the open pose; only the pad and its backing collide."""

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
# [kg] the fingertip: silicone 20 x 24 x 4 mm at 1.1 g/cm^3 (2.1 g), FR-4 board 20 x 24 x
# 1.6 mm at 1.85 g/cm^3 (1.4 g), aluminium backing about 5 g
FINGERTIP_MASS = 0.0085
# [m] the bars' square section: the links are plates about 8 mm deep (Menagerie's meshes)
LINK_BAR_SIZE = 0.008
# [N m] bounds only the implicit PD (the screw holds any load): twice the 26.9 N m of 235 N
DRIVER_EFFORT_LIMIT_NM = 60.0


def _point(p2, sign: float) -> np.ndarray:
    """A five-bar point (y, z) of the +y finger as 3D base coordinates of the finger on sign * y."""
    return np.array([0.0, sign * p2[0], p2[1]])


def _bar_inertia(p0, p1, mass: float) -> np.ndarray:
    """The inertia [kg m^2] about its centre of a bar of `mass` from p0 to p1."""
    X = segment_pose(p0, p1)
    size = (LINK_BAR_SIZE, LINK_BAR_SIZE, float(np.linalg.norm(np.subtract(p1, p0))))
    return X[:3, :3] @ box_inertia(mass, size) @ X[:3, :3].T


def _bar(name: str, p0, p1, mass: float, color: str) -> str:
    """Inertia and visual of a slender bar of `mass` from p0 to p1 [m, base frame, open pose]."""
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
    """The follower: bar, fingertip, `<finger>_pad` frame; the pad collides as its mesh or box."""
    pad_face = _point(linkage.PAD_CENTER_OPEN, sign)
    c, d = _point(linkage.C, sign), _point(linkage.D, sign)
    # The bar along C-D and the fingertip box, by the parallel-axis theorem.
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
    """A revolute joint at `point` [m, base frame] about sign * x; a `motor` carries the rotor."""
    # Drake's parser reads no <limit> as actuated: a free joint gets infinite bounds, effort 0.
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
    """The SDF text of the tactile linkage 2F-85 (pads as the box split pad_refinement times)."""
    uri = pad_mesh_url(pad_refinement) if pad_refinement else None
    parts = ['<?xml version="1.0"?>', '<sdf version="1.9">', '<model name="robotiq_2f85">',
             base_link_text(),
             # Where the prismatic hand has it, so the arm's tool frame does not depend on
             # the hand; the pad centres pass through it at a 54 mm opening.
             f'<frame name="grasp_frame" attached_to="base"><pose>0 0 {PAD_CENTER_Z} 0 0 0'
             "</pose></frame>",
             _finger("left", 1.0, uri), _finger("right", -1.0, uri), "</model></sdf>"]
    return "\n".join(parts) + "\n"
