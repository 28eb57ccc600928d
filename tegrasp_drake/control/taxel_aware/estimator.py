"""What the taxel-aware rules sense, estimated in one place apart from the decisions (the
contact's shape, the close's first touch, the faces touched, a finger strike, the push and
its tipping, a touch beyond the pads, a cage, a tilted hold). `ContactEstimator.update(
memory, reading)` is pure: the GraspStateMachine keeps the ContactMemory in its abstract
state and the rules read the ContactEstimate (Observation.estimate)."""

import dataclasses
import typing

from tegrasp_drake.control.finger_strike import (FINGERS, side_moment_nm, strike_force_n,
                                                  struck_finger)
from tegrasp_drake.control.grasp_modes import HOLDING_MODES, Mode, Stage
from tegrasp_drake.control.taxel_aware.contact_geometry import (
    bracketed_object, caged_behind_pads, curled_touch, held_tilted, opposite_face,
    pushed_distance_m, release_topples, remembered_faces, touched_beyond_pads, touched_face,
    touched_faces, untouched_reach_m)
from tegrasp_drake.control.taxel_aware.grip_settling import grip_settled
from tegrasp_drake.control.taxel_aware.hands import FILM_STRIKE_HANDS
from tegrasp_drake.control.taxel_aware.ra_onset import onset_finger
from tegrasp_drake.control.taxel_aware.touch_confirmed import (confirmed_delay_s,
                                                               match_confirm_window_s)
from tegrasp_drake.control.taxel_contact import GraspContact, grasp_contact
from tegrasp_drake.robotiq.units import STROKE_M


@dataclasses.dataclass(frozen=True)
class ContactMemory:
    """What the estimator remembers between ticks (times in s; -1: not running):
    first_touch_* (opening [m; -1 none], approach-axis offset [m], the pad alone or ""),
    the faces touched when the last Re-Reaches began, and the finger strike's baseline
    wrench, timer, summed side moment and finger; reach_match_at: the latest tick of this
    Reach at which the Reach-Load event matched (touch_confirmed.py); touched_before: a
    taxel touched the object, or a finger struck it, before the latest transition in this
    trial (untouched_close.py); ra_onset_*: the close's first RA onset, its film ("" both)
    and the opening [m; -1 none] (ra_onset.py)."""
    first_touch_opening_m: float = -1.0
    first_touch_offset_m: float = 0.0
    first_touch_finger: str = ""
    touched_faces: tuple = ()
    strike_baseline: tuple = ()
    strike_since: float = -1.0
    strike_moment_sum: float = 0.0
    strike_finger: str = ""
    approach_contact_since: float = -1.0
    tilted_since: float = -1.0
    reach_match_at: float = -1.0
    touched_before: bool = False
    ra_onset_finger: str = ""
    ra_onset_opening_m: float = -1.0

    def after_transition(self, from_mode: Mode, to_mode: Mode,
                         touched_now: tuple) -> "ContactMemory":
        """The memory on entering `to_mode`: timers restart; the first touch is kept into
        Load, its offset until a Re-Reach, which remembers the faces `touched_now`."""
        close_goes_on = to_mode == Mode.LOAD and from_mode != Mode.LIFT
        re_reach = to_mode == Mode.RE_REACH
        return ContactMemory(
            first_touch_opening_m=self.first_touch_opening_m if close_goes_on else -1.0,
            first_touch_finger=self.first_touch_finger if close_goes_on else "",
            first_touch_offset_m=0.0 if re_reach else self.first_touch_offset_m,
            touched_faces=(remembered_faces(self.touched_faces, touched_now) if re_reach
                           else self.touched_faces),
            touched_before=(self.touched_before or self.first_touch_opening_m >= 0.0
                            or bool(touched_now) or bool(self.strike_finger)
                            or self.strike_since >= 0.0))


@dataclasses.dataclass(frozen=True)
class ContactReading:
    """The tick's inputs [s, N, m; world]; wrench on G is None without a finger-strike sense;
    stopped_on_object: the 2F-85 reports its fingers stopped on an object while closing (gOBJ 2)
    for the close request in force; event_matched: the detector matches the mode's event;
    ra_mps2: the films' RA readings (left, right) [m/s^2]; ra_peak_mps2: each film's peak |RA|
    over the tick [m/s^2] (tactile/ra_tick_peak.py), None: the tick's ra_mps2."""
    t: float
    mode: Mode
    stage: object
    lift_loads: int
    taxel_forces: tuple
    sa_n: tuple
    contact: tuple
    opening_m: float
    at_requested_position: bool
    stopped_on_object: bool
    wrench: tuple | None
    gripper_y_m: float
    event_matched: bool
    ra_mps2: tuple = (0.0, 0.0)
    ra_peak_mps2: tuple | None = None

    @property
    def approaching(self) -> bool:
        return self.mode == Mode.REACH and self.stage == Stage.MOVING

    @property
    def closing(self) -> bool:
        return self.mode == Mode.REACH and self.stage == Stage.CLOSING


