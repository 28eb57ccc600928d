"""What one taxel sample costs on a held contact: the contact surfaces read into arrays and the
pressure integrated over the taxels, against the plain way of doing the same. From a checkout:

    python -m benchmarks.pad_contact_reads [--repeats 30] [--json] [--scenario FILE]
        [--scenario-name NAME] [--set KEY=VALUE ...]

The scenario's open-loop grasp runs to 0.5 s into Hold; its contact results are then the fixed
input. Per repeat, alternating (the machine's load drifts), each variant runs BATCH calls of:
  - read: both pads' contact surfaces into pad-frame arrays (tactile_pads._pads_surfaces);
  - integral: their pressure over the 12 taxels of each pad;
  - sample: both together (tactile_pads.pads_forces, what TactilePads does per sample).
Variants: "per element", every triangle's corners and every vertex read by their own
Python-level call and every triangle cut at every cell corner (the reference, below); "bulk",
the package's: pydrake's whole-mesh accessors where it has them, calls mapped where it has
not, and a triangle within one taxel column cut at that column's edge alone. Process CPU per
call [us], medians, bulk over per element; and the largest difference of the two samples'
taxel forces relative to the largest force. `--set plant_config.contact_surface_representation
=polygon` measures the polygon surfaces.
"""

import json
import statistics
import time

import numpy as np

from benchmarks.arguments import benchmark_parser, parse_benchmark_arguments
from tegrasp_drake.commands.scenario_args import scenario_from_arguments
from tegrasp_drake.runs.ideal_grasp import MakeIdealGraspDiagram
from tegrasp_drake.scenario.grasp_diagram import MakeSimulator
from tegrasp_drake.scenario.scenario import with_controller
from tegrasp_drake.simulation import tactile_pads
from tegrasp_drake.simulation.contact_pressure import (cell_pressure_integrals,
                                                       every_corner_cell_integrals,
                                                       surfaces_taxel_normal_forces)
from tegrasp_drake.simulation.tactile_pads import surface_arrays

HOLD_S = 0.5  # into Hold: the grip has settled
BATCH = 10  # calls per timing (process CPU time is read by a system call)
VARIANTS = ("per element", "bulk")


def per_element_surface_arrays(surface) -> tuple:
    """tactile_pads.surface_arrays by one call per triangle corner in a Python loop, and per
    vertex of a triangle mesh too."""
    if surface.is_triangle():
        mesh, field = surface.tri_mesh_W(), surface.tri_e_MN()
        triangles = np.array([[t.vertex(k) for k in range(3)] for t in mesh.triangles()])
    else:
        mesh, field = surface.poly_mesh_W(), surface.poly_e_MN()
        triangles = tactile_pads._fan_triangles(tuple(mesh.face_data()))
    count = mesh.num_vertices()
    p_WV = np.concatenate(list(map(mesh.vertex, range(count)))).reshape(count, 3)
    pressure = np.fromiter(map(field.EvaluateAtVertex, range(count)), float, count)
    return p_WV, pressure, triangles


def _reader(variant: str):
    return surface_arrays if variant == "bulk" else per_element_surface_arrays


def _cells(variant: str):
    return cell_pressure_integrals if variant == "bulk" else every_corner_cell_integrals


def pads_surfaces(variant: str, contacts, geometry_ids, pad_poses) -> list[list]:
    """tactile_pads._pads_surfaces of `variant`."""
    return tactile_pads._pads_surfaces(contacts, geometry_ids, pad_poses, _reader(variant))


def taxel_forces(variant: str, surfaces) -> list[np.ndarray]:
    """The noise-free forces of `surfaces` [(p_PV, pressure_V, triangles)] by `variant`."""
    return surfaces_taxel_normal_forces(surfaces, _cells(variant))


def pads_forces(variant: str, contacts, geometry_ids, pad_poses) -> list[np.ndarray]:
    """tactile_pads.pads_forces of `variant`."""
    return tactile_pads.pads_forces(contacts, geometry_ids, pad_poses,
                                    read_surface=_reader(variant),
                                    cell_integrals=_cells(variant))


