"""`tegrasp benchmark`: what a closed-loop trial costs, against the plant alone, per Python
system, and as contact faces and sensor rates grow (benchmarks/trial.py)."""

import argparse
import json

from tegrasp_drake.commands.scenario_args import add_scenario_arguments, scenario_from_arguments


EPILOG = """\
examples:
  tegrasp benchmark                      # 3 repeats of each controller and the floor, all tables
  tegrasp benchmark --repeats 5 --no-growth --no-profile --json

Variants alternate within each repeat; medians are printed, ratios are per repeat. It
times its runs, so it shows no progress bar (the runs are the measurement). It took 6 min
with 3 repeats on a shared 2-core host: about 1 min per repeat, 3 min for the recorded
trial, the profile and the growth tables."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "benchmark", help="print a trial's real-time factor per controller, the plant-alone "
        "floor, each Python system's cost and the growth with contact faces and sensor rates",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_scenario_arguments(parser)
    parser.add_argument("--repeats", type=int, default=3,
                        help="runs of each controller and of the floor, alternating")
    parser.add_argument("--no-growth", action="store_true",
                        help="skip the contact-face and sensor-rate tables")
    parser.add_argument("--no-profile", action="store_true",
                        help="skip the per-system profile")
    parser.add_argument("--json", action="store_true")
    parser.set_defaults(func=run)


def format_report(result: dict) -> str:
    """The benchmark's result as plain-text tables."""
    lines = [f"object {result['object']}, {result['repeats']} repeats, medians; rtf = "
             "simulated / wall (or process CPU) time; cost/floor = the trial's CPU (wall) "
             "time over the plant-alone floor's, per repeat",
             f"{'variant':<12} {'rtf wall':>9} {'rtf cpu':>8} {'cost/floor cpu':>15} "
             f"{'cost/floor wall':>16}"]
    for name, row in result["trials"].items():
        ratio_cpu = row.get("cost_over_floor_cpu")
        ratio_wall = row.get("cost_over_floor_wall")
        lines.append(f"{name:<12} {row['rtf_wall']:>9.3f} {row['rtf_cpu']:>8.3f} "
                     f"{'' if ratio_cpu is None else f'{ratio_cpu:.2f}':>15} "
                     f"{'' if ratio_wall is None else f'{ratio_wall:.2f}':>16}")
    floor = result["trials"]["plant_alone"]
    lines.append(f"(the floor's object ended {floor['object_deviation_from_trial_m']:.2e} m "
                 "from the recorded trial's)")
    if "python_systems" in result:
        profile = result["python_systems"]
        lines += ["", f"Python systems, one memorized trial under cProfile "
                  f"({profile['sim_time_s']:.2f} s simulated, {profile['profiled_cpu_time_s']:.2f}"
                  f" s CPU profiled, {profile['python_systems_s']:.2f} s in the systems, "
                  f"{profile['eval_calls']} input-port Evals from Python)",
                  f"{'system':<26} {'calls':>8} {'us/call':>9} {'own s':>8} {'Evals':>8} "
                  f"{'in Evals s':>11}"]
        for name, cost in profile["systems"].items():
            lines.append(f"{name:<26} {cost['calls']:>8} {cost['us_per_call']:>9.1f} "
                         f"{cost['own_s']:>8.3f} {cost['eval_calls']:>8} {cost['eval_s']:>11.3f}")
    if "contact_face_growth" in result:
        lines += ["", "contact faces (open-loop grasp, object mesh hint)",
                  f"{'mesh mm':>8} {'faces':>6} {'pad sample us':>14} {'rtf cpu':>8} "
                  f"{'rtf wall':>9}"]
        for row in result["contact_face_growth"]:
            lines.append(f"{row['object_mesh_m'] * 1000:>8g} "
                         f"{row['contact_faces_while_holding']:>6} "
                         f"{row['tactile_pad_sample_us']:>14.0f} {row['rtf_cpu']:>8.3f} "
                         f"{row['rtf_wall']:>9.3f}")
        lines += ["", "sensor rates (memorized trial)",
                  f"{'taxel Hz':>9} {'film Hz':>8} {'rtf cpu':>8} {'rtf wall':>9}"]
        for row in result["sensor_rate_growth"]:
            lines.append(f"{row['taxel_rate_hz']:>9g} {row['film_rate_hz']:>8g} "
                         f"{row['rtf_cpu']:>8.3f} {row['rtf_wall']:>9.3f}")
    return "\n".join(lines)


def run(args) -> int:
    if args.repeats < 1:
        print(f"tegrasp benchmark: --repeats {args.repeats}: give at least 1 run per variant")
        return 2
    scenario = scenario_from_arguments(args)
    from benchmarks.trial import run_trial_benchmark
    result = run_trial_benchmark(scenario, repeats=args.repeats, growth=not args.no_growth,
                                 profile=not args.no_profile)
    print(json.dumps(result) if args.json else format_report(result))
    return 0
