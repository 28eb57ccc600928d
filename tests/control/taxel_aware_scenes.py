"""Closed-loop scenes of the taxel_aware controller (no tests here): a Scene, what must happen
in it (Expect), how it runs in a world (run_scene) and the check every scene test makes
(check_scene). The prismatic hand's scenes (test_taxel_aware_trials.py) and the linkage
hand's (test_taxel_aware_linkage_scenes.py) share them."""

import dataclasses

from tegrasp_drake.control.taxel_aware import TAXEL_AWARE_TABLE
from tegrasp_drake.runs.trial import run_trial
from tegrasp_drake.scenario.scenario import LoadScenario


@dataclasses.dataclass(frozen=True)
class Scene:
    """A trial: the object placed `offset` [m] (approach axis, stroke) and `yaw_deg` from its
    marker, the taxel_aware settings changed by `taxel_aware`, further `--set` assignments
    `overrides`."""
    object_name: str = "box"
    offset: tuple = (0.0, 0.0)
    yaw_deg: float = 0.0
    seed: int | None = None
    taxel_aware: tuple = ()  # (setting, value) pairs
    reads_the_held_grip: bool = False  # its rule decides in Hold: run in the default contact
    overrides: tuple = ()  # KEY=VALUE assignments, after the world's


@dataclasses.dataclass(frozen=True)
class Expect:
    """The (from, to, rule name) transitions that must occur in this order (others may come
    between), `first`: the first of them is the trial's first transition; `check`: a
    further assertion on (the matched transitions, the result dict)."""
    steps: tuple
    first: bool = False
    no_re_reach: bool = False
    unload: bool = True
    check: object = None


def run_scene(scene: Scene, world: tuple):
    """The TrialRun of `scene` in the world of `world`'s `--set` assignments."""
    base = LoadScenario(name=scene.object_name, controller="taxel_aware",
                        overrides=list(world + tuple(scene.overrides)))
    controller = dataclasses.replace(base.controller, taxel_aware=dataclasses.replace(
        base.controller.taxel_aware, **dict(scene.taxel_aware)))
    changes = dict(placement=dataclasses.replace(base.placement, offset=list(scene.offset),
                                                 yaw_deg=scene.yaw_deg),
                   controller=controller)
    if scene.seed is not None:
        changes["random_seed"] = scene.seed
    return run_trial(dataclasses.replace(base, **changes))


def load_waited_the_timeout(found, result):
    """An Expect check: the first matched transition, out of Load, came load_event_timeout_s
    after Load was entered, on the corrective trigger (a timeout rule, not an event)."""
    entered = [t["t"] for t in result["transitions"] if t["to"] == "Load"][0]
    timeout = LoadScenario(name=result["object"]).controller.load_event_timeout_s
    return found[0].t - entered >= timeout - 1e-9 and found[0].trigger == "corrective"


def matched(transitions, steps):
    """The transitions matching `steps` in order, or None."""
    found, k = [], 0
    for t in transitions:
        if k < len(steps) and (t.from_mode.label, t.to_mode.label, t.code) == steps[k]:
            found.append(t)
            k += 1
    return found if k == len(steps) else None


def check_scene(scene: Scene, expect: Expect, world: tuple):
    """Runs `scene` in `world` and asserts `expect`: its rules decide its transitions in
    order, and the grasp is held (and put down unless not expect.unload). Returns the run."""
    hand = LoadScenario(overrides=list(world + tuple(scene.overrides))).gripper.model
    for _, _, rule in expect.steps:
        TAXEL_AWARE_TABLE.for_hand(hand).rule(rule)  # KeyError: no such rule on this hand
    run = run_scene(scene, world)
    result = run.result
    codes = [(t.from_mode.label, t.to_mode.label, t.code) for t in run.transitions]
    found = matched(run.transitions, expect.steps)
    assert found is not None, codes
    if expect.first:
        assert found[0] is run.transitions[0], codes
    if expect.no_re_reach:
        assert "re_reach" not in result["corrective_actions"]
    if expect.check is not None:
        assert expect.check(found, result), codes
    assert result["final_mode"] == "Done" and result["hold_success"], codes
    assert result["unload_success"] or not expect.unload, codes
    return run
