"""The taxel-aware rule table: the paper's (transition_logic.PAPER_TABLE) with one
module's rules and guards per correction added, its Re-Reaches centred on the contact
within taxel_aware.max_re_reaches."""

from tegrasp_drake.control.rule_engine import ReReachMove, RuleTable
from tegrasp_drake.control.taxel_aware.approach_contact import APPROACH_CONTACT
from tegrasp_drake.control.taxel_aware.beyond_pads import BEYOND_PADS
from tegrasp_drake.control.taxel_aware.bracketing import BRACKET_RECENTRE
from tegrasp_drake.control.taxel_aware.caged import (CAGED, LOAD_TIMEOUT_CAGED,
                                                     REACH_TIMEOUT_CAGED)
from tegrasp_drake.control.taxel_aware.curled_fingertips import CURLED_FINGERTIPS
from tegrasp_drake.control.taxel_aware.finger_strike import FINGER_STRIKE
from tegrasp_drake.control.taxel_aware.grip_settling import GRIP_SETTLING
from tegrasp_drake.control.taxel_aware.moves import centring_shift
from tegrasp_drake.control.taxel_aware.no_event_in_time import (LOAD_TIMEOUT_BOTH_PADS,
                                                                REACH_TIMEOUT_BOTH_PADS)
from tegrasp_drake.control.taxel_aware.off_centre import OFF_CENTRE
from tegrasp_drake.control.taxel_aware.one_sided_at_width import ONE_SIDED_AT_WIDTH
from tegrasp_drake.control.taxel_aware.ra_onset import RA_ONSET_ONE_FILM
from tegrasp_drake.control.taxel_aware.regrasp import (HELD_TILTED, REGRASP_AFTER_PLACE,
                                                      REGRASP_SET_DOWN)
from tegrasp_drake.control.taxel_aware.set_down import PLACE_SET_DOWN
from tegrasp_drake.control.taxel_aware.tipping_guard import TIPPING_GUARD
from tegrasp_drake.control.taxel_aware.touch_confirmed import TOUCH_CONFIRMED, TOUCH_UNCONFIRMED
from tegrasp_drake.control.taxel_aware.untouched_close import CLOSED_UNTOUCHED
from tegrasp_drake.control.transition_logic import PAPER_TABLE

CENTRING_RE_REACH = ReReachMove(
    shift_label="centred on the contact along both axes", limit_label="taxel_aware.max_re_reaches",
    limit=lambda s: s.config.taxel_aware.max_re_reaches, shift=centring_shift)

TAXEL_AWARE_TABLE = PAPER_TABLE.extended(
    "taxel_aware",
    rules=(FINGER_STRIKE, APPROACH_CONTACT, RA_ONSET_ONE_FILM, CURLED_FINGERTIPS, BEYOND_PADS,
           OFF_CENTRE, TOUCH_CONFIRMED, ONE_SIDED_AT_WIDTH, BRACKET_RECENTRE, CLOSED_UNTOUCHED,
           REACH_TIMEOUT_BOTH_PADS, REACH_TIMEOUT_CAGED, LOAD_TIMEOUT_BOTH_PADS, LOAD_TIMEOUT_CAGED, HELD_TILTED,
           REGRASP_AFTER_PLACE),
    guards=(CAGED, TIPPING_GUARD, GRIP_SETTLING, TOUCH_UNCONFIRMED, REGRASP_SET_DOWN,
            PLACE_SET_DOWN),
    re_reach_move=CENTRING_RE_REACH)


def rule_table() -> RuleTable:
    """The taxel_aware controller's rule table (its registry entry's)."""
    return TAXEL_AWARE_TABLE