@dataclasses.dataclass(frozen=True)
class ContactEstimate:
    """What the rules read [s, N, m; world], each field named for what contact_geometry.py
    computes. pad_travel_to_grasp_m: how much further along the approach the pads' centres lie
    once closed (0 on the prismatic hand); bracket: (centre y, extent) or None; grip_settling:
    the grip has not settled (grip_settling.grip_settled); match_confirmed_s: in Reach, the
    time since the latest Reach-Load match that a pad's touch confirms (0 at the match
    itself), -1 none (touch_confirmed.py); reach_matched: the Reach-Load event matched in this
    Reach, confirmed or not; untouched_reach_m: how far beyond the pads' centres at the
    object's width an object no pad touched in the close has its centre
    (contact_geometry.untouched_reach_m); touched_before: ContactMemory.touched_before;
    strike_by_film: the strike is one film's RA onset (ContactEstimator's film strike);
    ra_onset_finger, ra_onset_opening_m: ContactMemory's; ra_onset_topples: the push still to
    come from that opening would topple the object (contact_geometry.release_topples);
    hooked_object_dx_m: in the close, when its first touch was a curl
    (contact_geometry.curled_touch), where the hooked object's centre lies along the approach
    from the pads' centres at its width [m] (ObjectGeometry.hooked_object_offset), else None."""
    shape: GraspContact
    sa_n: tuple
    contact: tuple
    opening_m: float
    object_width_m: float
    gripper_y_m: float
    approaching: bool
    approach_contact_s: float = 0.0
    strike_s: float = 0.0
    strike_force_n: float = 0.0
    strike_finger: str = ""
    strike_by_film: bool = False
    topples_if_released: bool = False
    touched_beyond_pads: bool = False
    first_touch_finger: str = ""
    first_touch_opening_m: float = -1.0
    pad_travel_to_grasp_m: float = 0.0
    caged_behind_pads: bool = False
    bracket: tuple | None = None
    touched_now: tuple = ()
    tilted_s: float = 0.0
    grip_settling: bool = False
    match_confirmed_s: float = -1.0
    reach_matched: bool = False
    untouched_reach_m: float = 0.0
    touched_before: bool = False
    ra_onset_finger: str = ""
    ra_onset_opening_m: float = -1.0
    ra_onset_topples: bool = False
    hooked_object_dx_m: float | None = None

    @property
    def bracketed_width_m(self) -> float:
        """The bracketed object's extent [m]; 0 without a bracket."""
        return self.bracket[1] if self.bracket else 0.0


@dataclasses.dataclass(frozen=True)
class ObjectGeometry:
    """The expected object and grasp [m], the hand's pads' centres beyond G along the
    approach at an opening (gripper_hands.pad_center_offset), and where an object its curled
    fingertips hook lies (gripper_hands.hooked_object_offset; None on a hand that cannot
    curl)."""
    width_m: float
    height_m: float
    grasp_height_m: float
    pad_center_offset: typing.Callable[[float], float] = lambda opening_m: 0.0
    hooked_object_offset: typing.Callable[[float, float, float], float | None] = (
        lambda opening_m, contact_offset_m, object_width_m: None)


