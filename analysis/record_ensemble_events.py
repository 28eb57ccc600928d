"""Record the taxel_aware controller's ensemble events (recording/ensemble_events.py).

    python analysis/record_ensemble_events.py LOGS_DIR [--runs 8] [--template-runs 5]
        [--workers 2] [--events events]

Runs `--runs` randomised ideal grasps of each built-in object (seeds 1_000_000 + run),
saves each log to LOGS_DIR/<object>/run<k>.npz (a log already there is reused), combines the first `--template-runs` into
the events in EVENTS/ensemble (the mean rule), and leaves the other runs' logs for choosing
the thresholds (analysis/choose_ensemble_thresholds.py), apart from the sweeps that judge.
"""

import argparse
import pathlib
import sys
from concurrent.futures import ProcessPoolExecutor

from tegrasp_drake.events.memorized_event import save_memorized_events
from tegrasp_drake.recording.ensemble_events import (ENSEMBLE_FOLDER, combine_runs,
                                                       ensemble_scenario, record_ensemble_run,
                                                       run_events)
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS


def _one(job):
    object_name, run, path = job
    if path.is_file():  # recorded before: cut its events again, without simulating
        from tegrasp_drake.scenario.scenario import LoadScenario
        from tegrasp_drake.scenario.trial_log_file import load_trial_log
        return object_name, run, run_events(load_trial_log(path),
                                            ensemble_scenario(object_name, run), object_name,
                                            LoadScenario(name=object_name).object)
    return object_name, run, record_ensemble_run(object_name, run, log_path=path)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("logs", type=pathlib.Path)
    parser.add_argument("--runs", type=int, default=8)
    parser.add_argument("--template-runs", type=int, default=5)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--events", type=pathlib.Path, default=pathlib.Path("events"))
    args = parser.parse_args(argv)
    if not 0 < args.template_runs <= args.runs:
        raise SystemExit("record_ensemble_events: --template-runs must be 1..--runs")
    jobs = [(name, run, args.logs / name / f"run{run}.npz")
            for name in sorted(BUILTIN_OBJECTS) for run in range(args.runs)]
    runs = {}
    with ProcessPoolExecutor(args.workers) as pool:
        for name, run, events in pool.map(_one, jobs):
            runs[(name, run)] = events
            print(f"{name} run {run} done", flush=True)
    combined = []
    for name in sorted(BUILTIN_OBJECTS):
        members = [runs[(name, run)] for run in range(args.template_runs)]
        combined += list(combine_runs(
            members, scenario_note=f"ensemble of ideal grasps of {name}, seeds "
            f"1000000..{1000000 + args.template_runs - 1}").values())
    written = save_memorized_events(args.events / ENSEMBLE_FOLDER, combined)
    print(f"wrote {len(written)} files to {args.events / ENSEMBLE_FOLDER}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
