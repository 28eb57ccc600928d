"""The taxel-aware controller: the paper's rule table extended by rules that read
the whole taxel array, over what one ContactEstimator senses.

  table.py               the rule table (the paper's plus the rules below)
  estimator.py           ContactEstimator: what the rules sense, each tick
  contact_geometry.py    the geometry the estimator computes (pure functions)
  moves.py               the centring Re-Reach
  hands.py               the hands a rule is kept to (PRISMATIC_ONLY)
  finger_strike.py       rule: a finger's front struck the object in the approach
  approach_contact.py    rule: a pad touched in the approach
  ra_onset.py            rule: an RA onset on one film alone stops the close
  curled_fingertips.py   rule: a touch of fingertips curled past the object backs off
  beyond_pads.py         rule: a first touch beyond the pads stops the close
  off_centre.py          rule: re-centre along the approach axis
  one_sided_at_width.py  rule: one finger alone at the object's width loads
  bracketing.py          rule: faces touched in turn bracket the object
  untouched_close.py     rule: a close that touched nothing searches beyond the fingertips
  no_event_in_time.py    rules: both pads on, no event in time
  caged.py               rules and guard: an object caged behind the pads
  regrasp.py             rules and guard: re-grasp an object held tilted
  set_down.py            guard: a Place lets go once its move has set the object down
  tipping_guard.py       guard: no re-centring after a push past the tipping limit
  grip_settling.py       guard: the Load-Lift event lifts only a settled grip
  touch_confirmed.py     guard and rule: a pad's touch confirms the Reach-Load event"""

from tegrasp_drake.control.taxel_aware.estimator import (ContactEstimate, ContactEstimator,
                                                         ContactMemory, ContactReading,
                                                         ObjectGeometry, estimator_for_plan)
from tegrasp_drake.control.taxel_aware.table import TAXEL_AWARE_TABLE, rule_table

__all__ = ["ContactEstimate", "ContactEstimator", "ContactMemory", "ContactReading",
           "ObjectGeometry", "TAXEL_AWARE_TABLE", "estimator_for_plan", "rule_table"]
