"""`tegrasp plot`: the paper's figures from a trial log or a sweep's results folder.

  tegrasp plot events                  every memorized event, each channel (Fig. 5c)
  tegrasp plot signals LOG             a trial's raw and processed signals (Fig. 5a-b)
  tegrasp plot trial LOG               a trial's SA and RA with its states (Fig. 9)
  tegrasp plot avoid LOG               a trial's reaction to a hit in Hold (Fig. 10)
  tegrasp plot table1 RESULTS          Table I of a sweep against the paper's
  tegrasp plot latency RESULTS         detection latencies per transition and controller
  tegrasp plot success-maps RESULTS    success per marker position
LOG is a trial.npz written by `tegrasp trial` or `tegrasp demo`; RESULTS the --out folder
of `tegrasp sweep` (e.g. analysis/results_seed0). --format png|pdf|svg, or --out FILE whose
suffix names the format."""

import argparse
import logging
import os
import pathlib

from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.commands.events_option import check_events_folder
from tegrasp_drake.figures.figure_files import (FIGURE_FORMATS, MAX_LINES_TOLD_APART,
                                                figure_replace_problem)
from tegrasp_drake.rig.files import output_file_problem
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.echo import shown

logger = logging.getLogger(__name__)

TRIAL_FIGURES = ("signals", "trial", "avoid")
DEFAULT_STEMS = {"events": "memorized_events", "signals": "trial_signals",
                 "trial": "trial_states", "avoid": "avoid", "table1": "table1_vs_paper",
                 "latency": "latency", "success-maps": "success_maps"}


