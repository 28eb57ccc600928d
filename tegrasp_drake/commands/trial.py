"""`tegrasp trial`: one closed-loop grasp trial, its state timeline and its success.

`tegrasp demo` is this command on the default scenario with a figure (the README's main job).
Where the files go, and when an earlier run's are kept: commands/run_folder.py."""

import argparse
import contextlib
import json
import sys

from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.commands.progress import SimulatedTimeBar, progress_wanted
from tegrasp_drake.commands.run_folder import (REPLAY_KEY, RunFolderError, commit_run,
                                               new_run_folder, own_file_problem, staged_run)
from tegrasp_drake.commands.scenario_args import (add_events_argument, add_scenario_arguments,
                                                  controller_events, corrective_events,
                                                  scenario_from_arguments)
from tegrasp_drake.commands.viewer_args import (add_viewer_arguments, check_html_path,
                                                start_viewer, wait_for_viewer,
                                                write_replay_html)
from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controllers_help
from tegrasp_drake.figures.figure_files import FIGURE_FORMATS
from tegrasp_drake.rig.files import free_space_problem, os_error_text
from tegrasp_drake.rig.number_text import number_text

# [bytes per second of simulated time] what a trial's run folder takes, in the largest
# figure format. Measured on a 12.0 s box trial (memorized controller): trial.npz 0.40 MB,
# result.json 2 kB, its figures 0.91 MB as PNG, 0.39 MB as PDF, 1.85 MB as SVG: 2.26 MB at
# most, 0.19 MB/s (the log and the time-series figures grow with the time simulated);
# rounded up to 0.25 MB/s for the Avoid figure a hit adds. The free space asked before a
# trial simulates is this times its scenario's time limit (the longest it runs): its files
# are staged in full beside an earlier run's, which is kept until the new one is complete.
TRIAL_OUTPUT_BYTES_PER_S = 250_000


def trial_output_problem(out, scenario) -> str | None:
    """Why the disk holding the run folder `out` cannot take a trial of `scenario`'s files
    (rig.files.free_space_problem), or None; asked before the trial simulates."""
    from tegrasp_drake.scenario.grasp_diagram import scenario_time_limit
    limit_s = scenario_time_limit(scenario)
    return free_space_problem(
        out, round(TRIAL_OUTPUT_BYTES_PER_S * limit_s),
        f"its files (the trial log, the result and the figures of up to "
        f"{number_text(limit_s)} s simulated)")

DESCRIPTION = """\
One closed-loop grasp trial of any scenario: the object, its placement, the controller and
the seed, with any scenario field overridden. Prints each state transition (time, trigger
and the deciding rule's code, correlation scores), hold and unload success from the
simulation's ground truth, and the real-time factor. Writes a new run folder: trial.npz (the
log), result.json (what --json prints), states.png (Fig. 9) and signals.png (Fig. 5a-b)."""

EPILOG = """\
examples:
  tegrasp trial --set placement.offset=[0.0,0.015]    # misplaced along the stroke: Re-Reach
  tegrasp trial --set disturbance.hit_time_s=7.0 --out out/hit    # a hit in Hold: Avoid
  tegrasp trial --scenario-name thin_cylinder --controller heuristic --json

Without --out, each trial gets a new folder: out/trial, then out/trial-2, out/trial-3, ...
A folder given with --out that holds a run is refused unless --overwrite."""


def add_trial_arguments(parser, *, out_help: str) -> None:
    add_scenario_arguments(parser)
    add_events_argument(parser)
    parser.add_argument("--controller", choices=CONTROLLER_NAMES, default=None,
                        help=f"{controllers_help()}. Default: the scenario's controller; "
                             "another runs with the settings it shares with it and names "
                             "those it ignores")
    parser.add_argument("--out", metavar="DIR", default=None, help=out_help)
    parser.add_argument("--overwrite", action="store_true",
                        help="replace the run that the --out folder holds")
    parser.add_argument("--format", choices=FIGURE_FORMATS, default="png",
                        help="the figures' file format (default: %(default)s)")
    parser.add_argument("--json", action="store_true",
                        help="print the result as one JSON object (also in result.json)")
    add_viewer_arguments(parser)


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "trial", help="run one closed-loop grasp trial of any scenario and controller",
        description=DESCRIPTION, epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    add_trial_arguments(parser, out_help="folder for this run (default: out/trial, or the first "
                         "of out/trial-2, -3, ... that is not there yet)")
    parser.set_defaults(func=run, default_out="out/trial", replace_default_out=False)


