"""TrialResult: what one simulated trial did, judged against the ground truth (Sec. IV-C).
Its JSON form (`to_dict`) is what result.json, `tegrasp trial --json` and a sweep record's
"result" hold; `from_dict` reads one back (a missing field takes its default)."""

import dataclasses

from tegrasp_drake.rig.api_boundary import public_dataclass
from tegrasp_drake.rig.ranges import shorten
from tegrasp_drake.control.grasp_modes import Mode, Transition


@public_dataclass
@dataclasses.dataclass
class TrialResult:
    """One trial's outcome. Times in seconds of simulated time unless said, lengths in
    metres, angles in degrees; transitions in order, Mode labels in the JSON form."""
    object: str = ""
    offset_m: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0])
    controller: str = ""
    seed: int | None = None
    transitions: tuple[Transition, ...] = ()
    hold_success: bool = False  # lifted and held at least HOLD_REQUIRED_S
    unload_success: bool = False  # then placed upright, released, retracted
    final_mode: Mode = Mode.REACH
    hold_time_s: float | None = None
    lift_height_m: float | None = None  # the object's lowest point above its start
    final_tilt_deg: float | None = None
    placement_error_m: float | None = None
    released: bool = False
    # The physical event behind each event transition taken, and "hit" [s]
    # (trial.physical_event_times); None where it was not found.
    physical_events: dict[str, float | None] = dataclasses.field(default_factory=dict)
    detection_latency_s: dict[str, float | None] = dataclasses.field(default_factory=dict)
    false_triggers: int = 0
    lift_grip_fraction: float | None = None  # the weaker pad's grip at the first lift
    corrective_actions: list[str] = dataclasses.field(default_factory=list)
    failure: str = ""  # the reason of the transition to Failed, "" for none
    sim_time_s: float | None = None
    wall_time_s: float | None = None
    cpu_time_s: float | None = None
    real_time_factor: float | None = None
    # The trial's log (a TrialLog) when run here; not part of the JSON form.
    log: object = dataclasses.field(default=None, compare=False, repr=False)

    def to_dict(self) -> dict:
        """The JSON form: all fields but `log`; transitions as dicts, the final mode by label."""
        data = {field.name: getattr(self, field.name) for field in dataclasses.fields(self)
                if field.name != "log"}
        data["transitions"] = [transition.as_dict() for transition in self.transitions]
        data["final_mode"] = self.final_mode.label
        return data

    @property
    def result(self) -> dict:
        """The JSON form (to_dict), for code written when run_trial returned it."""
        return self.to_dict()

    @classmethod
    def from_dict(cls, data: dict) -> "TrialResult":
        """The TrialResult of its JSON form; unknown keys ignored, missing fields defaulted."""
        known = {field.name for field in dataclasses.fields(cls)} - {"log"}
        values = {key: value for key, value in data.items() if key in known}
        try:  # a hand-edited JSON form: one line naming the field
            transitions = data.get("transitions", ())
            if not isinstance(transitions, list | tuple):
                raise ValueError(f"'transitions' must be a list, got {shorten(repr(transitions))}")
            values["transitions"] = tuple(map(Transition.from_dict, transitions))
            if "final_mode" in data:
                values["final_mode"] = Mode.from_label(data["final_mode"])
            return cls(**values)
        except (ValueError, TypeError) as e:
            raise ValueError(f"not a trial result's JSON form: {shorten(str(e), 300)}") from None

    def entered(self, mode: Mode) -> bool:
        """Whether the trial ever entered `mode`."""
        return any(transition.to_mode == mode for transition in self.transitions)
