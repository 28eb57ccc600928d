"""A trial before and after a change of representation, against its plant-alone floor, in
lockstep. From a checkout:

    python -m benchmarks.lockstep [--repeats 3] [--variant KEY=VALUE ...] [--no-profile]
        [--json] [--scenario FILE] [--scenario-name NAME] [--set KEY=VALUE ...]

Three simulations, built afresh each repeat: the plant alone (plant_floor.py: the station's
plant replaying the plant inputs that the scenario's memorized trial recorded), that
closed-loop memorized trial ("before"), and the same trial with the `--variant`
assignments ("after"; default `vibration.pad_force_source=joint_forces`). They advance in
turn, STRIDE_S of simulated time each, to the recorded trial's end, and each one's process
CPU time is summed over its strides: a shared host's load drifts over seconds and falls on
the three alike, so their ratios compare even where the absolute figures do not. Per
repeat: CPU seconds per simulated second of each, each trial over the floor, and before
over after; the report gives the medians. Then, unless --no-profile, each trial once under
cProfile: each Python system's calls and own time per simulated second (system_costs.py).
"""

import argparse
import json
import statistics
import time

from benchmarks.plant_floor import build_plant_floor, record_plant_inputs
from benchmarks.system_costs import profile_trial
from benchmarks.arguments import benchmark_parser, parse_benchmark_arguments
from tegrasp_drake.commands.scenario_args import scenario_from_arguments
from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram, MakeSimulator
from tegrasp_drake.scenario.scenario import with_controller

STRIDE_S = 0.05  # simulated time each variant advances per turn
DEFAULT_VARIANT = ("vibration.pad_force_source=joint_forces",)
NAMES = ("floor", "before", "after")


def advance_in_lockstep(simulators: dict, end_s: float, stride_s: float = STRIDE_S) -> dict:
    """Advances every simulator of {name: Simulator} to end_s [s], in turn, stride_s of
    simulated time each; returns {name: process CPU seconds it took}."""
    cpu = {name: 0.0 for name in simulators}
    for simulator in simulators.values():
        simulator.Initialize()
    t = 0.0
    while t < end_s - 1e-9:
        t = min(t + stride_s, end_s)
        for name, simulator in simulators.items():
            start = time.process_time()
            simulator.AdvanceTo(t)
            cpu[name] += time.process_time() - start
    return cpu


def _trial_simulator(scenario):
    grasp = MakeGraspDiagram(scenario)
    return MakeSimulator(grasp.diagram, scenario)


def compare_in_lockstep(before, after, *, repeats: int = 3) -> dict:
    """The floor of scenario `before`'s memorized trial, that trial and scenario `after`'s
    in lockstep, `repeats` times (see the module docstring)."""
    before, after = (with_controller(s, "memorized") for s in (before, after))
    inputs = record_plant_inputs(before)
    end = float(inputs.times[-1])
    runs = []
    for _ in range(repeats):
        simulators = {"floor": build_plant_floor(before, inputs)[0],
                      "before": _trial_simulator(before), "after": _trial_simulator(after)}
        cpu = advance_in_lockstep(simulators, end)
        runs.append({name: cpu[name] / end for name in NAMES})
    ratios = {"before_over_floor": [r["before"] / r["floor"] for r in runs],
              "after_over_floor": [r["after"] / r["floor"] for r in runs],
              "before_over_after": [r["before"] / r["after"] for r in runs]}
    return {"object": before.object.name, "seed": before.random_seed,
            "sim_time_s": end, "repeats": repeats,
            "runs": runs,
            "cpu_per_sim_s": {name: statistics.median(r[name] for r in runs)
                              for name in NAMES},
            "ratios": {key: statistics.median(values) for key, values in ratios.items()}}


def profile_both(before, after) -> dict:
    """Each memorized trial (scenarios `before`, `after`) once under cProfile: {"before" or
    "after": {system: {"calls", "own_ms_per_sim_s"}}}."""
    profiles = {}
    for name, scenario in (("before", before), ("after", after)):
        profile = profile_trial(with_controller(scenario, "memorized"))
        profiles[name] = {system: {"calls": cost["calls"],
                                   "own_ms_per_sim_s": 1e3 * cost["own_s"]
                                   / profile["sim_time_s"]}
                          for system, cost in profile["systems"].items()}
    return profiles


def format_report(result: dict) -> str:
    """The benchmark's result as plain-text tables."""
    cpu, ratios = result["cpu_per_sim_s"], result["ratios"]
    lines = [f"{result['object']}, seed {result['seed']}, {result['sim_time_s']:.2f} s "
             f"simulated, {result['repeats']} repeats in lockstep ({STRIDE_S * 1e3:g} ms "
             f"strides), medians; after = {' '.join(result['variant'])}",
             f"{'':<8} {'CPU s per sim s':>16} {'x real time (CPU)':>18} {'over floor':>11}"]
    for name in NAMES:
        over = "1" if name == "floor" else f"{ratios[f'{name}_over_floor']:.2f}"
        lines.append(f"{name:<8} {cpu[name]:>16.3f} {1.0 / cpu[name]:>18.2f} {over:>11}")
    lines.append(f"before / after (CPU, per repeat, median): {ratios['before_over_after']:.3f}")
    lines.append("per repeat, CPU s per sim s (floor, before, after): " + "; ".join(
        ", ".join(f"{run[name]:.3f}" for name in NAMES) for run in result["runs"]))
    if "python_systems" in result:
        profiles = result["python_systems"]
        systems = sorted(set(profiles["before"]) | set(profiles["after"]),
                         key=lambda s: -profiles["before"].get(s, {}).get("own_ms_per_sim_s", 0))
        lines += ["", "Python systems under cProfile, own ms per simulated s (calls)",
                  f"{'system':<26} {'before':>18} {'after':>18}"]
        for system in systems:
            cells = [(f"{p[system]['own_ms_per_sim_s']:.0f} ({p[system]['calls']})"
                      if system in p else "-") for p in (profiles["before"], profiles["after"])]
            lines.append(f"{system:<26} {cells[0]:>18} {cells[1]:>18}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "lockstep runs of the three simulations")
    parser.add_argument("--variant", action="append", metavar="KEY=VALUE",
                        help="an assignment of the 'after' trial (repeatable; default "
                             f"{' '.join(DEFAULT_VARIANT)})")
    parser.add_argument("--no-profile", action="store_true",
                        help="skip the per-system profile")
    args = parse_benchmark_arguments(parser, argv)
    assignments = list(args.variant or DEFAULT_VARIANT)
    before = scenario_from_arguments(args)
    after = scenario_from_arguments(argparse.Namespace(  # a bad assignment stops here
        **{**vars(args), "overrides": args.overrides + assignments}))
    result = compare_in_lockstep(before, after, repeats=args.repeats)
    result["variant"] = assignments
    if not args.no_profile:
        result["python_systems"] = profile_both(before, after)
    print(json.dumps(result) if args.json else format_report(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
