"""`tegrasp plot`: figures.

  tegrasp plot events            every memorized event, each channel (paper Fig. 5c)
  tegrasp plot trial LOG         a trial's SA and RA with its states (Fig. 9)
  tegrasp plot avoid LOG         a trial's reaction to a hit in Hold (Fig. 10)
LOG is a trial.npz written by `tegrasp trial` or `tegrasp demo`.
"""

import pathlib

from tegrasp_drake.rig import paths

DEFAULT_OUT = {"events": "out/memorized_events.png", "trial": "out/trial_states.png",
               "avoid": "out/avoid.png"}


def register(subparsers) -> None:
    parser = subparsers.add_parser("plot", help="figures: events (Fig. 5c), trial (Fig. 9), "
                                                "avoid (Fig. 10)")
    parser.add_argument("what", choices=tuple(DEFAULT_OUT))
    parser.add_argument("log", nargs="?", help="trial log (trial.npz) for trial and avoid")
    parser.add_argument("--events", default=None, metavar="DIR",
                        help="events folder (default: $TEGRASP_EVENTS_DIR or "
                        "~/.local/share/tegrasp/events, then the package's)")
    parser.add_argument("--out", default=None, help="PNG to write")
    parser.set_defaults(func=run)


def _plot_events(args, out) -> str:
    from tegrasp_drake.events import MemorizedEventError, load_all_memorized_events
    from tegrasp_drake.experiments.figures.events import plot_memorized_events
    events = {}
    try:
        # The first folder that has an object's events wins (the user's before the package's).
        for folder in reversed(paths.events_search_path(args.events)):
            if (folder / "index.json").is_file() or args.events:
                events.update(load_all_memorized_events(folder))
    except MemorizedEventError as e:
        raise SystemExit(f"tegrasp: error: {e}") from None
    return plot_memorized_events(events, out)


def _plot_trial(args, out) -> str:
    from tegrasp_drake.experiments.figures.trial import plot_avoid_reaction, plot_trial_states
    from tegrasp_drake.experiments.trial_log import TrialLogError, load_trial_log
    if not args.log:
        raise SystemExit(f"tegrasp: error: `tegrasp plot {args.what}` needs a trial log "
                         "(e.g. out/trial/trial.npz from `tegrasp trial`)")
    try:
        log = load_trial_log(args.log)
    except TrialLogError as e:
        raise SystemExit(f"tegrasp: error: {e}") from None
    if args.what == "trial":
        return plot_trial_states(log, out)
    from tegrasp_drake.experiments.scenario import Scenario
    from pydrake.common.yaml import yaml_load_typed
    scenario = yaml_load_typed(schema=Scenario, data=log.meta["scenario"])
    try:
        return plot_avoid_reaction(log, out, hit_threshold=scenario.controller.hit_ra_mps2)
    except ValueError as e:
        raise SystemExit(f"tegrasp: error: {args.log}: {e}") from None


def run(args) -> int:
    out = pathlib.Path(args.out or DEFAULT_OUT[args.what])
    out.parent.mkdir(parents=True, exist_ok=True)
    print(_plot_events(args, out) if args.what == "events" else _plot_trial(args, out))
    return 0
