"""Where a contact sits on the pads, from the whole 3 x 4 taxel pattern (not Eq. 1's sum).

Pad frame P (rig/taxel_layout.py): +y along the pad's 24 mm length toward the fingertip,
+x across its 20 mm width. At the side grasp both pads have +y = world +x (the approach
axis, normal to the palm) and +x = world -z (down); so a taxel's row says where along the
approach axis the contact sits, its column how high.

  PadContact                 one pad's total force and force-weighted centroid [m, pad frame]
  pad_contact(taxels, contact_n)
                             PadContact of one pad's 12 taxel forces
  contact_line_tilt_deg      the angle of the contact line on a pad from the pad's x axis
                             (a line contact of an upright cylinder is 0; an object leaning
                             toward or away from the palm turns the line on the pad)
  GraspContact               both pads: the approach-axis offset of the contact from the
                             pads' centres, the in-pad tilt, the vertical mismatch
  grasp_contact(taxels24, contact_n)
                             GraspContact of the two pads' 24 taxel forces [left 12, right 12]

A taxel counts toward a contact above contact_n [N], the controller's taxel_contact_n:
raised above the taxels' noise (control/noise_thresholds.py) so that noise alone never
draws a line.
"""

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
    """PadContact of one pad's 12 taxel forces [N] (taxel_layout's order), counting the
    taxels above contact_n [N]."""
    forces = _pad_forces(taxels, contact_n)
    total = float(forces.sum())
    if total <= 0.0:
        return PadContact(0.0, 0.0, 0.0)
    x, y = (forces @ _CENTERS[:, :2]) / total
    return PadContact(total, float(x), float(y))


def contact_line_tilt_deg(taxels, contact_n: float) -> float | None:
    """The angle [deg] between the contact line and the pad's x axis (across the pad),
    from the force-weighted row centroid of each column: the least-squares slope of
    centroid y against column x. Positive: the line runs toward the fingertip at +x.
    None when fewer than two columns carry contact (no line to fit)."""
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
    """Both pads' contact, in the grasp's terms.

    left, right: PadContact. approach_offset_m: where the contact sits along the approach
    axis from the pads' centres [m, world +x = toward the fingertips], the force-weighted
    mean of the touching pads' y centroids (0 without contact). tilt_deg: the larger
    |contact_line_tilt_deg| of the touching pads, with its sign (None without a line).
    height_mismatch_m: left minus right x centroid [m] (pad x = world -z), when both touch:
    a side parallel to both pads presses both at the same height; an object tilted in the
    stroke plane presses one pad high and the other low.
    """
    left: PadContact
    right: PadContact
    approach_offset_m: float
    tilt_deg: float | None
    height_mismatch_m: float


def grasp_contact(taxels24, contact_n: float) -> GraspContact:
    """GraspContact of [left 12, right 12] taxel forces [N], counting the taxels above
    contact_n [N]."""
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

