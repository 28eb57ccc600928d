"""Record the memorized corrective events (recording/corrective_events.py).

    python analysis/record_corrective_events.py LOGS_DIR [--object box] [--workers 2]
        [--events events]

Simulates each of CORRECTIVE_RUNS on the object as an open-loop grasp, only as long as its
situation needs (a hit run to the end of the script's Hold, a slip run to the end of its
Lift), saves each log to LOGS_DIR/<object>/<label>.npz (a log already there is reused),
and writes the mean of the template runs of each corrective transition to
EVENTS/corrective/. The held-out runs' logs are for analysis/choose_corrective_thresholds.py.
"""

import argparse
import pathlib
from concurrent.futures import ProcessPoolExecutor

from tegrasp_drake.events.memorized_event import save_memorized_events
from tegrasp_drake.events.transitions import CORRECTIVE_TRANSITIONS
from tegrasp_drake.recording.corrective_events import (
    CORRECTIVE_FOLDER, CORRECTIVE_RUNS, combine_corrective_runs, corrective_scenario,
    run_corrective_event)

# Simulated time of a run [s]: the script's Hold ends at 8.6 s, its Lift at 5.6 s
# (scripted_grasp.plan_scripted_grasp with the default grasp timing).
RUN_DURATION_S = {"hold_avoid": 8.7, "lift_load": 6.0}


def log_path(logs: pathlib.Path, object_name: str, run) -> pathlib.Path:
    return logs / object_name / (run.label.replace(" ", "_").replace(",", "") + ".npz")


def simulate(job):
    object_name, run, path = job
    from tegrasp_drake.runs.ideal_grasp import run_ideal_grasp
    from tegrasp_drake.scenario.trial_log_file import load_trial_log
    if not path.is_file():
        log, wall = run_ideal_grasp(corrective_scenario(object_name, run),
                                    duration=RUN_DURATION_S[run.transition])
        log.meta["corrective_run"] = run.label
        log.save(path)
        print(f"{object_name} '{run.label}': {wall:.0f} s wall", flush=True)
    return load_trial_log(path)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("logs", type=pathlib.Path)
    parser.add_argument("--object", default="box")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--events", type=pathlib.Path, default=pathlib.Path("events"))
    args = parser.parse_args(argv)
    from tegrasp_drake.scenario.scenario import LoadScenario
    jobs = [(args.object, run, log_path(args.logs, args.object, run)) for run in CORRECTIVE_RUNS]
    with ProcessPoolExecutor(args.workers) as pool:
        logs = list(pool.map(simulate, jobs))
    nominal = LoadScenario(name=args.object).object
    events = []
    for transition in CORRECTIVE_TRANSITIONS:
        members = [run_corrective_event(log, corrective_scenario(args.object, run), run,
                                        args.object, nominal)
                   for run, log in zip(CORRECTIVE_RUNS, logs)
                   if run.transition == transition and run.role == "template"]
        events.append(combine_corrective_runs(
            members, f"corrective template runs of {args.object} ({transition})"))
    written = save_memorized_events(args.events / CORRECTIVE_FOLDER, events,
                                    required=CORRECTIVE_TRANSITIONS)
    print(f"wrote {len(written)} files to {args.events / CORRECTIVE_FOLDER}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
