"""`tegrasp trial`: one closed-loop grasp trial, its state timeline and its success.

`tegrasp demo` is this command on the default scenario with a figure (the README's main job).
"""

import json
import pathlib

from tegrasp_drake.commands.scenario_args import add_scenario_arguments, scenario_from_arguments
from tegrasp_drake.commands.viewer_args import (add_viewer_arguments, check_html_path,
                                                start_viewer, wait_for_viewer,
                                                write_replay_html)
from tegrasp_drake.control.controller_config import CONTROLLERS
from tegrasp_drake.experiments.figures.figure_files import FIGURE_FORMATS


def add_trial_arguments(parser, *, default_out: str) -> None:
    add_scenario_arguments(parser)
    parser.add_argument("--controller", choices=CONTROLLERS, default=None,
                        help="memorized: the paper's memorized tactile events; heuristic: "
                             "hand-set thresholds (Romano et al. style); open_loop: the ideal "
                             "scripted grasp (default: the scenario's controller.name)")
    parser.add_argument("--out", default=default_out,
                        help="folder for the trial log (trial.npz) and figures (states: "
                             "Fig. 9; signals: Fig. 5a-b; avoid: Fig. 10, after a hit)")
    parser.add_argument("--format", choices=FIGURE_FORMATS, default="png",
                        help="the figures' file format (default: %(default)s)")
    parser.add_argument("--json", action="store_true", help="print the result as one JSON object")
    add_viewer_arguments(parser)


def register(subparsers) -> None:
    parser = subparsers.add_parser("trial", help="run one closed-loop grasp trial")
    add_trial_arguments(parser, default_out="out/trial")
    parser.set_defaults(func=run)


def print_result(result: dict) -> None:
    from tegrasp_drake.control.grasp_modes import Transition
    print(f"object {result['object']} offset {result['offset_m']} m, controller "
          f"{result['controller']}, seed {result['seed']}")
    for transition in map(Transition.from_dict, result["transitions"]):
        scores = None if transition.scores is None else list(transition.scores)
        extra = f"  scores {scores}" if transition.trigger.is_event else ""
        print(f"  {transition.t:7.3f} s  {transition.from_mode.label:>8} -> "
              f"{transition.to_mode.label:<8} [{transition.trigger.value}] "
              f"{transition.reason}{extra}")
    print(f"hold {'SUCCESS' if result['hold_success'] else 'FAIL'} (held "
          f"{result['hold_time_s']:.2f} s), unload "
          f"{'SUCCESS' if result['unload_success'] else 'FAIL'} (tilt "
          f"{result['final_tilt_deg']:.1f} deg, {'released' if result['released'] else 'held'})"
          + (f"; failed: {result['failure']}" if result["failure"] else ""))
    print(f"simulated {result['sim_time_s']:.2f} s in {result['wall_time_s']:.2f} s wall "
          f"(real-time factor {result['real_time_factor']:.2f})")


def run(args) -> int:
    overrides = list(args.overrides)
    if args.controller:
        overrides.append(f"controller.name={args.controller}")
    args.overrides = overrides
    scenario = scenario_from_arguments(args)
    html = check_html_path(args)
    from tegrasp_drake.events import MemorizedEventError
    from tegrasp_drake.experiments.figures.trial_figures import write_trial_figures
    from tegrasp_drake.experiments.trial import run_trial
    meshcat = start_viewer(args)
    try:
        trial = run_trial(scenario, meshcat=meshcat)
    except MemorizedEventError as e:
        raise SystemExit(f"tegrasp: error: the memorized controller needs the memorized events "
                         f"of '{scenario.object.name}': {e}") from None
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    result = dict(trial.result, log=str(trial.log.save(out / "trial.npz")),
                  **write_trial_figures(trial.log, out, args.format))
    if html is not None:
        result["replay_html"] = str(write_replay_html(meshcat, html))
    if args.json:
        print(json.dumps(result, sort_keys=True), flush=True)
    else:
        print_result(result)
        print(f"log {result['log']}, figures {result['figure']} (Fig. 9), "
              f"{result['signals_figure']} (Fig. 5a-b)"
              + (f", {result['avoid_figure']} (Fig. 10)" if "avoid_figure" in result else ""))
        if html is not None:
            print(f"replay {result['replay_html']} (open it in a browser)")
    wait_for_viewer(args, meshcat)
    return 0

