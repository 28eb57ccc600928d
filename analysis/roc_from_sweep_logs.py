"""ROC-style curves of a memorized controller's event triggers from a sweep's trial logs
(`tegrasp sweep --logs DIR`), re-scored offline (recording/detection_quality.py): for each
event transition, detection and false-trigger rates as the thresholds are scaled from the
controller's own. A report of the judged trials: nothing here chooses a threshold.

    python analysis/roc_from_sweep_logs.py LOGS_DIR OUT.md [--controller taxel_aware]
        [--events events] [--limit N]

Armed spans follow the logged transitions, as the state machine looks for each event:
Reach-Load from the start of the last Reach before Load, Load-Lift from the entry into
Load, Place-Unload from the entry into Place. The physical events are the trial's own
(result physical_events, kept in the log's meta).
"""

import pathlib
import sys

import numpy as np

from tegrasp_drake.commands.script_output import (EVENTS_ADVICE, run_script, script_parser,
                                                  write_report)
from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig.paths import package_events_dir
from tegrasp_drake.rig.ranges import Range
from tegrasp_drake.control.controller_registry import controller_named
from tegrasp_drake.control.grasp_controller import controller_events_folders
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.events import EventMatcherConfig, tactile_trial_from_log
from tegrasp_drake.events.events_folder import find_memorized_events
from tegrasp_drake.recording.detection_quality import roc_curve, scored_span
from tegrasp_drake.scenario.trial_log_file import load_trial_log

TRANSITIONS = ("reach_load", "load_lift", "place_unload")
SOURCE = {"reach_load": "Reach", "load_lift": "Load", "place_unload": "Place"}
TARGET = {"reach_load": "Load", "load_lift": "Lift", "place_unload": "Unload"}
SCALES = np.round(np.arange(0.70, 1.111, 0.05), 3)


def armed_from(transitions, transition):
    """When the mode that waits for `transition` was last entered before it was left
    toward its target (None when the trial never reached that mode)."""
    source, target = SOURCE[transition], TARGET[transition]
    entered = 0.0 if source == "Reach" else None
    for entry in transitions:
        if entry["from"] == source and entry["to"] == target:
            return entered
        if entry["to"] == source:
            entered = entry["t"]
    return entered


def title(controller: str) -> str:
    """The report's first line, by which an earlier report at OUT is known."""
    return f"# ROC-style curves of the {controller} controller's event triggers"


def main(argv=None) -> int:
    parser = script_parser("roc_from_sweep_logs", __doc__)
    parser.add_input("logs", type=pathlib.Path, what="logs folder",
                     advice="give the --logs folder of a `tegrasp sweep`")
    parser.add_output("out", type=pathlib.Path, title=lambda args: title(args.controller))
    parser.add_argument("--controller", default="taxel_aware")
    parser.add_input("--events", default=str(package_events_dir()), what="--events folder",
                     advice=EVENTS_ADVICE)
    parser.add_number("--limit", type=integer_option, default=None, allowed=Range(low=1),
                      help="score at most this many logs (default: all)")
    parser.add_argument("--gripper-model", default="linkage",
                        help="the hand the logs were simulated on (its chosen thresholds)")
    args = parser.parse_args(argv)
    paths = sorted(args.logs.glob(f"{args.controller}.*.npz"))[:args.limit]
    if not paths:
        raise SystemExit(f"roc_from_sweep_logs: no {args.controller}.*.npz in {args.logs}")
    controller = controller_named(args.controller)
    # the paper's 0.9 / 0.7 for controllers without events
    matching = getattr(controller, "matching", EventMatcherConfig())
    thresholds = {t: (matching.sa_threshold, matching.ra_threshold) for t in TRANSITIONS}
    chosen = dict(gripper_hand(args.gripper_model).ensemble_thresholds)
    if hasattr(controller, "event_thresholds"):
        thresholds.update(controller.event_thresholds(chosen))
    events_by_object, spans = {}, {t: [] for t in TRANSITIONS}
    for path in paths:
        log = load_trial_log(path)
        name = path.name.split(".")[1]
        if name not in events_by_object:
            events_by_object[name] = find_memorized_events(
                controller_events_folders(controller, args.events), name)[1]
        trial = tactile_trial_from_log(log)
        physical = log.meta.get("events", {})
        for transition in TRANSITIONS:
            start = armed_from(log.meta["transitions"], transition)
            if start is None or physical.get(transition) is None:
                continue
            spans[transition].append(scored_span(
                path.stem, trial, events_by_object[name], transition, armed_from_s=start,
                physical_s=physical[transition]))
        print(f"scored {path.name}", flush=True)
    lines = [title(args.controller) + "\n",
             f"From {len(paths)} trial logs of `{args.logs.name}`, re-scored offline "
             "(`analysis/roc_from_sweep_logs.py`); the thresholds are scaled together from "
             "the controller's own (scale 1.00). Judged trials: no threshold is chosen "
             "here.\n"]
    for transition in TRANSITIONS:
        base = thresholds[transition]
        lines += [f"## {transition} ({len(spans[transition])} trials; SA > {base[0]:.2f}, "
                  f"RA > {base[1]:.2f} at 1.00)\n",
                  "| scale | SA | RA | detected | false | missed | median latency |",
                  "|---|---|---|---|---|---|---|"]
        for scale, p in zip(SCALES, roc_curve(spans[transition], SCALES, base=base)):
            latency = "–" if p.median_latency_s is None else f"{1000 * p.median_latency_s:.0f} ms"
            lines.append(f"| {scale:.2f} | {p.sa_threshold:.3f} | {p.ra_threshold:.3f} | "
                         f"{p.detection_rate:.2f} | {p.false_rate:.2f} | "
                         f"{p.missed / p.spans if p.spans else 0:.2f} | {latency} |")
        lines.append("")
    write_report(args.out, "\n".join(lines), script="roc_from_sweep_logs")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "roc_from_sweep_logs"))
