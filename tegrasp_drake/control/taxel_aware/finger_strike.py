"""Rule finger_strike (Reach, in the approach): a finger's front struck the object, felt at
the wrist (control/finger_strike.py) or, on the linkage hand, by that finger's film alone
(estimator.ContactEstimator's film strike): back off approach_retreat_m along the Reach's
path (the state machine's approach_retreat_target), shift toward the struck finger, approach
again (docs/controller.md, "Finger strike")."""

from tegrasp_drake.control.finger_strike import strike_shift
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift
from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.control.rule_actions import re_reach_or_fail
from tegrasp_drake.control.rule_engine import Rule


def strikes(situation) -> bool:
    """The wrist force for sustain_s, or one film's RA onset at once: its threshold already
    bounds noise over every 1 kHz sample, and a light strike rings for 6 ms."""
    strike = situation.config.taxel_aware.finger_strike
    e = situation.estimate
    return strike.enabled and (e.strike_by_film or e.strike_s >= strike.sustain_s)


def back_off_and_shift(situation):
    e = situation.estimate
    finger = e.strike_finger or None
    who = f"the {finger} finger" if finger else "a finger (side unknown)"
    shift = Shift(-situation.config.taxel_aware.approach_retreat_m,
                  strike_shift(finger, e.opening_m, e.object_width_m))
    felt = (f"its film's RA, {e.strike_force_n:.1f} N at the wrist" if e.strike_by_film
            else f"{e.strike_force_n:.1f} N at the wrist")
    return re_reach_or_fail(situation, shift, f"{who} struck the object during the "
                            f"approach ({felt})")


FINGER_STRIKE = Rule(
    "finger_strike", (Mode.REACH,), 10, strikes, back_off_and_shift,
    when="in the approach, the wrist force exceeded finger_strike.force_n for sustain_s, or "
    "(linkage hand) one film alone peaked above taxel_aware.ra_onset_mps2 in a tick",
    then="ReReach(back off, toward the struck finger by (opening - width + its front) / 2) "
    "or Failed")
