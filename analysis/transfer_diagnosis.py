"""Which channel's Eq. 3 score falls short, per transition, in trials run with events
memorized elsewhere (docs/transfer.md, "What breaks transfer"; the scoring is
tegrasp_drake/transfer/diagnosis.py).

    python analysis/transfer_diagnosis.py EVENTS_DIR RUN_DIR... [--ra-envelope-hz F]

Each RUN_DIR is a `tegrasp trial --out` folder (trial.npz, result.json); EVENTS_DIR the
events folder its trial read. Prints one JSON line per run: per transition, "best" (each
channel's highest score while its mode waited), "together" (the four scores at the tick
where all four came nearest their thresholds, at "at_s") and "match". --ra-envelope-hz
scores with the RA envelope on both sides (events/ra_envelope.py).
"""

import json
import pathlib
import sys

from tegrasp_drake.rig.number_text import number_option
from tegrasp_drake.commands.script_output import EVENTS_ADVICE, run_script, script_parser
from tegrasp_drake.rig.event_matching import EventMatchingConfig
from tegrasp_drake.rig.ranges import field_range
from tegrasp_drake.events.events_folder import load_memorized_events
from tegrasp_drake.events.replay import tactile_trial_from_log
from tegrasp_drake.scenario.trial_log_file import load_trial_log
from tegrasp_drake.transfer.diagnosis import diagnose_trial


def diagnose(run: pathlib.Path, events_dir, ra_envelope_hz: float) -> dict:
    trial = tactile_trial_from_log(load_trial_log(run / "trial.npz"))  # SA at the taxel times
    result = json.loads((run / "result.json").read_text())
    events = load_memorized_events(events_dir, result["object"])
    report = diagnose_trial(trial, result["transitions"], events,
                            ra_envelope_hz=ra_envelope_hz)
    return {"run": run.name, "final_mode": result["final_mode"],
            "transitions": {name: d.to_dict() for name, d in report.items()}}


def main(argv=None) -> int:
    parser = script_parser("transfer_diagnosis", __doc__)
    parser.add_input("events", help="the events folder the trials read",
                     what="events folder", advice=EVENTS_ADVICE)
    parser.add_input("runs", nargs="+", help="trial folders (tegrasp trial --out)",
                     what="trial folder", advice="give folders that `tegrasp trial --out` wrote")
    parser.add_number("--ra-envelope-hz", type=number_option, default=0.0,
                      allowed=field_range(EventMatchingConfig, "ra_envelope_hz"))
    args = parser.parse_args(argv)
    for run in map(pathlib.Path, args.runs):
        if not (run / "trial.npz").is_file() or not (run / "result.json").is_file():
            raise SystemExit(f"transfer_diagnosis: error: {run} holds no trial.npz and "
                             "result.json (give folders that `tegrasp trial --out` wrote)")
        print(json.dumps(diagnose(run, args.events, args.ra_envelope_hz)))
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "transfer_diagnosis"))
