"""Count the memorized events a sweep's controller waited for in vain, and why: the paper's
"very weak dynamic stimuli" that the piezoelectric film failed to pick up (Sec. V) among
them (tegrasp_drake/events/missed_waits.py, sweep/missed_event_report.py).

    python analysis/weak_stimuli.py RESULTS LOGS [--events DIR] [--out OUT.md]
        [--controller memorized]

RESULTS: a sweep's results folder (its records under trials/); LOGS: the same sweep's
`tegrasp sweep --logs` folder; --events: the memorized events folder the sweep ran with
(as `tegrasp sweep --events`); --out: also write the report there. Every wait of a
controller trial that ended on its event's timeout (Re-Reach after "no Reach-Load event
...", "no Load-Lift event within ...", "no Place-Unload event after the arm stopped") is
replayed from the log through Eq. 3 and classed:

  weak dynamic stimulus  both SA channels passed their threshold at some tick of the wait,
                         but at every such tick an RA channel stayed below its threshold
  SA did not match       no tick of the wait where both SA channels passed
  matched in replay      the replay matched where the run did not (other events/settings)

The report lists each wait (scores, each RA window's peak in m/s^2, noise sigmas and
converter codes) and the counts per object and class.
"""

import pathlib
import sys

from tegrasp_drake.sweep.missed_event_report import record_has_waits, report_markdown, sweep_misses
from tegrasp_drake.commands.script_output import (SWEEP_LOGS_ADVICE, SWEEP_RESULTS_ADVICE,
                                                  load_sweep_records, run_script,
                                                  script_parser, write_report)


def title(results: pathlib.Path) -> str:
    """The report's heading: its first line is `# ` and it."""
    return f"Missed memorized events of `{results.name}`"


def main(argv=None) -> int:
    parser = script_parser("weak_stimuli", __doc__)
    parser.add_input("results", type=pathlib.Path, what="results folder",
                     advice=SWEEP_RESULTS_ADVICE, help="a sweep's results folder")
    parser.add_input("logs", type=pathlib.Path, what="logs folder", advice=SWEEP_LOGS_ADVICE,
                     help="the sweep's --logs folder")
    parser.add_argument("--events", type=pathlib.Path, default=None,
                        help="the memorized events folder the sweep ran with")
    parser.add_output("--out", type=pathlib.Path, default=None, help="write the report here",
                      title=lambda args: f"# {title(args.results)}")
    parser.add_argument("--controller", default="memorized",
                        help="the event-triggered controller whose trials to look at")
    args = parser.parse_args(argv)
    loaded = load_sweep_records("weak_stimuli", args.results)
    if not loaded.records:
        raise SystemExit(f"weak_stimuli: {args.results} holds no trial records (trials/*.json)")
    try:
        misses, without_log, trials = sweep_misses(
            loaded.records, args.logs, controller=args.controller, events_dir=args.events)
    except ValueError as error:  # a log, events folder or record the replay cannot use
        raise SystemExit(f"weak_stimuli: {error}") from None
    if not trials:
        raise SystemExit(f"weak_stimuli: {args.results} holds no '{args.controller}' trials "
                         "that ran; see --controller")
    if without_log and not misses and len(without_log) == sum(
            record_has_waits(record, args.controller) for record in loaded.records.values()
            if record.get("status") == "ok" and record["trial"]["controller"] == args.controller):
        raise SystemExit(f"weak_stimuli: {args.logs} holds none of the logs of the "
                         f"{len(without_log)} trials that waited for an event; give the "
                         "--logs folder of the sweep that wrote the records")
    text = report_markdown(misses, without_log, trials, args.controller,
                           title(args.results))
    for trial_id in without_log:
        print(f"weak_stimuli: no log for {trial_id} in {args.logs}; not counted",
              file=sys.stderr)
    if args.out is not None:
        write_report(args.out, text, script="weak_stimuli")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "weak_stimuli"))