class ContactEstimator:
    """Estimates the contact each tick; a taxel counts above taxel_contact_n [N]; a pad's
    touch confirms a Reach-Load match within match_confirm_window_s [s]
    (touch_confirmed.match_confirm_window_s); film_strike: in the approach, one film's RA
    above taxel_aware.ra_onset_mps2 is also a finger strike, of that finger
    (hands.FILM_STRIKE_HANDS)."""

    def __init__(self, *, taxel_config, geometry: ObjectGeometry, taxel_contact_n: float,
                 match_confirm_window_s: float, film_strike: bool):
        self._config = taxel_config
        self._film_strike = film_strike
        self._geometry = geometry
        self._taxel_contact_n = taxel_contact_n
        self._match_confirm_window_s = match_confirm_window_s
        self._ra_onset_mps2 = taxel_config.ra_onset_mps2
        self._untouched_reach_m = untouched_reach_m(geometry.pad_center_offset,
                                                    geometry.width_m, STROKE_M)

    def update(self, memory: ContactMemory, r: ContactReading
               ) -> tuple[ContactMemory, ContactEstimate]:
        t, g = r.t, self._geometry
        shape = grasp_contact(r.taxel_forces, self._taxel_contact_n)
        tilted = r.mode == Mode.HOLD and held_tilted(shape, self._config)
        tilted_since = _since(memory.tilted_since, t, tilted)
        touching_in_approach = r.approaching and any(r.contact)
        approach_since = _since(memory.approach_contact_since, t, touching_in_approach)
        reaching = r.mode == Mode.REACH
        match_at = t if reaching and r.event_matched else memory.reach_match_at
        memory = dataclasses.replace(memory, tilted_since=tilted_since,
                                     approach_contact_since=approach_since,
                                     reach_match_at=match_at)
        memory, strike = self._sense_strike(memory, r)
        # a Reach-Load event can match a taxel sample (9.3 ms) before the taxels show it
        first_load = r.mode == Mode.LOAD and r.lift_loads == 0
        memory, topples = self._first_touch(memory, r, shape, first_load)
        memory = self._ra_onset(memory, r)
        touch = (touched_face("left" if r.contact[0] else "right", r.gripper_y_m, r.opening_m)
                 if r.closing and r.contact[0] != r.contact[1] else None)
        bracket = (bracketed_object(opposite_face(memory.touched_faces, touch.finger), touch,
                                    g.width_m) if touch is not None else None)
        first_close = r.closing or first_load
        beyond = first_close and touched_beyond_pads(
            first_touch_offset_m=memory.first_touch_offset_m,
            one_pad=bool(memory.first_touch_finger),
            pushed_m=pushed_distance_m(memory.first_touch_opening_m, g.width_m),
            grasp_height_m=g.grasp_height_m, object_width_m=g.width_m,
            object_height_m=g.height_m, taxel_config=self._config)
        closed = r.closing or r.mode in (Mode.LOAD, *HOLDING_MODES)
        caged = closed and caged_behind_pads(
            first_touch_offset_m=memory.first_touch_offset_m, opening_m=r.opening_m,
            object_width_m=g.width_m, pads_touch=shape.left.touching or shape.right.touching,
            closed_to_request=r.at_requested_position, taxel_config=self._config)
        estimate = ContactEstimate(
            shape=shape, sa_n=tuple(r.sa_n), contact=r.contact, opening_m=r.opening_m,
            object_width_m=g.width_m, gripper_y_m=r.gripper_y_m, approaching=r.approaching,
            approach_contact_s=t - approach_since if touching_in_approach else 0.0,
            **strike, topples_if_released=topples, touched_beyond_pads=beyond,
            first_touch_finger=memory.first_touch_finger,
            first_touch_opening_m=memory.first_touch_opening_m,
            pad_travel_to_grasp_m=(g.pad_center_offset(g.width_m)
                                   - g.pad_center_offset(r.opening_m)),
            caged_behind_pads=caged, bracket=bracket,
            touched_now=(touched_faces(r.contact, r.gripper_y_m, r.opening_m)
                         if r.closing else ()),
            tilted_s=t - tilted_since if tilted else 0.0,
            grip_settling=not grip_settled(r.contact, r.stopped_on_object),
            match_confirmed_s=(confirmed_delay_s(match_at, t, any(r.contact),
                                                 self._match_confirm_window_s)
                               if reaching else -1.0),
            reach_matched=reaching and match_at >= 0.0,
            untouched_reach_m=self._untouched_reach_m,
            touched_before=memory.touched_before,
            ra_onset_finger=memory.ra_onset_finger,
            ra_onset_opening_m=memory.ra_onset_opening_m,
            ra_onset_topples=release_topples(
                pushed_distance_m(memory.ra_onset_opening_m, g.width_m),
                grasp_height_m=g.grasp_height_m, object_width_m=g.width_m,
                object_height_m=g.height_m),
            hooked_object_dx_m=(
                g.hooked_object_offset(r.opening_m, shape.approach_offset_m, g.width_m)
                if r.closing and (shape.left.touching or shape.right.touching)
                and curled_touch(memory.first_touch_opening_m, g.width_m) else None))
        return memory, estimate

    def _ra_onset(self, memory: ContactMemory, r: ContactReading) -> ContactMemory:
        """Remembers the close's first RA onset (ra_onset.onset_finger)."""
        if not r.closing or memory.ra_onset_opening_m >= 0.0:
            return memory
        finger = onset_finger(_tick_ra(r), self._ra_onset_mps2)
        if finger is None:
            return memory
        return dataclasses.replace(memory, ra_onset_finger=finger,
                                   ra_onset_opening_m=r.opening_m)

    def _sense_strike(self, memory: ContactMemory, r: ContactReading):
        """The finger-strike sense: the updated memory and the estimate's strike fields. A
        strike is the wrist force above finger_strike.force_n or, with film_strike, one film's
        peak over the tick alone above the RA onset threshold, which names its finger
        (strike_by_film: a strike at once, finger_strike.strikes)."""
        config = self._config.finger_strike
        wrist = r.wrench is not None
        if not (config.enabled and r.approaching and (wrist or self._film_strike)):
            return memory, {}
        film = onset_finger(_tick_ra(r), self._ra_onset_mps2) if self._film_strike else None
        film_finger = film if film in FINGERS else ""
        baseline = (memory.strike_baseline or tuple(float(x) for x in r.wrench)) if wrist else ()
        force = strike_force_n(r.wrench, baseline) if wrist else 0.0
        felt_at_wrist = force > config.force_n
        striking = felt_at_wrist or bool(film_finger)
        since = _since(memory.strike_since, r.t, striking)
        # the side moment is summed over the ticks the wrist feels the strike
        moment_sum = (memory.strike_moment_sum + side_moment_nm(r.wrench, baseline)
                      if felt_at_wrist else memory.strike_moment_sum if striking else 0.0)
        finger = film_finger or struck_finger(moment_sum, r.contact, config) or ""
        memory = dataclasses.replace(memory, strike_baseline=baseline, strike_since=since,
                                     strike_moment_sum=moment_sum, strike_finger=finger)
        return memory, dict(strike_s=r.t - since if striking else 0.0, strike_force_n=force,
                            strike_finger=finger, strike_by_film=bool(film_finger))

    def _first_touch(self, memory: ContactMemory, r: ContactReading, shape: GraspContact,
                     first_load: bool) -> tuple[ContactMemory, bool]:
        """Remembers the close's first touch and whether the push since would topple the object."""
        g = self._geometry
        recording = r.closing or (first_load and shape.approach_offset_m >= 0.0)
        if (recording and memory.first_touch_opening_m < 0.0
                and (shape.left.touching or shape.right.touching)):
            finger = ("" if shape.left.touching == shape.right.touching
                      else "left" if shape.left.touching else "right")
            memory = dataclasses.replace(memory, first_touch_opening_m=r.opening_m,
                                         first_touch_offset_m=shape.approach_offset_m,
                                         first_touch_finger=finger)
        pushed = pushed_distance_m(memory.first_touch_opening_m, g.width_m)
        topples = r.closing and release_topples(pushed, grasp_height_m=g.grasp_height_m,
                                                object_width_m=g.width_m,
                                                object_height_m=g.height_m)
        return memory, topples


