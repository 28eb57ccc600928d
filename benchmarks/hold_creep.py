"""Hold creep benchmark: how fast a grip held by pad friction alone decays, and what the
contact settings that slow it cost. From a checkout:

    python -m benchmarks.hold_creep [--cells 1e-3:polygon:0 5e-4:triangle:1 ...]
        [--rod-facet 0.002] [--json]

On the gripper bench (simulation/gripper_bench.py) the 2F-85 closes at 25 N on a rigid rod
of the thick cylinder's diameter and friction, 10 mm below the pads' centres: the couplers
leave their pins, the fingertips curl and each is held there by its pad's friction, so
SAP's regularised friction lets the pads creep along the rod and the locked drive unloads
(docs/model.md, "Friction creep"). Each cell is a plant time step [s], a hydroelastic
contact-surface representation and a pad refinement (contact_geometry.pad_refinement);
for each:

  - the grip rate [N/s]: the slope of the pads' mean normal force from 1 to 2 s (the
    fingers stop about 0.75 s after the close command), against the rate the film reads
    at its own noise (tests/simulation/test_gripper_bench.py);
  - the faces of each pad's contact surface and the mean normal force of a face [N] at 2 s;
  - the CPU seconds per simulated second of the hold, the cells advanced in turn 0.1 s at a
    time (only figures measured side by side compare), and each as a ratio to the first
    cell's.

The default cells are the grid of the creep section: time steps 1, 0.5 and 0.25 ms, both
representations, the pad meshes 0, 1 and 2 (18 cells, about 10 min of one core).
`--rod-facet` is the rod's mesh resolution [m]: 2 mm by default (the bench's), 5 mm is the
built-in cylinders' (simulation/object_model.py), which gives fewer faces.
"""

import argparse
import copy
import itertools
import json
import time

import numpy as np
from pydrake.systems.analysis import Simulator

from tegrasp_drake.rig.number_text import number_option
from tegrasp_drake.control.scripted_grasp import gripper_command
from tegrasp_drake.robotiq import linkage
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS
from tegrasp_drake.scenario.scenario import Scenario
from tegrasp_drake.simulation.gripper_bench import BenchObstacle, MakeGripperBench
from tegrasp_drake.simulation.pad_normal_forces import collision_geometry_bodies
from tegrasp_drake.simulation.pad_vibration_sensor import (VibrationSensorConfig,
                                                           ra_noise_std_mps2)

FORCE_N = 25.0
FINGER_SPEED = 0.025  # m/s a finger
ROD = BUILTIN_OBJECTS["thick_cylinder"]
ROD_BELOW_PAD_CENTRES_M = 0.010
SETTLED_S, END_S, CHUNK_S = 1.0, 2.0, 0.1
DEFAULT_CELLS = [f"{step:g}:{representation}:{refinement}" for step, representation, refinement
                 in itertools.product((1e-3, 5e-4, 2.5e-4), ("polygon", "triangle"), (0, 1, 2))]


def quiet_grip_rate() -> float:
    """The grip rate [N/s] the film reads at its own noise: (dF/dt) / (2 pi f_c m)."""
    vibration = VibrationSensorConfig()
    return (ra_noise_std_mps2(vibration) * vibration.film.mode_mass_kg * 2 * np.pi
            * vibration.highpass_cutoff_hz)


def parse_cell(text: str) -> tuple[float, str, int]:
    """(time step [s], representation, pad refinement) of 'STEP:REPRESENTATION:REFINEMENT'."""
    try:
        step, representation, refinement = text.split(":")
        cell = float(step), representation, int(refinement)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"cell '{text}': give STEP:REPRESENTATION:REFINEMENT, e.g. 5e-4:triangle:1")
    if representation not in ("polygon", "triangle"):
        raise argparse.ArgumentTypeError(f"cell '{text}': the representation is polygon or "
                                         "triangle")
    return cell


