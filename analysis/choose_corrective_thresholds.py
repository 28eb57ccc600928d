"""Choose the memorized corrective events' Eq. 3 thresholds on held-out recorded runs, and
compare them with the heuristic triggers on the same spans (recording/corrective_
detection.py, recording/detection_quality.py).

    python analysis/choose_corrective_thresholds.py CORRECTIVE_LOGS ENSEMBLE_LOGS OUT.md
        [--object box] [--events events]

CORRECTIVE_LOGS: analysis/record_corrective_events.py's logs; ENSEMBLE_LOGS:
analysis/record_ensemble_events.py's (normal grasps: <object>/run<k>.npz). Chosen on: the
held-out corrective runs (role "held_out") as the situations, the ensemble's runs 5-7 as
normal grasps (none made a corrective template). Also reported, not used to choose: the
template runs and the ensemble's runs 0-4. The closed-loop trials that judge the choice
(tests/runs/test_corrective_trials.py) use other seeds.
"""

import pathlib
import sys

import numpy as np

from tegrasp_drake.commands.script_output import (CORRECTIVE_LOGS_ADVICE, ENSEMBLE_LOGS_ADVICE,
                                                  EVENTS_ADVICE, run_script, script_parser,
                                                  write_report)
from tegrasp_drake.rig.paths import package_events_dir
from tegrasp_drake.control.controller_config import GraspControllerConfig
from tegrasp_drake.events import tactile_trial_from_log
from tegrasp_drake.events.events_folder import load_memorized_events
from tegrasp_drake.events.transitions import CORRECTIVE_TRANSITIONS
from tegrasp_drake.recording.corrective_detection import (
    SituationSpan, choose_centred_thresholds, classify_first_firing, event_span,
    heuristic_hit_time, heuristic_slip_time, on_controller_ticks)
from tegrasp_drake.recording.corrective_events import (
    CORRECTIVE_FOLDER, CORRECTIVE_RUNS, HOLD_END_S, LIFT_END_S, LIFT_START_S,
    corrective_event_time, corrective_scenario)
from tegrasp_drake.recording.detection_quality import classify, rate_point
from tegrasp_drake.scenario.trial_log_file import load_trial_log

sys.path.insert(0, str(pathlib.Path(__file__).parent))
from record_corrective_events import log_path  # noqa: E402

GRID = np.round(np.concatenate([[-0.05], np.arange(0.0, 0.951, 0.05), [0.98]]), 3)
# The script's Lift and Hold (scripted_grasp.plan_scripted_grasp, default timing) [s].
LIFT_S, HOLD_S = (LIFT_START_S, LIFT_END_S), (LIFT_END_S, HOLD_END_S)
CONFIG = GraspControllerConfig()


def armed(transition):
    if transition == "lift_load":
        return LIFT_S
    return HOLD_S[0] + CONFIG.avoid.hit_refractory_s, HOLD_S[1]


def spans(args):
    """[(set name, SituationSpan, log)] of every run."""
    out = []
    for run in CORRECTIVE_RUNS:
        log = load_trial_log(log_path(args.corrective_logs, args.object, run))
        scenario = corrective_scenario(args.object, run)
        for transition in CORRECTIVE_TRANSITIONS:
            start, end = armed(transition)
            physical = (corrective_event_time(log, scenario, transition)
                        if transition == run.transition else None)
            if transition != run.transition and transition == "hold_avoid":
                continue  # a slip run's log ends with its Lift
            out.append((run.role, SituationSpan(f"{run.label}", transition, start,
                                                min(end, float(log.t_ra[-1])), physical), log))
    for k in range(8):
        log = load_trial_log(args.ensemble_logs / args.object / f"run{k}.npz")
        role = "held_out" if k >= 5 else "template"
        for transition in CORRECTIVE_TRANSITIONS:
            start, end = armed(transition)
            out.append((role + "_normal", SituationSpan(f"normal grasp {k}", transition,
                                                       start, end, None), log))
    return out


def tally(outcomes, situations: int):
    """detected / spans with the situation, false / all spans, latencies."""
    det = [o for o in outcomes if o.kind == "detected"]
    lat = [o.latency_s for o in det]
    return (f"{len(det)}/{situations}",
            f"{sum(o.kind == 'false' for o in outcomes)}/{len(outcomes)}",
            f"{1000 * np.median(lat):.0f} ms" if lat else "-",
            f"{1000 * max(lat):.0f} ms" if lat else "-")


def title(object_name: str) -> str:
    """The report's first line, by which an earlier report at OUT is known."""
    return f"# Memorized corrective triggers of `{object_name}`: thresholds and detection"


