"""Where a contact sits on the pads, from the whole 3 x 4 taxel pattern (not Eq. 1's sum):
each pad's force-weighted centroid, the contact line's tilt, and both pads' approach-axis
offset and height mismatch. Pad frame P (rig/taxel_layout.py): +y toward the fingertip
(world +x at the side grasp), +x across the pad (world -z). A taxel counts above contact_n
[N], the controller's taxel_contact_n, raised above the taxels' noise."""

import dataclasses
import math

import numpy as np

from tegrasp_drake.rig.taxel_layout import COLUMNS, ROWS, taxel_centers

TAXELS_PER_PAD = ROWS * COLUMNS
_CENTERS = taxel_centers()


@dataclasses.dataclass(frozen=True)
class PadContact:
    """One pad's contact: total force [N] of its taxels above the contact force, and their
    force-weighted centroid [m, pad frame] (0, 0 with no contact)."""
    force_n: float
    x_m: float  # across the pad (world -z at the side grasp)
    y_m: float  # along the pad toward the fingertip (world +x, the approach axis)

    @property
    def touching(self) -> bool:
        return self.force_n > 0.0


def _pad_forces(taxels, contact_n: float) -> np.ndarray:
    forces = np.asarray(taxels, dtype=float).reshape(TAXELS_PER_PAD)
    return np.where(forces > contact_n, forces, 0.0)


def pad_contact(taxels, contact_n: float) -> PadContact:
    """PadContact of one pad's 12 taxel forces [N], counting those above contact_n [N]."""
    forces = _pad_forces(taxels, contact_n)
    total = float(forces.sum())
    if total <= 0.0:
        return PadContact(0.0, 0.0, 0.0)
    x, y = (forces @ _CENTERS[:, :2]) / total
    return PadContact(total, float(x), float(y))


def contact_line_tilt_deg(taxels, contact_n: float) -> float | None:
    """The angle [deg] of the contact line from the pad's x axis (least-squares slope of each
    column's row centroid; positive toward the fingertip); None with under two columns."""
    forces = _pad_forces(taxels, contact_n).reshape(ROWS, COLUMNS)
    column_force = forces.sum(axis=0)
    columns = np.flatnonzero(column_force > 0.0)
    if len(columns) < 2:
        return None
    row_y = _CENTERS[::COLUMNS, 1]  # the y of each row
    y_of_column = (row_y @ forces[:, columns]) / column_force[columns]
    x_of_column = _CENTERS[columns, 0]
    weights = column_force[columns]
    x_mean = np.average(x_of_column, weights=weights)
    y_mean = np.average(y_of_column, weights=weights)
    dx = x_of_column - x_mean
    slope = float(np.sum(weights * dx * (y_of_column - y_mean)) / np.sum(weights * dx * dx))
    return math.degrees(math.atan(slope))


@dataclasses.dataclass(frozen=True)
class GraspContact:
    """Both pads' contact: approach_offset_m, the force-weighted y centroid from the pads'
    centres [m, world +x]; tilt_deg, the larger pad tilt (None: no line); height_mismatch_m,
    left minus right x centroid [m] when both touch (an object tilted in the stroke plane)."""
    left: PadContact
    right: PadContact
    approach_offset_m: float
    tilt_deg: float | None
    height_mismatch_m: float


def grasp_contact(taxels24, contact_n: float) -> GraspContact:
    """GraspContact of [left 12, right 12] taxel forces [N], those above contact_n counted."""
    taxels = np.asarray(taxels24, dtype=float).reshape(2, TAXELS_PER_PAD)
    pads = [pad_contact(taxels[k], contact_n) for k in range(2)]
    total = pads[0].force_n + pads[1].force_n
    offset = ((pads[0].force_n * pads[0].y_m + pads[1].force_n * pads[1].y_m) / total
              if total > 0.0 else 0.0)
    tilts = [contact_line_tilt_deg(taxels[k], contact_n) for k in range(2)
             if pads[k].touching]
    tilts = [t for t in tilts if t is not None]
    tilt = max(tilts, key=abs) if tilts else None
    mismatch = pads[0].x_m - pads[1].x_m if pads[0].touching and pads[1].touching else 0.0
    return GraspContact(pads[0], pads[1], float(offset), tilt, float(mismatch))