def build_cell(cell, rod_facet_m: float):
    """A simulator of the bench for `cell`, the grip settled (at SETTLED_S)."""
    step, representation, refinement = cell
    plant_config = copy.copy(Scenario().plant_config)  # the scenario's contact settings
    plant_config.time_step = step
    plant_config.contact_surface_representation = representation
    z = (linkage.PAD_CENTER_OPEN[1] + linkage.pad_travel_at_opening(ROD.width_along_stroke())
         - ROD_BELOW_PAD_CENTRES_M)
    bench = MakeGripperBench(
        command=gripper_command(0.0, 2 * FINGER_SPEED, FORCE_N),
        obstacle=BenchObstacle("rod", (ROD.width_along_stroke(), 0.06), z,
                               friction=ROD.friction, resolution_hint_m=rod_facet_m),
        plant_config=plant_config, pad_refinement=refinement)
    simulator = Simulator(bench.diagram)
    simulator.AdvanceTo(SETTLED_S)
    return bench, simulator


def pad_faces(bench, context) -> list[int]:
    """The faces of each pad's contact surfaces (left, right)."""
    plant = bench.plant
    bodies = [plant.GetBodyByName(f"{finger}_finger", bench.gripper).index()
              for finger in ("left", "right")]
    geometry_body = collision_geometry_bodies(plant)
    results = plant.get_contact_results_output_port().Eval(plant.GetMyContextFromRoot(context))
    faces = [0, 0]
    for i in range(results.num_hydroelastic_contacts()):
        surface = results.hydroelastic_contact_info(i).contact_surface()
        for k, body in enumerate(bodies):
            if body in (geometry_body.get(surface.id_M()), geometry_body.get(surface.id_N())):
                faces[k] += surface.num_faces()
    return faces


def run(cells, rod_facet_m: float) -> list[dict]:
    """The figures of each cell (module docstring)."""
    built = [build_cell(cell, rod_facet_m) for cell in cells]
    samples = [[] for _ in cells]
    cpu = [0.0] * len(cells)
    t = SETTLED_S
    while t < END_S - 1e-9:
        t = min(t + CHUNK_S, END_S)
        for k, (bench, simulator) in enumerate(built):
            start = time.process_time()
            # Sample the grip every 10 ms within the chunk (the samples' cost is the same
            # in every cell).
            for sample_t in np.arange(t - CHUNK_S + 0.01, t + 1e-9, 0.01):
                simulator.AdvanceTo(sample_t)
                context = bench.pad_forces.GetMyContextFromRoot(simulator.get_context())
                samples[k].append((sample_t, float(np.mean(
                    bench.pad_forces.get_output_port().Eval(context)))))
            cpu[k] += time.process_time() - start
    rows = []
    for cell, (bench, simulator), grip, seconds in zip(cells, built, samples, cpu):
        times, forces = np.array(grip).T
        faces = pad_faces(bench, simulator.get_context())
        rows.append({"time_step_s": cell[0], "representation": cell[1],
                     "pad_refinement": cell[2],
                     "grip_rate_n_per_s": float(np.polyfit(times, forces, 1)[0]),
                     "grip_n": float(forces[-1]), "faces_per_pad": faces,
                     "face_force_n": float(forces[-1] / np.mean(faces)),
                     "cpu_s_per_s": seconds / (END_S - SETTLED_S),
                     "cpu_ratio": seconds / cpu[0]})
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", nargs="+", type=parse_cell,
                        default=[parse_cell(c) for c in DEFAULT_CELLS],
                        help="STEP:REPRESENTATION:REFINEMENT, the first the CPU reference")
    parser.add_argument("--rod-facet", type=number_option, default=0.002,
                        help="the rod's mesh resolution [m] (default 0.002)")
    parser.add_argument("--json", action="store_true", help="print the rows as JSON")
    args = parser.parse_args(argv)
    if not 0.0005 <= args.rod_facet <= 0.02:
        parser.error(f"--rod-facet {args.rod_facet}: give 0.0005 to 0.02 m")
    rows = run(args.cells, args.rod_facet)
    if args.json:
        print(json.dumps({"quiet_grip_rate_n_per_s": quiet_grip_rate(), "cells": rows}))
        return 0
    print(f"grip rate the film reads at its noise: {quiet_grip_rate():.2f} N/s")
    print("| time step [ms] | representation | pad refinement | grip rate [N/s] | faces a pad "
          "| N a face | CPU s per s | CPU ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['time_step_s'] * 1e3:g} | {r['representation']} | {r['pad_refinement']} | "
              f"{r['grip_rate_n_per_s']:.3f} | {r['faces_per_pad'][0]}, {r['faces_per_pad'][1]} | "
              f"{r['face_force_n']:.3f} | {r['cpu_s_per_s']:.2f} | {r['cpu_ratio']:.2f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