def main(argv=None) -> int:
    parser = script_parser("choose_corrective_thresholds", __doc__)
    parser.add_input("corrective_logs", type=pathlib.Path, what="corrective logs folder",
                     advice=CORRECTIVE_LOGS_ADVICE)
    parser.add_input("ensemble_logs", type=pathlib.Path, what="ensemble logs folder",
                     advice=ENSEMBLE_LOGS_ADVICE)
    parser.add_output("out", type=pathlib.Path, title=lambda args: title(args.object))
    parser.add_argument("--object", default="box")
    parser.add_input("--events", type=pathlib.Path, default=package_events_dir(),
                     what="--events folder", advice=EVENTS_ADVICE)
    args = parser.parse_args(argv)
    events = load_memorized_events(args.events / CORRECTIVE_FOLDER, args.object,
                                   required=CORRECTIVE_TRANSITIONS)
    rows = spans(args)
    scored = [(role, span, log, on_controller_ticks(
        event_span(tactile_trial_from_log(log), events, span), CONFIG.update_period_s))
              for role, span, log in rows]
    lines = [title(args.object),
             "", "Made by `python analysis/choose_corrective_thresholds.py` (its docstring: "
             "which runs choose, which only report). Detected: first firing from 10 ms "
             "before to 0.5 s after the physical event (a hit's start; the pads' first 1 mm "
             "of slip); false: earlier, or in a normal grasp's span; latency after the "
             "physical event. Scores are read at the state machine's 5 ms ticks. Rule: "
             "recording/corrective_detection.choose_centred_thresholds.", ""]
    chosen = {}
    for transition in CORRECTIVE_TRANSITIONS:
        choosing = [s for role, span, _, s in scored if span.transition == transition
                    and role in ("held_out", "held_out_normal")]
        situations = sum(s.physical_s != np.inf for s in choosing)
        try:
            best = choose_centred_thresholds(choosing, GRID, GRID)
            verdict = (f"**SA > {best.sa_threshold:g}, RA > {best.ra_threshold:g}** "
                       f"(detected {best.detected}, false {best.false}, missed {best.missed}, "
                       + (f"median latency {1000 * best.median_latency_s:.0f} ms)."
                          if best.median_latency_s is not None else "none detected)."))
        except ValueError:
            # No pair without a false trigger: show the pair with the fewest (then the most
            # detected, then the highest thresholds); the event is not usable as a trigger.
            points = [rate_point(choosing, sa, ra) for sa in GRID for ra in GRID]
            best = min(points, key=lambda p: (p.false, -p.detected,
                                              -(p.sa_threshold + p.ra_threshold)))
            verdict = (f"**no pair of the grid is free of false triggers**; the fewest: SA > "
                       f"{best.sa_threshold:g}, RA > {best.ra_threshold:g} with {best.false} "
                       f"false of {best.spans} spans. Not usable as a trigger.")
        chosen[transition] = best
        lines += [f"## {transition}", "",
                  f"Chosen on {len(choosing)} held-out spans ({situations} with the "
                  f"situation): {verdict}", "",
                  "| spans | trigger | detected | false (of all spans) | median latency | max latency |",
                  "|---|---|---|---|---|---|"]
        for roles, name in ((("held_out", "held_out_normal"), "held-out (chose)"),
                            (("template", "template_normal"), "template runs + normal 0-4")):
            part = [(span, log, s) for role, span, log, s in scored
                    if span.transition == transition and role in roles]
            memorized = [classify(s, best.sa_threshold, best.ra_threshold) for _, _, s in part]
            paper = [classify(s, 0.9, 0.7) for _, _, s in part]
            heuristic = []
            for span, log, _ in part:
                fire = (heuristic_slip_time(log, span, CONFIG.lift_load, 1000.0)
                        if transition == "lift_load"
                        else heuristic_hit_time(log, span, CONFIG.avoid.hit_ra_mps2))
                if fire is not None:  # read at the state machine's next tick
                    fire = CONFIG.update_period_s * np.ceil(fire / CONFIG.update_period_s - 1e-6)
                heuristic.append(classify_first_firing(fire, span.physical_s))
            for trigger, outcomes in (("memorized, chosen", memorized),
                                      ("memorized, paper's 0.9 / 0.7", paper),
                                      ("heuristic", heuristic)):
                situations = sum(span.physical_s is not None for span, _, _ in part)
                lines.append(f"| {name} | {trigger} | " + " | ".join(
                    map(str, tally(outcomes, situations))) + " |")
        lines += ["", "ROC-style (held-out spans; SA threshold fixed at the chosen one; "
                  "detected of the spans with the situation, false of all):", "",
                  "| RA > | detected | false | median latency |", "|---|---|---|---|"]
        for ra in GRID[::2]:
            p = rate_point(choosing, best.sa_threshold, ra)
            lat = (f"{1000 * p.median_latency_s:.0f} ms" if p.median_latency_s is not None
                   else "-")
            lines.append(f"| {ra:g} | {p.detected}/{situations} | {p.false}/{p.spans} | {lat} |")
        lines.append("")
        print(transition, best, flush=True)
    write_report(args.out, "\n".join(lines) + "\n", script="choose_corrective_thresholds")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "choose_corrective_thresholds"))
