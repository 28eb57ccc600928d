"""Trial benchmark: what a closed-loop trial costs and where. From a checkout:

    python -m benchmarks.trial [--repeats 3] [--no-growth] [--no-profile] [--json]
        [--scenario FILE] [--scenario-name NAME] [--set KEY=VALUE ...]

In one run, variants alternate within each repeat (the machine's load drifts, so only
figures measured side by side compare):
  - the closed-loop trial's real-time factor per controller (simulated time over wall time
    and over process CPU time; CPU time is the steadier on a shared machine);
  - the plant-alone floor of the same scene (plant_floor.py: the station's plant replaying
    the memorized trial's plant inputs, the same contacts, no other system) and the
    trial-to-floor cost ratio, per repeat, then the median;
  - each Python system's calls per trial and cost per call (system_costs.py, under cProfile);
  - how the cost grows with the contact faces on the pads (the object's mesh resolution,
    open-loop grasp of the thick cylinder; Drake's compliant pad box ignores its own hint)
    and with the sensor rates (taxel and film rates, memorized trial).

It times its runs, so it shows no progress bar (the runs are the measurement). It took 6 min
with 3 repeats on a shared 2-core host: about 1 min per repeat, 3 min for the recorded
trial, the profile and the growth tables.
"""

import dataclasses
import json
import pathlib
import statistics
import tempfile
import time

from benchmarks.plant_floor import record_plant_inputs, run_plant_floor
from benchmarks.system_costs import profile_trial
from benchmarks.arguments import benchmark_parser, parse_benchmark_arguments
from tegrasp_drake.commands.scenario_args import scenario_from_arguments
from tegrasp_drake.control.controller_registry import PAPER_CONTROLLERS
from tegrasp_drake.scenario.grasp_diagram import MakeSimulator
from tegrasp_drake.runs.ideal_grasp import END_MARGIN_S, MakeIdealGraspDiagram
from tegrasp_drake.scenario.scenario import with_controller
from tegrasp_drake.runs.trial import run_trial
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS, ObjectConfig
from tegrasp_drake.simulation.object_model import object_sdf

# The paper's controllers, by name (Table I).
PAPER_CONTROLLER_NAMES = PAPER_CONTROLLERS
FLOOR = "plant_alone"
MESH_RESOLUTIONS_M = (0.01, 0.005, 0.0025)  # object mesh hints of the contact-face curve
TAXEL_RATES_HZ = (108.0, 500.0, 1000.0)
FILM_RATES_HZ = (500.0, 1000.0)


def _factors(sim_s: float, wall_s: float, cpu_s: float) -> dict:
    return {"sim_time_s": sim_s, "wall_time_s": wall_s, "cpu_time_s": cpu_s,
            "rtf_wall": sim_s / wall_s, "rtf_cpu": sim_s / cpu_s}


def time_trial(scenario) -> dict:
    """Simulated, wall and CPU time of one closed-loop trial of `scenario` (its controller),
    and its real-time factors."""
    result = run_trial(scenario).result
    return _factors(result["sim_time_s"], result["wall_time_s"], result["cpu_time_s"])


def _medians(runs: list[dict]) -> dict:
    return {key: statistics.median(run[key] for run in runs)
            for key in ("rtf_wall", "rtf_cpu", "wall_time_s", "cpu_time_s")}


def compare_trials_with_floor(scenario, *, repeats: int = 3,
                              controllers=PAPER_CONTROLLER_NAMES) -> dict:
    """Each controller's trial and the plant-alone floor, alternating, `repeats` times:
    medians per variant and the median per-repeat ratio of each trial's cost to the floor's."""
    inputs = record_plant_inputs(with_controller(scenario, "memorized"))
    runs = {name: [] for name in (*controllers, FLOOR)}
    deviation = 0.0
    for _ in range(repeats):
        for name in controllers:
            runs[name].append(time_trial(with_controller(scenario, name)))
        floor = run_plant_floor(scenario, inputs)
        deviation = max(deviation, floor.object_deviation_m)
        runs[FLOOR].append(_factors(floor.sim_time_s, floor.wall_time_s, floor.cpu_time_s))
    result = {name: _medians(variant) for name, variant in runs.items()}
    for name in controllers:
        for clock in ("wall", "cpu"):
            result[name][f"cost_over_floor_{clock}"] = statistics.median(
                floor[f"rtf_{clock}"] / trial[f"rtf_{clock}"]
                for trial, floor in zip(runs[name], runs[FLOOR]))
    result[FLOOR]["object_deviation_from_trial_m"] = deviation
    return result


def _contact_faces(contact_results) -> int:
    return sum(contact_results.hydroelastic_contact_info(i).contact_surface().num_faces()
               for i in range(contact_results.num_hydroelastic_contacts()))


def _median_call_us(function, repeats: int) -> float:
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        samples.append((time.perf_counter() - start) * 1e6)
    return statistics.median(samples)


