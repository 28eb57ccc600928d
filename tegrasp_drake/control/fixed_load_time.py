"""The paper's state machine with a fixed Load time: Load-Lift fires load_time_s after
entering Load, by the clock, instead of on the memorized Load-Lift event. Every other
transition is the paper's (transition_logic.next_mode), the Reach-Load and Place-Unload
events included.

A controller in two parts, as docs/controller.md ("Adding a controller") shows: its config
class (the YAML tag `!FixedLoadTimeControllerConfig`) and its rules; its entry in
controller_registry.py says how it is built (the shared state machine and event matcher).
"""

import dataclasses
import typing

from tegrasp_drake.control.controller_config import EventTriggeredConfig
from tegrasp_drake.control.grasp_modes import Decision, Mode, Trigger
from tegrasp_drake.rig.ranges import bounded


@dataclasses.dataclass
class FixedLoadTimeControllerConfig(EventTriggeredConfig):
    """The memorized controller's settings (it reads the same events) and the fixed Load
    time."""
    name: typing.ClassVar[str] = "fixed_load_time"
    events_folder: typing.ClassVar[str | None] = ""  # the paper's memorized events
    extra_time_s: typing.ClassVar[float] = 0.0
    # Lift this long after entering Load [s]. 1.0 s: the open-loop script's dwell on the
    # object after first contact is 0.56-1.06 s on the built-in objects
    # (scripted_grasp.GraspScriptConfig.load_s), and Load is entered on the Reach-Load
    # event, after that contact; the grip has settled by then. At or beyond
    # load_event_timeout_s the paper's give-up (Re-Reach) comes first.
    load_time_s: float = bounded(1.0, low=0.0, low_open=True, high=10.0, unit="s",
                                 below="must be positive [s]")


def next_mode(mode: Mode, obs, counters, config, *, event_trigger: Trigger,
              hold_s: float) -> Decision | None:
    """The paper's next_mode, except that the first Load ends by the clock: Lift once
    obs.time_in_mode reaches config.load_time_s, unless a device fails; the Load-Lift event
    is not read. A re-load after a Lift-Load is the paper's."""
    from tegrasp_drake.control import transition_logic  # loads Drake: on use, not import
    if mode == Mode.LOAD and not counters.lift_loads:
        failure = transition_logic.device_failure(obs)
        if failure is None and obs.time_in_mode >= config.load_time_s:
            return Decision(Mode.LIFT, Trigger.TIMER, f"loaded for {config.load_time_s:g} s")
        obs = dataclasses.replace(obs, event_matched=False)
    return transition_logic.next_mode(mode, obs, counters, config, event_trigger=event_trigger,
                                      hold_s=hold_s)
