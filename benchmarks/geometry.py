"""Contact geometry benchmark: what each coarser contact world saves and what it changes.
From a checkout:

    python -m benchmarks.geometry [--repeats 3] [--objects box thick_cylinder] [--json]
        [--set random_seed=600 ...]

For each object, each variant of the contact world (VARIANTS) that changes its plant:
  - its closed-loop memorized trial and that trial's plant-alone floor (plant_floor.py:
    the plant replaying the trial's own plant inputs), CPU seconds, alternating with the
    other variants within each repeat (only figures measured side by side compare), the
    medians, and each as a ratio to the reference geometry's;
  - the floor's CPU ms per simulated second in free motion (reach) and in contact (hold);
  - the contact-surface faces at sampled instants of reach, close and hold (the median);
  - the taxel forces on a fixed scene: the plant replaying the *reference's* trial inputs
    (the same finger and arm motion), the 24 noise-free taxel forces every 10 ms from the
    first touch to the start of Unload, against the reference's at the same instants: the
    largest difference of each taxel [N], their maximum, and the largest force for scale.

The variants: the reference geometry; the box as its corners' convex hull (12 triangles);
the table as a compliant half-space; the cylinder's facets at 10 and 20 mm (not a scenario
setting: they fail the contact world's validation, simulation/contact_meshing.py; measured on the
same cylinder written as a model file, its events the built-in's). A variant that leaves an object's plant as another variant
has it (the box setting on a cylinder) is not run again for that object.
"""

import dataclasses
import json
import pathlib
import statistics
import tempfile

import numpy as np

from benchmarks.plant_floor import build_plant_floor, record_plant_inputs
from benchmarks.station_costs import (floor_step_breakdown, station_scenario,
                                      timed_floor_by_phase, timed_trial_by_phase)
from benchmarks.trial import meshed_object
from benchmarks.arguments import benchmark_parser, parse_benchmark_arguments
from tegrasp_drake.commands.scenario_args import scenario_from_arguments
from tegrasp_drake.rig.objects import ObjectConfig
from tegrasp_drake.scenario.scenario import resolve_object
from tegrasp_drake.simulation.station import pad_geometries
from tegrasp_drake.simulation.tactile_pads import pads_forces

OBJECTS = ("box", "thick_cylinder")
TAXEL_PERIOD_S = 0.01  # taxel forces compared every this [s]
CONTACT_PHASES = ("close", "lift", "hold", "place")  # from the first touch to Unload
FACE_PHASES = ("reach", "close", "hold")


def _with_geometry(**fields):
    return lambda scenario, folder: dataclasses.replace(
        scenario, contact_geometry=dataclasses.replace(scenario.contact_geometry, **fields))


def _cylinder_facets(facet_m: float):
    """The scenario's cylinder at a mesh hint of facet_m [m], as a model file with the
    built-in's name and events (None for other objects)."""
    def variant(scenario, folder):
        if scenario.object.shape != "cylinder":
            return None
        obj = dataclasses.replace(meshed_object(scenario.object, facet_m, folder),
                                  name=scenario.object.name)
        controller = dataclasses.replace(scenario.controller, event_object_may_differ=[
            *scenario.controller.event_object_may_differ, "shape", "size", "file"])
        return dataclasses.replace(scenario, object=obj, controller=controller)
    return variant


VARIANTS = {
    "reference": lambda scenario, folder: scenario,
    "box_12_triangles": _with_geometry(box_triangles=12),
    "table_half_space": _with_geometry(table="half_space"),
    "cylinder_facets_10mm": _cylinder_facets(0.010),
    "cylinder_facets_20mm": _cylinder_facets(0.020),
}


def _plant_key(scenario) -> tuple:
    """What of a scenario's contact world its plant is built from."""
    geometry = scenario.contact_geometry
    box = geometry.box_triangles if scenario.object.shape == "box" else None
    return scenario.object.shape, scenario.object.file, box, geometry.table


def replayed_taxel_forces(scenario, inputs, times) -> np.ndarray:
    """The 24 noise-free taxel forces [N] (left pad's 12, then the right's) of `scenario`'s
    plant replaying `inputs`, at each of `times` [s]: shape (len(times), 24)."""
    simulator, parts = build_plant_floor(scenario, inputs)
    plant = parts.plant
    pads = list(pad_geometries(plant, parts.scene_graph, parts.gripper).values())
    context = plant.GetMyContextFromRoot(simulator.get_context())

    def pad_poses():
        return [plant.EvalBodyPoseInWorld(context, plant.get_body(pad.body_index)) @ pad.X_BP
                for pad in pads]

    rows = []
    simulator.Initialize()
    for t in times:
        simulator.AdvanceTo(t)
        contact = plant.get_contact_results_output_port().Eval(context)
        rows.append(np.concatenate(pads_forces(
            contact, [pad.geometry_id for pad in pads], pad_poses)))
    return np.array(rows)


def _contact_times(timeline: list) -> np.ndarray:
    """Instants every TAXEL_PERIOD_S [s] through the contact phases of a trial's timeline."""
    spans = [(t, t_next) for (t, phase), (t_next, _) in zip(timeline, timeline[1:])
             if phase in CONTACT_PHASES]
    # On the grid k TAXEL_PERIOD_S, each span's [start, end), whatever the rounding.
    steps = [np.arange(np.ceil(t0 / TAXEL_PERIOD_S - 1e-9), np.ceil(t1 / TAXEL_PERIOD_S - 1e-9))
             for t0, t1 in spans]
    return np.concatenate(steps) * TAXEL_PERIOD_S


