"""Judge a sweep's trials again from their logs with the current judge
(scenario/trial_judge.judge_trial), e.g. after the judge changed; writes a results folder of
updated records beside the original (records' results replaced, nothing re-simulated).

    python analysis/rejudge_from_logs.py RESULTS LOGS OUT

RESULTS: a sweep's results folder; LOGS: its `tegrasp sweep --logs` folder; OUT: the new
results folder (created; must not exist). A record whose log is missing is copied unchanged
and named on stderr; RESULTS without records, or LOGS holding none of their logs, is refused
(exit 1) before OUT is made, as is a log that is not its record's trial (another
controller, object, seed or placement: logs swapped or renamed), naming the log, the record
and the field.
"""

import json
import pathlib
import sys

from tegrasp_drake.commands.script_output import (SWEEP_LOGS_ADVICE, load_sweep_records,
                                                  refuse_unusable_input, run_script,
                                                  script_parser)
from tegrasp_drake.control.grasp_modes import Transition
from tegrasp_drake.sweep.records import TRIALS_FOLDER, make_record, write_record
from tegrasp_drake.sweep.trial_function import (load_record_log, scenario_from_trial_spec,
                                                trial_log_name)
from tegrasp_drake.scenario.trial_judge import judge_trial
from tegrasp_drake.scenario.moved_keys import migrate_stored_trial


def main(argv=None) -> int:
    parser = script_parser("rejudge_from_logs", __doc__)
    parser.add_argument("results", type=pathlib.Path)
    parser.add_argument("logs", type=pathlib.Path)
    parser.add_argument("out", type=pathlib.Path)
    args = parser.parse_args(argv)
    loaded = load_sweep_records("rejudge_from_logs", args.results)  # the input first
    if args.out.exists():
        raise SystemExit(f"rejudge_from_logs: {args.out} exists; choose a new folder")
    logs = {trial_id: args.logs / trial_log_name(record["trial"], record.get("events"))
            for trial_id, record in loaded.records.items() if record.get("result") is not None}
    if not logs:
        raise SystemExit(f"rejudge_from_logs: {args.results} holds no trial record with a "
                         "result (trials/*.json); give the --out folder of a `tegrasp sweep`")
    refuse_unusable_input("rejudge_from_logs", args.logs, "logs folder", SWEEP_LOGS_ADVICE)
    if not any(path.is_file() for path in logs.values()):
        raise SystemExit(f"rejudge_from_logs: {args.logs} holds none of the {len(logs)} "
                         f"records' logs (e.g. {next(iter(logs.values())).name}); give the "
                         "--logs folder of the sweep that wrote the records")
    for trial_id, path in logs.items():  # each log its record's trial's, before OUT is made
        if path.is_file():
            load_record_log(path, loaded.records[trial_id], rejudge=False)
    (args.out / TRIALS_FOLDER).mkdir(parents=True)
    changed = 0
    for trial_id, record in loaded.records.items():
        path = logs.get(trial_id)
        result = record.get("result")
        if result is not None and path.is_file():
            scenario = scenario_from_trial_spec(migrate_stored_trial(record["trial"]))
            transitions = [Transition.from_dict(t) for t in result["transitions"]]
            judged = judge_trial(load_record_log(path, record, rejudge=False), transitions,
                                 scenario)
            new = dict(result, **judged)
            changed += int(json.dumps(new, sort_keys=True, default=str)
                           != json.dumps(result, sort_keys=True, default=str))
            record = make_record(record["trial"], result=new, events=record.get("events"))
        elif result is not None:
            print(f"rejudge_from_logs: no log {path}; {trial_id} copied unchanged",
                  file=sys.stderr)
        write_record(args.out, record)
    without_log = sum(not path.is_file() for path in logs.values())
    print(f"wrote {args.out}; {len(logs) - without_log} results re-judged, {changed} changed; "
          f"{without_log} without a log copied unchanged")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "rejudge_from_logs"))
