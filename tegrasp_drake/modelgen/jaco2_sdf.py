"""Writes models/jaco2/j2n6s300.sdf from jaco2_dh.py: link frames are DH frames, links visual-only
capsule chains (only the gripper touches the world), masses Kinova's j2n6s300 description's."""

import numpy as np

from tegrasp_drake.modelgen import jaco2_dh
from tegrasp_drake.modelgen.sdf_text import (inertial_text, pose_text, segment_pose,
                                             tube_inertia)

LINK_RADIUS = 0.04  # m; JACO2 links are about 80 mm across.
BASE_HEIGHT = 0.12  # m, visual base ring
BASE_MASS = 0.468  # kg


def _capsules(points, radius, color) -> str:
    text = []
    for k, (p0, p1) in enumerate(zip(points[:-1], points[1:])):
        length = np.linalg.norm(p1 - p0)
        if length < 1e-6:
            continue
        text.append(f'<visual name="segment_{k}">{pose_text(segment_pose(p0, p1))}'
                    f"<geometry><capsule><radius>{radius}</radius><length>{length:.9g}"
                    f"</length></capsule></geometry><material><diffuse>{color}</diffuse>"
                    f"</material></visual>")
    return "".join(text)


def jaco2_sdf() -> str:
    """The SDF text of the JACO2 arm, base link `base` welded by the user."""
    parts = ['<?xml version="1.0"?>', '<sdf version="1.9">', '<model name="jaco2">',
             '<link name="base">',
             inertial_text(BASE_MASS, (0, 0, BASE_HEIGHT / 2), np.eye(3) * 1e-3),
             f'<visual name="ring"><pose>0 0 {BASE_HEIGHT / 2} 0 0 0</pose><geometry>'
             f"<cylinder><radius>{LINK_RADIUS + 0.01}</radius><length>{BASE_HEIGHT}</length>"
             "</cylinder></geometry><material><diffuse>0.15 0.15 0.15 1</diffuse></material>"
             "</visual></link>"]
    parent = "base"
    for i, joint in enumerate(jaco2_dh.JOINTS, start=1):
        link = f"link_{i}"
        X_parent_link = jaco2_dh.dh_transform(joint.alpha, joint.a, joint.d, joint.offset)
        X_link_parent = np.linalg.inv(X_parent_link)
        corner = np.array([0.0, 0.0, joint.d, 1.0])
        points = np.array([(X_link_parent @ p)[:3] for p in
                           (np.array([0.0, 0.0, 0.0, 1.0]), corner, np.array([0, 0, 0, 1.0]))])
        points[2] = 0.0  # the link's own origin
        com, inertia = tube_inertia(joint.mass, points, LINK_RADIUS)
        color = "0.2 0.2 0.22 1" if i % 2 else "0.75 0.75 0.78 1"
        parts.append(f'<link name="{link}">{pose_text(X_parent_link, parent)}'
                     f"{inertial_text(joint.mass, com, inertia)}"
                     f"{_capsules(points, LINK_RADIUS, color)}</link>")
        limit = (f"<lower>{joint.lower:.9g}</lower><upper>{joint.upper:.9g}</upper>"
                 if joint.lower is not None else "")
        joint_type = "revolute" if joint.lower is not None else "continuous"
        parts.append(
            f'<joint name="joint_{i}" type="{joint_type}"><parent>{parent}</parent>'
            f"<child>{link}</child>"
            f'<pose relative_to="{parent}">0 0 0 0 0 0</pose>'
            f'<axis><xyz expressed_in="{parent}">0 0 {joint.sign:g}</xyz>'
            f"<limit>{limit}<effort>{joint.max_torque:g}</effort>"
            f"<velocity>{joint.max_speed:.9g}</velocity></limit>"
            f"<dynamics><damping>0.0</damping></dynamics></axis></joint>")
        parent = link
    parts.append('<frame name="flange" attached_to="link_6"/>')
    parts.append("</model></sdf>")
    return "\n".join(parts) + "\n"