def run_object(scenario, *, repeats: int, folder: pathlib.Path) -> dict:
    """Every variant that changes `scenario`'s plant (module docstring), measured."""
    variants, seen, same = {}, {}, {}
    for name, make in VARIANTS.items():
        variant = make(scenario, folder)
        if variant is None:
            continue
        key = _plant_key(variant)
        if key in seen:
            same[name] = seen[key]
            continue
        seen[key] = name
        variants[name] = variant
    inputs = {name: record_plant_inputs(s) for name, s in variants.items()}
    trials = {name: [] for name in variants}
    floors = {name: [] for name in variants}
    for _ in range(repeats):
        for name, s in variants.items():
            trial = timed_trial_by_phase(s)
            trials[name].append(trial)
            floors[name].append(timed_floor_by_phase(s, inputs[name], trial["timeline"]))
    reference_timeline = trials["reference"][0]["timeline"]
    times = _contact_times(reference_timeline)
    reference_forces = replayed_taxel_forces(variants["reference"], inputs["reference"], times)
    rows = {}
    for name, s in variants.items():
        faces = floor_step_breakdown(s, inputs[name], trials[name][0]["timeline"])
        forces = replayed_taxel_forces(s, inputs["reference"], times)
        difference = np.abs(forces - reference_forces).max(axis=0)
        rows[name] = {
            "trial_cpu_s": statistics.median(t["cpu_time_s"] for t in trials[name]),
            "floor_cpu_s": statistics.median(f["cpu_time_s"] for f in floors[name]),
            "floor_ms_per_s": {phase: 1e3 * statistics.median(
                f["phase_cpu_s"][phase] / f["phase_sim_s"][phase] for f in floors[name])
                for phase in ("reach", "hold")
                if all(f["phase_sim_s"][phase] > 0 for f in floors[name])},
            "faces": {phase: faces[phase]["faces"] for phase in FACE_PHASES if phase in faces},
            "taxel_max_abs_difference_n": difference.tolist(),
            "taxel_max_force_n": float(reference_forces.max()),
        }
    for row in rows.values():
        row["trial_ratio"] = row["trial_cpu_s"] / rows["reference"]["trial_cpu_s"]
        row["floor_ratio"] = row["floor_cpu_s"] / rows["reference"]["floor_cpu_s"]
    return {"variants": rows, "same_plant_as": same}


def run_geometry_benchmark(scenario, *, objects=OBJECTS, repeats: int = 3) -> dict:
    """run_object for each of `objects` (the memorized controller on the full arm)."""
    result = {"seed": scenario.random_seed, "repeats": repeats, "objects": {}}
    base = station_scenario(scenario, "jaco2")
    with tempfile.TemporaryDirectory(prefix="tegrasp-geometry-") as folder:
        for name in objects:
            obj = resolve_object(ObjectConfig(name=name))
            result["objects"][name] = run_object(dataclasses.replace(base, object=obj),
                                                 repeats=repeats, folder=pathlib.Path(folder))
    return result


def format_geometry_report(result: dict) -> str:
    """The benchmark as plain-text tables, one per object."""
    lines = [f"contact geometry: seed {result['seed']}, memorized controller on the full arm, "
             f"{result['repeats']} repeats, medians of process CPU time; x ref = the "
             "reference geometry's ratio in the same run",
             "free / contact: the floor's CPU ms per simulated s in reach / hold; faces: "
             "contact-surface faces in reach / close / hold; taxel |dF|: largest difference "
             "from the reference over the contact phases, replaying its inputs [N]"]
    for name, measured in result["objects"].items():
        rows = measured["variants"]
        lines += ["", name,
                  f"{'variant':<22} {'trial s':>8} {'x ref':>6} {'floor s':>8} {'x ref':>6} "
                  f"{'free':>5} {'contact':>8} {'faces':>12} {'taxel |dF|':>11} "
                  f"{'of max F':>9}"]
        for variant, row in rows.items():
            ms = row["floor_ms_per_s"]
            faces = " / ".join(f"{row['faces'].get(p, 0):.0f}" for p in FACE_PHASES)
            lines.append(
                f"{variant:<22} {row['trial_cpu_s']:>8.2f} {row['trial_ratio']:>6.2f} "
                f"{row['floor_cpu_s']:>8.2f} {row['floor_ratio']:>6.2f} "
                f"{ms.get('reach', float('nan')):>5.0f} {ms.get('hold', float('nan')):>8.0f} "
                f"{faces:>12} {max(row['taxel_max_abs_difference_n']):>11.3f} "
                f"{row['taxel_max_force_n']:>9.2f}")
        for variant, other in measured["same_plant_as"].items():
            lines.append(f"{variant:<22} the same plant as {other}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "runs of each variant's trial and floor, alternating")
    parser.add_argument("--objects", nargs="+", default=list(OBJECTS),
                        help="built-in objects to measure (default: box thick_cylinder)")
    args = parse_benchmark_arguments(parser, argv)
    scenario = scenario_from_arguments(args)
    if args.json:
        print(json.dumps(run_geometry_benchmark(scenario, objects=args.objects,
                                                repeats=args.repeats)))
        return 0
    for k, name in enumerate(args.objects):  # each object's table as soon as it is measured
        result = run_geometry_benchmark(scenario, objects=[name], repeats=args.repeats)
        report = format_geometry_report(result)
        print(report if k == 0 else report.split("\n", 2)[2], flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
