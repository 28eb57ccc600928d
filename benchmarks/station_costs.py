"""Station benchmark: the full-arm and the carriage stations' memorized trials, their
plant-alone floors, and the floor's cost per phase of the trial, split into its parts.
From a checkout:

    python -m benchmarks.station_costs [--repeats 3] [--json] [--set random_seed=600 ...]

In one run, alternating within each repeat (only figures measured side by side compare):
  - each station's closed-loop memorized trial: real-time factor on process CPU time and
    CPU seconds per simulated second, per phase and whole;
  - the same station's plant alone replaying that trial's plant inputs (plant_floor.py),
    per phase and whole; the trial-to-floor ratio per repeat, then the median;
  - once per station, the floor's plant step at sampled instants of each phase, timed
    apart (`step_parts`): the pose update (forward kinematics to SceneGraph), the contact
    surfaces (SceneGraph's hydroelastic query with point-contact fallback), and the rest of
    the step (the SAP solve and the multibody dynamics around it). A phase's "python"
    figure is the trial's CPU there less the floor's: the controller's and sensors'
    Python systems and the simulator's own events.

Phases follow the state machine's mode, and Reach is split at the pads' first touch:
reach (free motion), close (Reach touching and Load), lift, hold (and Avoid), place,
unload (and the settling after Done).
"""

import dataclasses
import json
import statistics
import time

import numpy as np
from pydrake.geometry import HydroelasticContactRepresentation

from benchmarks.arguments import benchmark_parser, parse_benchmark_arguments
from tegrasp_drake.commands.scenario_args import scenario_from_arguments
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.control.grasp_modes import Mode
from benchmarks.plant_floor import (build_plant_floor,
                                                              record_plant_inputs)
from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram, MakeSimulator
from tegrasp_drake.scenario.scenario import with_controller
from tegrasp_drake.simulation.station import SimulatedStationConfig

STATIONS = ("jaco2", "carriage")
PHASES = ("reach", "close", "lift", "hold", "place", "unload")
CHUNK_S = 0.01  # the phase clock's resolution [s]
END_MARGIN_S = 0.5  # simulated after the machine ends, as a trial does
SAMPLES_PER_PHASE = 12  # instants at which the floor's step is timed apart
TIMING_REPEATS = 5  # each part timed this often at an instant; the median is kept
_PHASE_OF_MODE = {Mode.REACH: "reach", Mode.RE_REACH: "reach", Mode.LOAD: "close",
                  Mode.LIFT: "lift", Mode.HOLD: "hold", Mode.AVOID: "hold",
                  Mode.PLACE: "place", Mode.UNLOAD: "unload", Mode.DONE: "unload",
                  Mode.FAILED: "unload"}


def station_scenario(scenario, arm: str):
    """`scenario` with the memorized controller on the simulated station `arm`."""
    return dataclasses.replace(with_controller(scenario, "memorized"),
                               station=SimulatedStationConfig(arm=arm))


def _phase(mode: Mode, touched: bool) -> str:
    phase = _PHASE_OF_MODE[mode]
    return "close" if phase == "reach" and touched else phase


def timed_trial_by_phase(scenario) -> dict:
    """One closed-loop trial, its clock read every CHUNK_S: CPU seconds per phase, the
    phase timeline [(t_start, phase)], and the whole run's simulated, wall and CPU time."""
    grasp = MakeGraspDiagram(scenario)
    simulator = MakeSimulator(grasp.diagram, scenario)
    context = simulator.get_mutable_context()
    station_context = grasp.station.GetMyContextFromRoot(context)
    taxels = grasp.station.GetOutputPort(ports.TRUE_TAXEL_FORCES)
    cpu = {phase: 0.0 for phase in PHASES}
    timeline, touched, ended, limit = [], False, False, grasp.time_limit
    wall_start, cpu_start = time.perf_counter(), time.process_time()
    simulator.Initialize()
    while context.get_time() < limit - 1e-9:
        mode = grasp.controller.current_mode(context)
        touched = touched or bool(np.any(taxels.Eval(station_context) > 0.0))
        phase = _phase(mode, touched)
        if not timeline or timeline[-1][1] != phase:
            timeline.append((context.get_time(), phase))
        start = time.process_time()
        simulator.AdvanceTo(min(context.get_time() + CHUNK_S, limit))
        cpu[phase] += time.process_time() - start
        if not ended and mode in (Mode.DONE, Mode.FAILED):
            ended, limit = True, min(limit, context.get_time() + END_MARGIN_S)
    end = context.get_time()
    return {"sim_time_s": end, "wall_time_s": time.perf_counter() - wall_start,
            "cpu_time_s": time.process_time() - cpu_start, "phase_cpu_s": cpu,
            "phase_sim_s": _phase_sim(timeline, end), "timeline": timeline}


