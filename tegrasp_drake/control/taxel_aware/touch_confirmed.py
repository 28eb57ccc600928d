"""Guard touch_unconfirmed and rule touch_confirmed (Reach): a Reach-Load event match is
acted on only when a pad's touch confirms it (reach_load_confirmed, the one test every rule
acting on the match reads: the paper's reach_event through the guard, off_centre and
touch_confirmed directly). A pad's SA sum above contact_force_n at the match, or within
match_confirm_window_s after it, confirms it; until then the paper's reach_event and
off_centre are held back, and a match no pad confirms in the window is dropped, Reach going
on, the matcher free to match again (docs/controller.md, "A pad's touch confirms the
Reach-Load event")."""

from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.control.rule_actions import Load, decide
from tegrasp_drake.control.rule_engine import Guard, Rule
from tegrasp_drake.rig.number_text import number_text


def match_confirm_window_s(sa_rate_hz: float, update_period_s: float) -> float:
    """How long after a Reach-Load match [s] a pad's touch still confirms it: two taxel
    frames at the pads' sample rate `sa_rate_hz` [Hz] and one controller tick
    `update_period_s` [s]. The matcher passes on the RA film's first transient of a touch
    (sampled far faster than the taxels), so the touch that moved the film reaches the
    taxels' next converted frame, or the one after when the match fell just after a frame's
    conversion had started (a frame is converted over its whole period, its stages one after
    the other, and sampled at its end); the controller then reads that frame on its first
    tick at or after it, up to one period later. ValueError unless both are positive."""
    if not (sa_rate_hz > 0.0 and update_period_s > 0.0):
        raise ValueError(f"the pads' sample rate ({number_text(sa_rate_hz)} Hz) and the "
                         f"controller's update period ({number_text(update_period_s)} s) must "
                         "be positive")
    return 2.0 / sa_rate_hz + update_period_s


def confirmed_delay_s(matched_at: float, t: float, touching: bool, window_s: float) -> float:
    """The time [s] from the latest Reach-Load match at `matched_at` [s] (-1: none) to `t`
    [s] when a pad is `touching` (its SA sum above contact_force_n) within `window_s` [s]
    of it; -1 when no match is pending or no pad confirms it."""
    pending = matched_at >= 0.0 and t - matched_at <= window_s
    return t - matched_at if pending and touching else -1.0


def reach_load_confirmed(situation) -> bool:
    """The Reach-Load match is confirmed: in Reach, a pad's touch at the latest match or
    within the window after it (ContactEstimate.match_confirmed_s, 0 at the match itself)."""
    return situation.estimate.match_confirmed_s >= 0.0


def touch_unconfirmed(situation) -> bool:
    return not reach_load_confirmed(situation)


def load_confirmed(situation):
    pads = [name for name, on in zip(("left", "right"), situation.obs.contact) if on]
    delay_ms = 1000.0 * situation.estimate.match_confirmed_s
    return decide(Load(), situation.event_trigger,
                  f"Reach-Load event, confirmed {delay_ms:.0f} ms after by the "
                  f"{' and '.join(pads)} pad's touch")


TOUCH_UNCONFIRMED = Guard(
    "touch_unconfirmed", ("reach_event",), touch_unconfirmed,
    when="no pad's touch confirms the Reach-Load match (a pad's SA above contact_force_n at "
    "it or within two taxel frames and a controller tick after it)")
TOUCH_CONFIRMED = Rule(
    "touch_confirmed", (Mode.REACH,), 110, reach_load_confirmed, load_confirmed,
    when="a pad's SA above contact_force_n within two taxel frames and a controller tick "
    "of a Reach-Load event match",
    then="Load (event): close at the grip force")
