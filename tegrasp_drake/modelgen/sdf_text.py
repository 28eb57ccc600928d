"""Small helpers that format SDFormat elements; the model generators use them."""

import numpy as np
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix


# Below this magnitude a generated number is floating-point round-off (e.g. 1e-19 m from a
# rotation's cosine): it is written as 0 so that the text does not depend on the CPU's libm.
ROUND_OFF = 1e-12


def number_text(value: float) -> str:
    """A number for SDF text: 9 significant digits, round-off written as 0."""
    value = float(value)
    return "0" if abs(value) < ROUND_OFF else f"{value:.9g}"


def pose_text(X: np.ndarray, relative_to: str | None = None) -> str:
    """An SDF <pose> for a 4x4 transform, with an optional relative_to frame."""
    rpy = RollPitchYaw(RotationMatrix(X[:3, :3])).vector()
    values = " ".join(number_text(v) for v in (*X[:3, 3], *rpy))
    attribute = f' relative_to="{relative_to}"' if relative_to else ""
    return f"<pose{attribute}>{values}</pose>"


def translation(p) -> np.ndarray:
    X = np.eye(4)
    X[:3, 3] = p
    return X


def segment_pose(p0, p1) -> np.ndarray:
    """The pose of a frame at the midpoint of p0-p1 whose z axis points from p0 to p1."""
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    direction = (p1 - p0) / np.linalg.norm(p1 - p0)
    X = RigidTransform(RotationMatrix.MakeFromOneVector(direction, 2), (p0 + p1) / 2)
    return X.GetAsMatrix4()


def inertial_text(mass: float, com, inertia: np.ndarray) -> str:
    """An SDF <inertial> block (inertia about the centre of mass, in the link frame)."""
    i = inertia
    n = number_text
    return (f"<inertial><pose>{n(com[0])} {n(com[1])} {n(com[2])} 0 0 0</pose>"
            f"<mass>{n(mass)}</mass><inertia>"
            f"<ixx>{n(i[0, 0])}</ixx><ixy>{n(i[0, 1])}</ixy><ixz>{n(i[0, 2])}</ixz>"
            f"<iyy>{n(i[1, 1])}</iyy><iyz>{n(i[1, 2])}</iyz><izz>{n(i[2, 2])}</izz>"
            f"</inertia></inertial>")


def box_inertia(mass: float, size) -> np.ndarray:
    x, y, z = size
    return mass / 12.0 * np.diag([y * y + z * z, x * x + z * z, x * x + y * y])


def tube_inertia(mass: float, points: np.ndarray, radius: float):
    """COM and inertia about it of mass spread evenly over solid rods of `radius` joining `points`
    (the arm links' capsule chains), in the points' frame."""
    samples, weights = [], []
    for p0, p1 in zip(points[:-1], points[1:]):
        length = np.linalg.norm(p1 - p0)
        if length < 1e-9:
            continue
        s = (np.arange(20) + 0.5) / 20
        samples.append(p0 + np.outer(s, p1 - p0))
        weights.append(np.full(20, length / 20))
    samples, weights = np.vstack(samples), np.concatenate(weights)
    weights = weights * mass / weights.sum()
    com = weights @ samples / mass  # the mass-weighted mean of the samples
    r = samples - com
    inertia = np.einsum("k,kij->ij", weights,
                        np.einsum("ki,ki->k", r, r)[:, None, None] * np.eye(3)
                        - np.einsum("ki,kj->kij", r, r))
    inertia += np.eye(3) * 0.5 * mass * radius * radius
    return com, inertia


def friction_text(mu: float) -> str:
    """Drake's friction elements for a geometry's proximity properties: one coefficient as
    both mu_dynamic and mu_static (the discrete solvers read only mu_dynamic; materials.py)."""
    return (f"<drake:mu_dynamic>{mu:g}</drake:mu_dynamic>"
            f"<drake:mu_static>{mu:g}</drake:mu_static>")
