"""The centring Re-Reach of the taxel-aware table: along the stroke the paper's
shift; along the approach axis the contact's offset (contact_geometry.approach_shift), or a
back-off of approach_retreat_m in the approach."""

from tegrasp_drake.control.corrective_actions import re_reach_shift
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift, approach_shift


def centring_shift(situation) -> Shift:
    """The centring Re-Reach's shift [m, world] from the situation's ContactEstimate."""
    e, config = situation.estimate, situation.config
    dy = re_reach_shift(e.sa_n, e.opening_m, e.object_width_m, config.contact_force_n)
    if e.approaching:
        return Shift(-config.taxel_aware.approach_retreat_m, dy)
    return Shift(approach_shift(e.shape, config.taxel_aware, e.pad_travel_to_grasp_m), dy)
