"""`tegrasp replay LOG`: what a hardware run's log holds, and the event matcher re-run on
its tactile data offline (runs/hardware_log_replay.py). Exit codes: 0 replayed; 1 nothing to
replay; 3 the log is damaged (the readable part was replayed; stderr says what was lost)."""

import argparse
import json
import sys

from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.commands.events_option import check_events_folder


EPILOG = """\
examples:
  tegrasp replay out/run.lcmlog                  # what the log holds; the matcher, offline
  tegrasp replay out/run.lcmlog --events my_events --object box --json"""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "replay", help="re-run the event matcher offline on the LCM log of `tegrasp hardware`",
        description=__doc__, epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("log", metavar="LOG")
    parser.add_argument("--events", default=None,
                        help="memorized events folder (default: the one the run used, which "
                        "must still be there; for a log naming none, yours, then the "
                        "package's)")
    parser.add_argument("--object", default=None,
                        help="whose memorized events (default: the run's object)")
    parser.add_argument("--json", action="store_true")
    parser.set_defaults(func=run)


def _fmt(value):
    return "-" if value is None else f"{value:8.3f}"


def _logged(text: str) -> str:
    """A text from the log as the replay prints it: escaped to one line and cut (echo)."""
    from tegrasp_drake.rig.echo import shorten
    from tegrasp_drake.rig.files import one_line
    return shorten(one_line(text))


def run(args) -> int:
    from tegrasp_drake.events import MemorizedEventError
    from tegrasp_drake.runs.hardware_log_reader import RunLogError
    from tegrasp_drake.hardware.device_log_messages import RUN_INFO_CHANNEL
    from tegrasp_drake.runs.hardware_log_replay import replay_run_log
    check_events_folder(args.events)
    try:
        replay = replay_run_log(args.log, object_name=args.object, events_dir=args.events)
    except (RunLogError, MemorizedEventError, ValueError) as e:
        raise SystemExit(f"{ERROR_LEAD}{e}") from None
    summary = replay.summary()
    damaged = replay.log.damage_text()
    if damaged:
        print(f"tegrasp: warning: {damaged}", file=sys.stderr)
    runs_object = replay.log.object_name
    if runs_object and runs_object != replay.object_name:
        print(f"tegrasp: warning: the run was of the object '{runs_object}' (its "
              f"{RUN_INFO_CHANNEL}); its tactile data are matched against "
              f"'{replay.object_name}''s events, as --object asks", file=sys.stderr)
    if args.json:
        print(json.dumps(dict(summary, damage=replay.log.damage), sort_keys=True))
        return 3 if damaged else 0
    log = replay.log
    events_of = (f"{replay.object_name}'s events (the run's object: {runs_object})"
                 if runs_object and runs_object != replay.object_name else replay.object_name)
    print(f"{summary['log']}: controller {summary['controller']}, object "
          f"{events_of}, {summary['tactile_s']:.2f} s of tactile data "
          f"({summary['stale_ticks']} stale ticks)")
    print("messages: " + ", ".join(f"{_logged(c)} {n}"
                                   for c, n in sorted(log.message_counts.items())))
    for t in log.transitions:
        print(f"  [{t['t']:8.3f} s] {t['from']} -> {t['to']}  ({t['trigger']})")
    for f in summary["faults"]:
        print(f"  [{f['t']:8.3f} s] FAULT {f['device']}: {f['kind']}: "
              f"{_logged(f['description'])} (since {f['since']:.3f} s)")
    print("offline matcher (expected event from the logged transitions):")
    print("  transition      expected from  transition   match    scores at match (or max)")
    for r in replay.transitions:
        print(f"  {r.transition:14s}  {_fmt(r.mode_entered)}  {_fmt(r.logged_time)}  "
              f"{_fmt(r.match_time)}  " + " ".join(f"{s:5.2f}" for s in r.best_scores))
    print("offline matcher with an EventSequencer (events expected in grasp order):")
    for transition, fired in replay.in_sequence.fire_times.items():
        print(f"  {transition:14s}  fired at {_fmt(fired)}")
    return 3 if damaged else 0
