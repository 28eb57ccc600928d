"""Rule ra_onset_one_film (closing): the close's first RA onset is on one film alone, no
pad's SA touching, and the push still to come, (opening - width) / 2 at the onset, would
topple the expected object (contact_geometry.release_topples): a light one-pad touch that the
SA taxels cannot see. Stop the close (open) and Re-Reach toward the touched finger by that
push, finger_strike.pad_touch_shift (docs/controller.md, "An RA onset on one film stops the
close")."""

from tegrasp_drake.control.finger_strike import FINGERS, pad_touch_shift
from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import ReReach, decide, re_reach_allowed
from tegrasp_drake.control.rule_engine import Rule
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift


def onset_finger(ra_mps2, threshold_mps2: float) -> str | None:
    """The film whose RA [m/s^2] is above threshold_mps2: "left" or "right", "" both, None
    neither or a threshold of 0 (the rule off)."""
    if threshold_mps2 <= 0.0:
        return None
    above = [abs(float(x)) > threshold_mps2 for x in ra_mps2]
    if not any(above):
        return None
    return "" if all(above) else FINGERS[above.index(True)]


def one_film_onset(situation) -> bool:
    e = situation.estimate
    return (e.ra_onset_finger in FINGERS and e.ra_onset_topples and not any(e.contact)
            and re_reach_allowed(situation))


def stop_and_shift(situation):
    e = situation.estimate
    shift = Shift(0.0, pad_touch_shift(e.ra_onset_finger, e.ra_onset_opening_m,
                                       e.object_width_m))
    return decide(ReReach(shift), Trigger.CORRECTIVE,
                  f"the {e.ra_onset_finger} film alone felt a touch at "
                  f"{e.ra_onset_opening_m * 1e3:.1f} mm open: stop, shift "
                  f"{shift.dy_m * 1e3:+.1f} mm toward it")


RA_ONSET_ONE_FILM = Rule(
    "ra_onset_one_film", (Mode.REACH,), 25, one_film_onset, stop_and_shift,
    when="the close's first RA above taxel_aware.ra_onset_mps2 on one film alone, no pad's SA "
    "touching, the push to come would topple the object; Re-Reaches left",
    then="ReReach(toward the touched finger by (opening - width) / 2)")