def _phase_sim(timeline: list, end: float) -> dict:
    return {phase: sum(t1 - t0 for p, t0, t1 in _phase_spans(timeline, end) if p == phase)
            for phase in PHASES}


def _phase_spans(timeline: list, end: float) -> list:
    """[(phase, t_start, t_end)] of a timeline cut at `end`."""
    ends = [t for t, _ in timeline[1:]] + [end]
    return [(phase, t, min(t_end, end)) for (t, phase), t_end in zip(timeline, ends)
            if t < end]


def timed_floor_by_phase(scenario, inputs, timeline: list) -> dict:
    """The plant alone over the trial's phases: CPU seconds per phase and in all."""
    simulator, _ = build_plant_floor(scenario, inputs)
    end = float(inputs.times[-1])
    cpu = {phase: 0.0 for phase in PHASES}
    cpu_start = time.process_time()
    simulator.Initialize()
    for phase, _, t_end in _phase_spans(timeline, end):
        start = time.process_time()
        simulator.AdvanceTo(min(t_end, end))
        cpu[phase] += time.process_time() - start
    return {"sim_time_s": end, "cpu_time_s": time.process_time() - cpu_start,
            "phase_cpu_s": cpu, "phase_sim_s": _phase_sim(timeline, end)}


def _median_s(function) -> float:
    samples = []
    for _ in range(TIMING_REPEATS):
        start = time.process_time()
        function()
        samples.append(time.process_time() - start)
    return statistics.median(samples)


def step_parts(simulator, plant, scene_graph, time_step: float) -> dict:
    """The floor's plant step here, timed apart [us]: `step` (TIMING_REPEATS real steps,
    the median), `poses` (the plant's kinematics into SceneGraph, caches cold),
    `contact_surfaces` (SceneGraph's hydroelastic query with fallback, poses warm), `rest`
    = step - poses - surfaces (the SAP solve and the multibody dynamics), and the number
    of contact-surface faces."""
    context = simulator.get_mutable_context()
    steps = []
    for _ in range(TIMING_REPEATS):
        start = time.process_time()
        simulator.AdvanceTo(context.get_time() + time_step)
        steps.append(time.process_time() - start)
    probe = context.Clone()
    plant_context = plant.GetMyMutableContextFromRoot(probe)
    sg_context = scene_graph.GetMyContextFromRoot(probe)
    x = plant.GetPositionsAndVelocities(plant_context).copy()
    query_port = scene_graph.get_query_output_port()

    def invalidate():
        plant.SetPositionsAndVelocities(plant_context, x)

    def surfaces():
        return query_port.Eval(sg_context).ComputeContactSurfacesWithFallback(
            HydroelasticContactRepresentation.kPolygon)

    def cold_surfaces():
        invalidate()
        surfaces()

    contact, _ = surfaces()
    parts = {"step": statistics.median(steps), "contact_surfaces": _median_s(surfaces)}
    parts["poses"] = _median_s(cold_surfaces) - _median_s(invalidate) - parts["contact_surfaces"]
    parts["rest"] = parts["step"] - parts["poses"] - parts["contact_surfaces"]
    result = {key: value * 1e6 for key, value in parts.items()}
    result["faces"] = sum(surface.num_faces() for surface in contact)
    return result


def floor_step_breakdown(scenario, inputs, timeline: list) -> dict:
    """Per phase, the median of step_parts over SAMPLES_PER_PHASE instants of the floor."""
    simulator, parts = build_plant_floor(scenario, inputs)
    end = float(inputs.times[-1])
    samples = {phase: [] for phase in PHASES}
    time_step = scenario.plant_config.time_step
    simulator.Initialize()
    for phase, t_start, t_end in _phase_spans(timeline, end - TIMING_REPEATS * time_step):
        for t in np.linspace(t_start, t_end, SAMPLES_PER_PHASE + 2)[1:-1]:
            if t > simulator.get_context().get_time():
                simulator.AdvanceTo(t)
            samples[phase].append(step_parts(simulator, parts.plant, parts.scene_graph,
                                             time_step))
    return {phase: {key: statistics.median(s[key] for s in rows) for key in rows[0]}
            for phase, rows in samples.items() if rows}