def print_result(result) -> None:
    """The trial's result (a TrialResult) as text: its scene, its timeline, its success."""
    print(f"object {result.object} offset {number_text(result.offset_m)} m, controller "
          f"{result.controller}, seed {result.seed}")
    for transition in result.transitions:
        scores = None if transition.scores is None else list(transition.scores)
        extra = f"  scores {scores}" if transition.trigger.is_event else ""
        print(f"  {transition.t:7.3f} s  {transition.from_mode.label:>8} -> "
              f"{transition.to_mode.label:<8} [{transition.decided_by}] "
              f"{transition.reason}{extra}")
    print(f"hold {'SUCCESS' if result.hold_success else 'FAIL'} (held "
          f"{result.hold_time_s:.2f} s), unload "
          f"{'SUCCESS' if result.unload_success else 'FAIL'} (tilt "
          f"{result.final_tilt_deg:.1f} deg, {'released' if result.released else 'held'})"
          + (f"; failed: {result.failure}" if result.failure else ""))
    print(f"simulated {result.sim_time_s:.2f} s in {result.wall_time_s:.2f} s wall "
          f"(real-time factor {result.real_time_factor:.2f})")


def run(args) -> int:
    scenario = scenario_from_arguments(args, simulates="trial")
    events = controller_events(scenario, args.events)  # fails before anything is written
    corrective = corrective_events(scenario, args.events)
    html = check_html_path(args)
    problem = html and own_file_problem(html, args.out or args.default_out)
    if problem:
        raise SystemExit(f"{ERROR_LEAD}--html {html} {problem}")
    with contextlib.ExitStack() as stack:  # the folder made for a run that fails is removed
        try:
            out = stack.enter_context(new_run_folder(
                args.out, default=args.default_out, replace_default=args.replace_default_out,
                overwrite=args.overwrite))
        except RunFolderError as e:
            raise SystemExit(f"{ERROR_LEAD}{e}") from None
        problem = trial_output_problem(out, scenario)
        if problem:  # before the simulation, not after it (the folder made is removed)
            raise SystemExit(f"{ERROR_LEAD}--out {out} {problem}")
        from tegrasp_drake.figures.trial_figures import write_trial_figures
        from tegrasp_drake.runs.trial import SimulationFailedError, run_trial
        meshcat = start_viewer(args)
        try:
            with staged_run(out) as stage:
                with SimulatedTimeBar(args.command, enabled=progress_wanted(args)) as progress:
                    trial = run_trial(scenario, meshcat=meshcat, events=events,
                                      corrective_events=corrective, progress=progress)
                html_error = None
                if html is not None:
                    try:  # its own error: a failed replay names --html and keeps the run
                        replay_html = str(write_replay_html(meshcat, html))
                    except OSError as e:
                        html_error = (f"{ERROR_LEAD}--html {html}: cannot write it "
                                      f"({os_error_text(e)}); the run is kept in {out}")
                try:
                    result = dict(trial.to_dict(), log=str(trial.log.save(stage / "trial.npz")),
                                  **write_trial_figures(trial.log, stage, args.format))
                    if html is not None and html_error is None:
                        result[REPLAY_KEY] = replay_html
                    result = commit_run(stage, out, result)
                except OSError as e:
                    raise RunFolderError(f"cannot write the run to {out}: {os_error_text(e)}; "
                                         "an earlier run there is kept whole") from None
        except (RunFolderError, SimulationFailedError) as e:
            raise SystemExit(f"{ERROR_LEAD}{e}") from None
    if args.json:
        print(json.dumps(result, sort_keys=True), flush=True)
    else:
        print_result(trial)
        print(f"log {result['log']}, result {result['result']}, figures {result['figure']} "
              f"(Fig. 9), {result['signals_figure']} (Fig. 5a-b)"
              + (f", {result['contact_ra_figure']} (RA at first contact)"
                 if "contact_ra_figure" in result else "")
              + (f", {result['avoid_figure']} (Fig. 10)" if "avoid_figure" in result else ""))
        if REPLAY_KEY in result:
            print(f"replay {result[REPLAY_KEY]} (open it in a browser)")
    wait_for_viewer(args, meshcat)
    if html_error:
        print(html_error, file=sys.stderr, flush=True)
        return 1
    return 0

