"""Why a trial failed: one class per failed trial (FAILURE_CLASSES, the first that applies),
from its sweep record's result, after the paper's failure modes (Sec. IV-C) and the
controller's own reasons for giving up: by the rule that went to Failed (its code,
FAILURE_CLASS_OF_RULE), or by the reason's words for a result written before timeline
entries carried their rule's code; the classes: docs/sweeps.md, "A sweep"."""

from tegrasp_drake.control.controller_registry import controller_title
from tegrasp_drake.control.corrective_actions import corrective_action_of
from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.scenario.grasp_outcome import LIFTED_HEIGHT_M
from tegrasp_drake.scenario.trial_result import UPRIGHT_TILT_DEG
from tegrasp_drake.sweep.records import record_result

FAILURE_CLASSES = ("struck on approach", "closed on nothing", "one finger only",
                   "slipped in Lift", "event never matched", "object lost", "device fault",
                   "not lifted", "dropped in Hold", "toppled at release", "not placed", "other")

# The failure class of each rule that can go to Failed (its `then` says so in the rule tables,
# docs/controller.md), by its name: the code of the transition into Failed.
FAILURE_CLASS_OF_RULE = {
    "device_fault": "device fault",
    "gripper_fault": "device fault",
    "object_lost": "object lost",
    "closed_on_nothing": "closed on nothing",
    "one_sided": "one finger only",
    "bracket_recentre": "one finger only",  # one finger alone again, the other's face known
    "reach_timeout": "event never matched",
    "load_timeout": "event never matched",
    "lift_load": "slipped in Lift",  # still slipping after max_lift_loads
    # the open gripper ran into the object on its way in, Re-Reaches used up: a finger's front
    # struck it (the wrist's force) or a pad's face touched it before the close
    "finger_strike": "struck on approach",
    "approach_contact": "struck on approach",
}
# The class instead once the trial has made a Lift-Load (corrective_actions.py): no Load-Lift
# event after it is the slip that the Lift-Load did not stop.
FAILURE_CLASS_AFTER_LIFT_LOAD = {"load_timeout": "slipped in Lift"}


def failing_rule(result) -> str | None:
    """The code of the transition into Failed that ended `result` (a TrialResult), None when it
    did not end in Failed or its timeline carries no codes (written before them)."""
    if result.final_mode != Mode.FAILED or not result.transitions:
        return None
    last = result.transitions[-1]
    return last.code if last.to_mode == Mode.FAILED else None


def rule_failure_class(code: str, result) -> str:
    """The failure class of `result`, which the rule `code` sent to Failed; ValueError for a
    rule without one (FAILURE_CLASS_OF_RULE lacks it)."""
    if code not in FAILURE_CLASS_OF_RULE:
        raise ValueError(f"the rule '{code}' went to Failed but has no failure class: add it "
                         "to FAILURE_CLASS_OF_RULE (tegrasp_drake/sweep/failure_classes.py)")
    lift_loaded = any(corrective_action_of(entry.from_mode, entry.to_mode) == "lift_load"
                      for entry in result.transitions[:-1])
    if lift_loaded and code in FAILURE_CLASS_AFTER_LIFT_LOAD:
        return FAILURE_CLASS_AFTER_LIFT_LOAD[code]
    return FAILURE_CLASS_OF_RULE[code]


def failure_class(result) -> str | None:
    """The failure class of a trial's result (a TrialResult), None when it held and unloaded:
    a Failed one's by the rule that sent it there (failing_rule), else by its failure's words."""
    if result.unload_success:
        return None
    code = failing_rule(result)
    if code is not None:
        return rule_failure_class(code, result)
    failure = result.failure
    if failure:  # a result without codes: the reason's words
        if "during the approach" in failure:  # finger_strike's and approach_contact's
            return "struck on approach"
        if "closed on nothing" in failure:
            return "closed on nothing"
        if "finger touched" in failure:
            return "one finger only"
        if "still slips" in failure or "after Lift-Load" in failure:
            return "slipped in Lift"
        if "event" in failure and failure.startswith("no "):
            return "event never matched"
        if failure.startswith("object lost"):
            return "object lost"
        if failure.startswith("gripper fault") or result.final_mode == Mode.FAILED \
                and any(entry.trigger == Trigger.FAULT for entry in result.transitions):
            return "device fault"
        return "other"
    if result.lift_height_m is None or result.final_tilt_deg is None:
        return "other"  # a record without the ground truth (not written by run_trial)
    if not result.hold_success:
        if result.lift_height_m < LIFTED_HEIGHT_M:
            return "not lifted"
        return "dropped in Hold"
    if result.final_tilt_deg >= UPRIGHT_TILT_DEG:
        return "toppled at release"
    return "not placed"


def failure_class_counts(records) -> dict:
    """{controller: {object: {class: trials}}} over the records that ran, every class present."""
    counts = {}
    for record in records:
        if record["status"] != "ok":
            continue
        trial = record["trial"]
        per_object = counts.setdefault(trial["controller"], {}).setdefault(
            trial["object_name"], dict.fromkeys(FAILURE_CLASSES, 0))
        name = failure_class(record_result(record))
        if name is not None:
            per_object[name] += 1
    return counts


def failure_classes_markdown(counts: dict) -> str:
    """A table per controller: objects by the failure classes that occur in the sweep."""
    present = [name for name in FAILURE_CLASSES
               if any(per_object[name] for objects in counts.values()
                      for per_object in objects.values())]
    lines = ["## Failure classes (trials that were not held and unloaded)", "",
             "Classes and their order: `tegrasp_drake/sweep/failure_classes.py`.", ""]
    if not present:
        return "\n".join(lines + ["No trial failed.", ""])
    for controller, objects in counts.items():
        lines += [f"### {controller_title(controller)}", "",
                  "| Object | " + " | ".join(present) + " |",
                  "|---|" + "---|" * len(present)]
        for name, per_object in objects.items():
            lines.append(f"| {name} | " + " | ".join(str(per_object[c]) for c in present) + " |")
        lines.append("")
    return "\n".join(lines)