EPILOG = """\
examples:
  tegrasp plot events                            # Fig. 5c: out/memorized_events.png
  tegrasp plot trial out/demo/trial.npz --out out/demo/fig9.png
  tegrasp plot avoid out/hit/trial.npz           # Fig. 10: the reaction to a hit
  tegrasp plot table1 analysis/results_seed0 --format pdf

out/hit/trial.npz: `tegrasp trial --set disturbance.hit_time_s=7.0 --out out/hit`."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "plot", help="figures: events (Fig. 5c), signals (Fig. 5a-b), trial (Fig. 9), avoid "
                     "(Fig. 10), table1 (Table I), latency, success-maps",
        description=__doc__, epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", choices=tuple(DEFAULT_STEMS))
    parser.add_argument("source", nargs="?", metavar="LOG|RESULTS",
                        help="trial log (trial.npz) for signals, trial and avoid; sweep "
                             "results folder for table1, latency and success-maps")
    parser.add_argument("--events", default=None, metavar="DIR",
                        help="events folder (default: $TEGRASP_EVENTS_DIR or "
                        "~/.local/share/tegrasp/events, then the package's)")
    parser.add_argument("--object", action="append", default=None, metavar="NAME",
                        help="events: plot this object's memorized events (repeat for more; "
                        f"at most {MAX_LINES_TOLD_APART} in a figure; default: every "
                        "object's)")
    parser.add_argument("--format", choices=FIGURE_FORMATS, default=None,
                        help="file format (default: --out's suffix, else png)")
    parser.add_argument("--out", default=None,
                        help="figure file (default: out/<figure>.<format>)")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace an existing figure at --out (a file that is not a "
                             "figure of its format is never replaced)")
    parser.set_defaults(func=run, usage_error=parser.error)


def output_path(args) -> pathlib.Path:
    """--out, or out/<figure>.<format> (the command's own, replaced by the next plot of that
    figure); exits when --out's suffix and --format disagree, or when --out (or the default)
    exists and is not a figure of its format, or is one and --overwrite is not given
    (figure_replace_problem)."""
    if args.out is None:
        out = pathlib.Path("out") / f"{DEFAULT_STEMS[args.what]}.{args.format or 'png'}"
        problem = figure_replace_problem(out)
        if problem:
            raise SystemExit(f"{ERROR_LEAD}{out} {problem}")
        return out
    out = pathlib.Path(args.out)
    suffix = out.suffix.lstrip(".").lower()
    if suffix not in FIGURE_FORMATS:
        raise SystemExit(f"{ERROR_LEAD}--out {out}: the file name must end in one of "
                         f"{', '.join('.' + f for f in FIGURE_FORMATS)}")
    if args.format is not None and args.format != suffix:
        raise SystemExit(f"{ERROR_LEAD}--out {out} is a .{suffix} file but --format is "
                         f"{args.format}; give one of them")
    problem = output_file_problem(out) or figure_replace_problem(
        out, overwrite=getattr(args, "overwrite", False))
    if problem:
        raise SystemExit(f"{ERROR_LEAD}--out {out} {problem}")
    return out


def _plot_events(args, out) -> str:
    from tegrasp_drake.events import MemorizedEventError, load_all_memorized_events
    from tegrasp_drake.events.event_file import has_index
    from tegrasp_drake.figures.events import plot_memorized_events
    from tegrasp_drake.scenario.scenario_events import check_recorded_runs
    check_events_folder(args.events)
    events = {}
    try:
        # The first folder that has an object's events wins (the user's before the package's).
        # A folder is passed over only when nothing is at its index path (has_index): an
        # index there that cannot be read is refused, from --events or the environment alike.
        for folder in reversed(paths.events_search_path(args.events)):
            if has_index(folder) or args.events:
                loaded = load_all_memorized_events(folder)
                for object_events in loaded.values():
                    check_recorded_runs(folder, object_events)
                logger.debug(f"plot events: {len(loaded)} memorized events from {folder}")
                events.update(loaded)
    except MemorizedEventError as e:
        raise SystemExit(f"{ERROR_LEAD}{e}") from None
    return str(plot_memorized_events(_objects_picked(args, events), out))


def _objects_picked(args, events: dict) -> dict:
    """The events of the objects --object names (each must have events), else of every
    object; exits when they are more than a figure tells apart (MAX_LINES_TOLD_APART)."""
    from tegrasp_drake.rig.echo import shorten
    where = args.events or "the events folders"
    if args.object:
        unknown = [name for name in args.object if name not in events]
        if unknown:
            raise SystemExit(f"{ERROR_LEAD}--object {shown(unknown[0])}: no memorized events "
                             f"of that object in {where}; its objects: "
                             f"{shorten(', '.join(sorted(events)) or 'none', 200)}")
        events = {name: events[name] for name in dict.fromkeys(args.object)}
    if len(events) > MAX_LINES_TOLD_APART:
        names = sorted(events)
        raise SystemExit(
            f"{ERROR_LEAD}{where} holds the memorized events of {len(events)} objects "
            f"({shorten(', '.join(names), 120)}); a figure tells at most "
            f"{MAX_LINES_TOLD_APART} apart: pick them with --object NAME (repeatable), "
            f"e.g. --object {names[0]} --object {names[1]}")
    return events


def _require_source(args, what: str) -> None:
    """A usage error (exit 2) when `tegrasp plot WHAT` was given no LOG|RESULTS."""
    if not args.source:
        args.usage_error(f"`tegrasp plot {args.what}` needs LOG|RESULTS, {what}")


def _plot_trial(args, out) -> str:
    from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
    _require_source(args, "a trial log (e.g. out/demo/trial.npz from `tegrasp demo`)")
    try:
        log = load_trial_log(args.source)
    except TrialLogError as e:
        raise SystemExit(f"{ERROR_LEAD}{e}") from None
    logger.debug(f"plot {args.what}: {args.source}: {log.t_sa.size} slow-adapting and "
                 f"{log.t_ra.size} fast-adapting tactile samples, "
                 f"{len(log.meta.get('transitions', ()))} transitions")
    if args.what == "signals":
        from tegrasp_drake.figures.signals import plot_trial_signals
        return plot_trial_signals(log, out)
    if args.what == "trial":
        from tegrasp_drake.figures.states import plot_trial_states
        return plot_trial_states(log, out)
    from tegrasp_drake.figures.avoid import (NoAvoidError, logged_hit_rule,
                                             plot_avoid_reaction)
    try:
        return plot_avoid_reaction(log, out, hit_rule=logged_hit_rule(log))
    except NoAvoidError as e:
        raise SystemExit(f"{ERROR_LEAD}{args.source}: {e}") from None


def _plot_sweep(args, out) -> str:
    from tegrasp_drake.rig.files import is_folder
    from tegrasp_drake.sweep import load_records
    _require_source(args, "a sweep's results folder (e.g. analysis/results_seed0)")
    if not is_folder(args.source):  # UserPathError when it cannot be read
        raise SystemExit(f"{ERROR_LEAD}no trial records under {args.source}/trials "
                         f"({args.source} is not a folder; give the --out folder of "
                         "`tegrasp sweep`)")
    trials = pathlib.Path(args.source) / "trials"
    if not is_folder(trials) and os.path.lexists(trials):
        raise SystemExit(f"{ERROR_LEAD}{trials} is not a folder of trial records (a "
                         "sweep writes its records there); give the --out folder of "
                         "`tegrasp sweep`")
    loaded = load_records(args.source)
    problem = loaded.table_problem(args.source)
    if problem:
        raise SystemExit(f"{ERROR_LEAD}{problem}")
    records = list(loaded.records.values())
    logger.debug(f"plot {args.what}: {len(records)} trial records from {args.source}")
    if not records:
        raise SystemExit(f"{ERROR_LEAD}no trial records under {args.source}/trials "
                         "(run `tegrasp sweep --out FOLDER` first)")
    from tegrasp_drake.figures.latency import plot_latency_distributions
    from tegrasp_drake.figures.sweep import write_success_maps
    from tegrasp_drake.figures.table1 import plot_table1
    try:
        if args.what == "table1":
            return plot_table1(records, out)
        if args.what == "latency":
            return plot_latency_distributions(records, out)
        return str(write_success_maps(records, out.parent, out.name))
    except ValueError as e:
        raise SystemExit(f"{ERROR_LEAD}{args.source}: {e}") from None


def run(args) -> int:
    if args.what == "events" and args.source is not None:  # a command line that does not parse
        args.usage_error(f"`tegrasp plot events` takes no LOG or RESULTS (got "
                         f"{shown(args.source)}); give the events folder as --events DIR")
    if args.object and args.what != "events":
        args.usage_error(f"--object picks the objects of `tegrasp plot events`, not of "
                         f"`tegrasp plot {args.what}`")
    out = output_path(args)
    logger.info(f"plot {args.what}: reading "
                f"{args.source or args.events or 'the memorized events'}, writing {out}")
    if args.what == "events":
        written = _plot_events(args, out)
    elif args.what in TRIAL_FIGURES:
        from tegrasp_drake.rig.typed_yaml import ConfigError
        try:
            written = _plot_trial(args, out)
        except ConfigError as e:  # the log's scenario, damaged or edited
            raise SystemExit(f"{ERROR_LEAD}trial log '{args.source}': {e}") from None
    else:
        written = _plot_sweep(args, out)
    print(written)
    logger.info(f"plot {args.what}: wrote {written}")
    return 0