def ideal_grasp_cost(scenario, *, repeats: int = 100) -> dict:
    """One open-loop grasp of `scenario`: its real-time factors; at 0.5 s into Hold, the
    contact faces and the median cost of one tactile-pad sample (timed outside the run)."""
    grasp = MakeIdealGraspDiagram(scenario)
    segments = grasp.controller.segments
    simulator = MakeSimulator(grasp.diagram, scenario)
    end = segments[-1].t_end + END_MARGIN_S
    hold = next(s.t_start for s in segments if s.phase == "hold") + 0.5
    pads = grasp.diagram.GetSubsystemByName("station").GetSubsystemByName("tactile_pads")
    wall, cpu = time.perf_counter(), time.process_time()
    simulator.Initialize()
    simulator.AdvanceTo(hold)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    context = pads.GetMyContextFromRoot(simulator.get_context())
    faces = _contact_faces(pads.GetInputPort("contact_results").Eval(context))
    state = context.get_discrete_state().Clone()
    pad_us = _median_call_us(lambda: pads._sample(context, state), repeats)
    wall2, cpu2 = time.perf_counter(), time.process_time()
    simulator.AdvanceTo(end)
    wall, cpu = wall + time.perf_counter() - wall2, cpu + time.process_time() - cpu2
    return {**_factors(end, wall, cpu), "contact_faces_while_holding": faces,
            "tactile_pad_sample_us": pad_us}


def meshed_object(base: ObjectConfig, resolution_m: float, folder: pathlib.Path):
    """`base` (a built-in cylinder) as a file object whose mesh hint is resolution_m."""
    path = folder / f"object_{resolution_m * 1000:g}mm.sdf"
    path.write_text(object_sdf(base, mesh_resolution_m=resolution_m))
    diameter, height = base.size
    return dataclasses.replace(base, name=f"{base.name}_{resolution_m * 1000:g}mm",
                               shape="file", file=str(path),
                               size=[diameter, diameter, height])


def contact_face_growth(scenario, *, resolutions_m=MESH_RESOLUTIONS_M,
                        object_name: str = "thick_cylinder") -> list[dict]:
    """The open-loop grasp's cost as the object's mesh gets finer (more contact faces)."""
    rows = []
    with tempfile.TemporaryDirectory(prefix="tegrasp-mesh-") as folder:
        for resolution in resolutions_m:
            obj = meshed_object(BUILTIN_OBJECTS[object_name], resolution, pathlib.Path(folder))
            cost = ideal_grasp_cost(with_controller(
                dataclasses.replace(scenario, object=obj), "open_loop"))
            rows.append({"object_mesh_m": resolution, **cost})
    return rows


def sensor_rate_growth(scenario, *, taxel_rates_hz=TAXEL_RATES_HZ,
                       film_rates_hz=FILM_RATES_HZ) -> list[dict]:
    """The memorized trial's cost at each taxel rate (film at its default) and each film
    rate (taxels at their default)."""
    rows = []
    memorized = with_controller(scenario, "memorized")
    for rate in taxel_rates_hz:
        tactile = dataclasses.replace(scenario.tactile, sample_rate_hz=rate)
        rows.append({"taxel_rate_hz": rate, "film_rate_hz": scenario.vibration.sample_rate_hz,
                     **time_trial(dataclasses.replace(memorized, tactile=tactile))})
    for rate in film_rates_hz:
        vibration = dataclasses.replace(scenario.vibration, sample_rate_hz=rate)
        rows.append({"taxel_rate_hz": scenario.tactile.sample_rate_hz, "film_rate_hz": rate,
                     **time_trial(dataclasses.replace(memorized, vibration=vibration))})
    return rows


def run_trial_benchmark(scenario, *, repeats: int = 3, growth: bool = True,
                        profile: bool = True) -> dict:
    """All of the above for `scenario` (see the module docstring)."""
    result = {"object": scenario.object.name, "repeats": repeats,
              "trials": compare_trials_with_floor(scenario, repeats=repeats)}
    if profile:
        result["python_systems"] = profile_trial(with_controller(scenario, "memorized"))
    if growth:
        result["contact_face_growth"] = contact_face_growth(scenario)
        result["sensor_rate_growth"] = sensor_rate_growth(scenario)
    return result


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


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "runs of each controller and of the floor, alternating")
    parser.add_argument("--no-growth", action="store_true",
                        help="skip the contact-face and sensor-rate tables")
    parser.add_argument("--no-profile", action="store_true",
                        help="skip the per-system profile")
    args = parse_benchmark_arguments(parser, argv)
    result = run_trial_benchmark(scenario_from_arguments(args), repeats=args.repeats,
                                 growth=not args.no_growth, profile=not args.no_profile)
    print(json.dumps(result) if args.json else format_report(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
