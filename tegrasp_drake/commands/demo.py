"""`tegrasp demo`: run a grasp on a scenario and summarise it."""

import json
import pathlib

import numpy as np

from tegrasp_drake.commands.scenario_args import add_scenario_arguments, scenario_from_arguments


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "demo", help="run the grasp on the default (or given) scenario and summarise it")
    add_scenario_arguments(parser)
    parser.add_argument("--controller", choices=("open_loop",), default="open_loop",
                        help="open_loop: the ideal scripted grasp of Sec. III-A")
    parser.add_argument("--out", default="out/demo", help="folder for the figure and log")
    parser.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    parser.add_argument("--meshcat", action="store_true",
                        help="show the run in Meshcat (prints the URL; waits for Enter at the end)")
    parser.set_defaults(func=run)


def summarize(scenario, log, wall_time: float) -> dict:
    from tegrasp_drake.grasp_outcome import judge_grasp
    target = np.add(np.add(scenario.expected_object_xy, scenario.object_offset),
                    scenario.grasp.place_offset)
    outcome = judge_grasp(log, target_xy=target, grip_force=scenario.grasp.grip_force)
    sim_time = float(log.meta["sim_time_s"])
    return {
        "object": scenario.object.name,
        "object_offset_m": list(scenario.object_offset),
        "controller": log.meta["controller"],
        "seed": scenario.random_seed,
        "phases": log.meta["phase_starts"],
        "events": outcome.events,
        "lift_height_m": outcome.lift_height_m,
        "hold_time_s": outcome.hold_time_s,
        "final_tilt_deg": outcome.final_tilt_deg,
        "placed_upright": outcome.final_tilt_deg < 5.0,
        "placement_error_m": outcome.placement_error_m,
        "released": outcome.released,
        "sim_time_s": sim_time,
        "wall_time_s": wall_time,
        "real_time_factor": sim_time / wall_time,
    }


def _print_summary(summary: dict) -> None:
    print(f"object {summary['object']} offset {summary['object_offset_m']} m, "
          f"controller {summary['controller']}, seed {summary['seed']}")
    print("phases: " + ", ".join(f"{name} {t:.2f} s" for name, t in summary["phases"].items()))
    print("events: " + ", ".join(f"{name} {'-' if t is None else f'{t:.3f} s'}"
                                 for name, t in summary["events"].items()))
    print(f"lift height {summary['lift_height_m'] * 100:.1f} cm, hold time "
          f"{summary['hold_time_s']:.2f} s, tilt {summary['final_tilt_deg']:.1f} deg "
          f"({'upright' if summary['placed_upright'] else 'NOT upright'}), placement error "
          f"{summary['placement_error_m'] * 1000:.1f} mm, "
          f"{'released' if summary['released'] else 'NOT released'}")
    print(f"simulated {summary['sim_time_s']:.1f} s in {summary['wall_time_s']:.1f} s wall "
          f"(real-time factor {summary['real_time_factor']:.2f})")


def run(args) -> int:
    scenario = scenario_from_arguments(args)
    from tegrasp_drake.figures import plot_trial_signals
    from tegrasp_drake.ideal_grasp import run_ideal_grasp
    meshcat = None
    if args.meshcat:
        from pydrake.geometry import StartMeshcat
        meshcat = StartMeshcat()
    log, wall = run_ideal_grasp(scenario, meshcat=meshcat)
    summary = summarize(scenario, log, wall)
    log.meta.update(events=summary["events"], object=scenario.object.name)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    log_path = log.save(out / "trial.npz")
    figure_path = out / "signals.png"
    plot_trial_signals(log, figure_path)
    summary.update(log=str(log_path), figure=str(figure_path))
    if args.json:
        print(json.dumps(summary, sort_keys=True))
    else:
        _print_summary(summary)
        print(f"log {log_path}, figure {figure_path}")
    if meshcat is not None and not args.json:
        input(f"Meshcat at {meshcat.web_url()}: replay the recording there; Enter to quit. ")
    return 0