def run_station_benchmark(scenario, *, repeats: int = 3, stations=STATIONS) -> dict:
    """All of the above for `scenario` on each station (see the module docstring)."""
    scenarios = {arm: station_scenario(scenario, arm) for arm in stations}
    inputs = {arm: record_plant_inputs(s) for arm, s in scenarios.items()}
    runs = {arm: {"trial": [], "floor": []} for arm in stations}
    timelines = {}
    for _ in range(repeats):
        for arm, s in scenarios.items():
            trial = timed_trial_by_phase(s)
            timelines[arm] = trial["timeline"]
            runs[arm]["trial"].append(trial)
            runs[arm]["floor"].append(timed_floor_by_phase(s, inputs[arm], trial["timeline"]))
    result = {"object": scenario.object.name, "seed": scenario.random_seed,
              "repeats": repeats, "stations": {}}
    for arm in stations:
        trials, floors = runs[arm]["trial"], runs[arm]["floor"]
        result["stations"][arm] = {
            "sim_time_s": trials[0]["sim_time_s"],
            "trial_cpu_s": statistics.median(t["cpu_time_s"] for t in trials),
            "floor_cpu_s": statistics.median(f["cpu_time_s"] for f in floors),
            "trial_rtf_cpu": statistics.median(t["sim_time_s"] / t["cpu_time_s"]
                                               for t in trials),
            "trial_rtf_wall": statistics.median(t["sim_time_s"] / t["wall_time_s"]
                                                for t in trials),
            "floor_rtf_cpu": statistics.median(f["sim_time_s"] / f["cpu_time_s"]
                                               for f in floors),
            "trial_over_floor_cpu": statistics.median(
                (t["cpu_time_s"] / t["sim_time_s"]) / (f["cpu_time_s"] / f["sim_time_s"])
                for t, f in zip(trials, floors)),
            "phase_sim_s": trials[0]["phase_sim_s"],
            "phase_trial_cpu_per_sim_s": _per_sim_s(trials),
            "phase_floor_cpu_per_sim_s": _per_sim_s(floors),
            "floor_step_us": floor_step_breakdown(scenarios[arm], inputs[arm], timelines[arm]),
        }
    return result


def _per_sim_s(runs: list) -> dict:
    """Median over runs of each phase's CPU seconds per simulated second."""
    return {phase: statistics.median(r["phase_cpu_s"][phase] / r["phase_sim_s"][phase]
                                     for r in runs)
            for phase in PHASES if all(r["phase_sim_s"][phase] > 0 for r in runs)}


def format_station_report(result: dict) -> str:
    """The station benchmark as plain-text tables."""
    lines = [f"stations: {result['object']}, seed {result['seed']}, memorized controller, "
             f"{result['repeats']} repeats, medians; rtf = simulated / process CPU time "
             "(wall in brackets)",
             f"{'station':<10} {'sim s':>6} {'trial CPU s':>12} {'floor CPU s':>12} "
             f"{'trial/floor':>12} {'trial rtf':>16} {'floor rtf':>10}"]
    for arm, row in result["stations"].items():
        lines.append(f"{arm:<10} {row['sim_time_s']:>6.2f} {row['trial_cpu_s']:>12.2f} "
                     f"{row['floor_cpu_s']:>12.2f} {row['trial_over_floor_cpu']:>12.2f} "
                     f"{row['trial_rtf_cpu']:>7.2f} ({row['trial_rtf_wall']:>5.2f})"
                     f" {row['floor_rtf_cpu']:>10.2f}")
    for arm, row in result["stations"].items():
        lines += ["", f"{arm}: per phase, CPU ms per simulated s (trial, floor, python = "
                  "their difference) and the floor's step at sampled instants [us]",
                  f"{'phase':<7} {'sim s':>6} {'trial':>6} {'floor':>6} {'python':>7} "
                  f"{'faces':>6} {'step':>6} {'poses':>6} {'surfaces':>9} {'SAP+dyn':>8}"]
        for phase, sim in row["phase_sim_s"].items():
            if sim <= 0:
                continue
            if phase not in row["phase_floor_cpu_per_sim_s"]:
                continue
            trial = row["phase_trial_cpu_per_sim_s"][phase] * 1e3
            floor = row["phase_floor_cpu_per_sim_s"][phase] * 1e3
            step = row["floor_step_us"].get(phase)
            parts = ("" if step is None else
                     f"{step['faces']:>6.0f} {step['step']:>6.0f} {step['poses']:>6.0f} "
                     f"{step['contact_surfaces']:>9.0f} {step['rest']:>8.0f}")
            lines.append(f"{phase:<7} {sim:>6.2f} {trial:>6.0f} {floor:>6.0f} "
                         f"{trial - floor:>7.0f} {parts}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "runs of each station's trial and floor, alternating")
    args = parse_benchmark_arguments(parser, argv)
    result = run_station_benchmark(scenario_from_arguments(args), repeats=args.repeats)
    print(json.dumps(result) if args.json else format_station_report(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
