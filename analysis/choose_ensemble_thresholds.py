"""Choose the taxel_aware controller's Eq. 3 thresholds on held-out ensemble runs, and
write their ROC-style table (recording/detection_quality.py).

    python analysis/choose_ensemble_thresholds.py LOGS_DIR OUT.md [--runs 5 6 7]
        [--events events]

LOGS_DIR holds analysis/record_ensemble_events.py's logs (<object>/run<k>.npz); --runs
names the runs NOT used for the templates (the default: runs 5-7 of 8, the first 5 made
the templates). The sweeps that judge the controller use other seeds altogether.
"""

import pathlib
import sys

import numpy as np

from tegrasp_drake.commands.script_output import (ENSEMBLE_LOGS_ADVICE, EVENTS_ADVICE,
                                                  run_script, script_parser, write_report)
from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig.paths import package_events_dir
from tegrasp_drake.rig.ranges import Range
from tegrasp_drake.control.controller_config import TaxelAwareControllerConfig
from tegrasp_drake.control.grasp_controller import controller_events_folders
from tegrasp_drake.events import tactile_trial_from_log
from tegrasp_drake.events.events_folder import find_memorized_events
from tegrasp_drake.recording.detection_quality import (choose_thresholds, rate_point, roc_curve,
                                                       scored_span)
from tegrasp_drake.scenario.grasp_outcome import physical_events
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.scenario.trial_log_file import load_trial_log
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS

SA_GRID = np.round(np.arange(0.40, 0.981, 0.02), 3)
RA_GRID = np.round(np.arange(0.40, 0.901, 0.05), 3)
TRANSITIONS = ("reach_load", "load_lift", "place_unload")
ROC_SCALES = np.round(np.arange(0.70, 1.111, 0.05), 3)


def spans_of_log(path, object_name, events):
    log = load_trial_log(path)
    scenario = LoadScenario(name=object_name)
    physical = physical_events(log, scenario.grasp.grip_force, scenario.object)
    starts = log.meta["phase_starts"]
    trial = tactile_trial_from_log(log)
    armed = {"reach_load": 0.0, "load_lift": physical["first_contact"],
             "place_unload": starts["place"]}
    # Scored as the trial judge scores a closed-loop run (runs/trial.py): Load-Lift against
    # the grip settled, the earliest a lift may start, not the script's lift start (the
    # event's anchor), which a controller that lifts on the event cannot wait for.
    times = {"reach_load": physical["first_contact"],
             "load_lift": physical["grip_force_reached"],
             "place_unload": physical["table_touch"]}
    return [scored_span(f"{object_name}/{path.stem}", trial, events, transition,
                        armed_from_s=armed[transition], physical_s=times[transition])
            for transition in ("reach_load", "load_lift", "place_unload")]


def _fmt(value):
    return "–" if value is None else f"{1000 * value:.0f} ms"


TITLE = "# Eq. 3 thresholds of the taxel_aware controller's ensemble events"  # OUT's first line


def main(argv=None) -> int:
    parser = script_parser("choose_ensemble_thresholds", __doc__)
    parser.add_input("logs", type=pathlib.Path, what="logs folder",
                     advice=ENSEMBLE_LOGS_ADVICE)
    parser.add_output("out", type=pathlib.Path, title=TITLE)
    parser.add_number("--runs", type=integer_option, nargs="+", default=[5, 6, 7],
                      allowed=Range(low=0, why="the index of a run record_ensemble_events "
                                               "wrote"))
    parser.add_input("--events", default=str(package_events_dir()), what="--events folder",
                     advice=EVENTS_ADVICE)
    args = parser.parse_args(argv)
    spans = []
    for name in sorted(BUILTIN_OBJECTS):
        _, events = find_memorized_events(controller_events_folders(TaxelAwareControllerConfig(), args.events),
                                          name)
        for run in args.runs:
            path = args.logs / name / f"run{run}.npz"
            if not path.is_file():
                raise SystemExit(f"choose_ensemble_thresholds: {path} is missing; run "
                                 "analysis/record_ensemble_events.py first")
            spans += spans_of_log(path, name, events)
            print(f"scored {path}", flush=True)
    chosen = {t: choose_thresholds([s for s in spans if s.transition == t], SA_GRID, RA_GRID)
              for t in TRANSITIONS}
    lines = [TITLE + "\n",
             f"Chosen per transition on the held-out ensemble runs (seeds 1000000 + "
             f"{args.runs} of each object: {len(spans) // 3} spans per transition; the "
             "templates came from the other runs) by `analysis/choose_ensemble_thresholds.py`"
             " (rule: `recording/detection_quality.py`), and set as the hand's "
             "(gripper_hands.*Hand.ensemble_thresholds). Load-Lift is scored against "
             "the grip settled (both pads at 90 % of the grip), as the trial judge scores a "
             "closed-loop run; its event is cut at the script's start of the lift.\n",
             "| transition | SA > | RA > | detected | false | missed | median latency |",
             "|---|---|---|---|---|---|---|"]
    for t in TRANSITIONS:
        c = chosen[t]
        lines.append(f"| {t} | {c.sa_threshold:.2f} | {c.ra_threshold:.2f} | "
                     f"{c.detected}/{c.spans} | {c.false} | {c.missed} | "
                     f"{_fmt(c.median_latency_s)} |")
    lines += ["\nThe paper's thresholds (SA > 0.9, RA > 0.7) on the same spans:\n",
              "| transition | detected | false | missed | median latency |",
              "|---|---|---|---|---|"]
    for t in TRANSITIONS:
        p = rate_point([s for s in spans if s.transition == t], 0.9, 0.7)
        lines.append(f"| {t} | {p.detected}/{p.spans} | {p.false} | {p.missed} | "
                     f"{_fmt(p.median_latency_s)} |")
    for t in TRANSITIONS:
        c = chosen[t]
        mine = [s for s in spans if s.transition == t]
        lines += [f"\n## ROC-style, {t}: thresholds scaled from the chosen "
                  f"{c.sa_threshold:.2f} / {c.ra_threshold:.2f}\n",
                  "| scale | SA | RA | detection rate | false-trigger rate | median latency |",
                  "|---|---|---|---|---|---|"]
        for scale, p in zip(ROC_SCALES, roc_curve(mine, ROC_SCALES,
                                                  base=(c.sa_threshold, c.ra_threshold))):
            lines.append(f"| {scale:.2f} | {p.sa_threshold:.3f} | {p.ra_threshold:.3f} | "
                         f"{p.detection_rate:.2f} | {p.false_rate:.2f} | "
                         f"{_fmt(p.median_latency_s)} |")
    write_report(args.out, "\n".join(lines) + "\n", script="choose_ensemble_thresholds")
    print({t: (c.sa_threshold, c.ra_threshold) for t, c in chosen.items()}, f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "choose_ensemble_thresholds"))