def held_contact(scenario):
    """(contact results, pad geometry ids, pad poses function, the surfaces' (faces,
    vertices, representation), the simulator that owns the results) of the scenario's
    open-loop grasp HOLD_S into Hold."""
    grasp = MakeIdealGraspDiagram(with_controller(scenario, "open_loop"))
    hold = next(s.t_start for s in grasp.controller.segments if s.phase == "hold") + HOLD_S
    simulator = MakeSimulator(grasp.diagram, scenario)
    simulator.Initialize()
    simulator.AdvanceTo(hold)
    pads = grasp.diagram.GetSubsystemByName("station").GetSubsystemByName("tactile_pads")
    context = pads.GetMyContextFromRoot(simulator.get_context())
    contacts = pads.GetInputPort("contact_results").Eval(context)
    poses = pads._pad_poses(context)
    surfaces = [contacts.hydroelastic_contact_info(i).contact_surface()
                for i in range(contacts.num_hydroelastic_contacts())]
    shapes = [(s.num_faces(), s.num_vertices(), "triangle" if s.is_triangle() else "polygon")
              for s in surfaces]
    return contacts, list(pads._geometry_ids), (lambda: poses), shapes, simulator


def _cpu_us(function) -> float:
    start = time.process_time()
    for _ in range(BATCH):
        function()
    return (time.process_time() - start) / BATCH * 1e6


def run(scenario, *, repeats: int = 30) -> dict:
    """Per variant and part, the median process CPU per call [us]; see the module docstring."""
    contacts, ids, poses, shapes, _simulator = held_contact(scenario)
    surfaces = {v: [s[:3] for pad in pads_surfaces(v, contacts, ids, poses) for s in pad]
                for v in VARIANTS}
    parts = {"read": lambda v: pads_surfaces(v, contacts, ids, poses),
             "integral": lambda v: taxel_forces(v, surfaces[v]),
             "sample": lambda v: pads_forces(v, contacts, ids, poses)}
    times = {(v, part): [] for v in VARIANTS for part in parts}
    for _ in range(repeats):
        for part, call in parts.items():
            for variant in VARIANTS:
                times[variant, part].append(_cpu_us(lambda: call(variant)))
    medians = {f"{v}/{part}": statistics.median(t) for (v, part), t in times.items()}
    before, after = (np.concatenate(pads_forces(v, contacts, ids, poses)) for v in VARIANTS)
    return {"surfaces": shapes, "repeats": repeats, "median_us": medians,
            "ratio": {part: medians[f"bulk/{part}"] / medians[f"per element/{part}"]
                      for part in parts},
            "max_force_n": float(np.abs(before).max()),
            "max_relative_difference": float(np.abs(after - before).max()
                                             / max(np.abs(before).max(), 1e-300))}


def format_report(result: dict) -> str:
    """The result as a plain-text table."""
    lines = ["held contact: " + ", ".join(f"{faces} faces, {vertices} vertices ({kind})"
                                          for faces, vertices, kind in result["surfaces"]),
             f"{result['repeats']} repeats of {BATCH} calls, process CPU per call, medians",
             f"{'part':<10} {'per element us':>15} {'bulk us':>9} {'bulk/per element':>17}"]
    for part, ratio in result["ratio"].items():
        lines.append(f"{part:<10} {result['median_us'][f'per element/{part}']:>15.0f} "
                     f"{result['median_us'][f'bulk/{part}']:>9.0f} {ratio:>17.2f}")
    lines.append(f"largest taxel force {result['max_force_n']:.3f} N; largest difference "
                 f"between the variants {result['max_relative_difference']:.1e} of it")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "timings of each variant and part, alternating",
                              default_repeats=30)
    args = parse_benchmark_arguments(parser, argv)
    result = run(scenario_from_arguments(args), repeats=args.repeats)
    print(json.dumps(result) if args.json else format_report(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