def _tick_ra(r: ContactReading):
    """Each film's RA over the tick [m/s^2]: its peak |RA| over every sample since the last
    tick where the diagram gives it (ra_tick_peak.py), else the tick's own sample. A light
    touch's ring can last one tick or less (the wide light box's strike: 6 ms above the
    onset), and the onset threshold was set against noise on every sample."""
    return r.ra_mps2 if r.ra_peak_mps2 is None else r.ra_peak_mps2


def _since(since: float, t: float, on: bool) -> float:
    """A timer's start: kept while `on` (started now if it was not running), else -1."""
    return (since if since >= 0 else t) if on else -1.0


def estimator_for_plan(config, plan, *, sa_rate_hz: float) -> ContactEstimator:
    """The ContactEstimator of taxel_aware `config` for the GraspPlan `plan`, its pads'
    taxels sampled at sa_rate_hz [Hz] (the scenario's tactile.sample_rate_hz)."""
    from tegrasp_drake.simulation.gripper_hands import gripper_hand
    hand = gripper_hand(plan.gripper_model)
    return ContactEstimator(
        taxel_config=config.taxel_aware, taxel_contact_n=config.taxel_contact_n,
        match_confirm_window_s=match_confirm_window_s(sa_rate_hz, config.update_period_s),
        film_strike=plan.gripper_model in FILM_STRIKE_HANDS,
        geometry=ObjectGeometry(
            width_m=plan.object_width, height_m=plan.object_height,
            grasp_height_m=plan.grasp_height,
            pad_center_offset=hand.pad_center_offset,
            hooked_object_offset=hand.hooked_object_offset))
