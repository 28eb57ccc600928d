"""`tegrasp trial`: one closed-loop grasp trial, its state timeline and its success.

`tegrasp demo` is this command on the default scenario with a figure (the README's main job).
"""

import json
import pathlib

from tegrasp_drake.commands.scenario_args import (add_events_argument, add_scenario_arguments,
                                                   controller_events, scenario_from_arguments)
from tegrasp_drake.control.controller_config import CONTROLLERS


def add_trial_arguments(parser, *, default_out: str) -> None:
    add_scenario_arguments(parser)
    add_events_argument(parser)
    parser.add_argument("--controller", choices=CONTROLLERS, default=None,
                        help="memorized: the paper's memorized tactile events; heuristic: "
                             "hand-set thresholds (Romano et al. style); open_loop: the ideal "
                             "scripted grasp (default: the scenario's controller.name)")
    parser.add_argument("--out", default=default_out,
                        help="folder for the trial log (trial.npz) and figures (states.png: "
                             "Fig. 9; signals.png: Fig. 5a-b)")
    parser.add_argument("--json", action="store_true", help="print the result as one JSON object")
    parser.add_argument("--meshcat", action="store_true",
                        help="show the run in Meshcat (prints the URL; waits for Enter at the end)")


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
    events = controller_events(scenario, args.events)
    from tegrasp_drake.experiments.trial import run_trial
    from tegrasp_drake.experiments.figures.signals import plot_trial_signals
    from tegrasp_drake.experiments.figures.trial import plot_trial_states
    meshcat = None
    if args.meshcat:
        from pydrake.geometry import StartMeshcat
        meshcat = StartMeshcat()
    trial = run_trial(scenario, meshcat=meshcat, events=events)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    plot_trial_signals(trial.log, out / "signals.png")  # Fig. 5a-b: raw and processed
    result = dict(trial.result, log=str(trial.log.save(out / "trial.npz")),
                  figure=plot_trial_states(trial.log, out / "states.png"),
                  signals_figure=str(out / "signals.png"))
    if args.json:
        print(json.dumps(result, sort_keys=True))
    else:
        print_result(result)
        print(f"log {result['log']}, figures {result['figure']} (Fig. 9), "
              f"{result['signals_figure']} (Fig. 5a-b)")
    if meshcat is not None and not args.json:
        input(f"Meshcat at {meshcat.web_url()}: replay the recording there; Enter to quit. ")
    return 0
