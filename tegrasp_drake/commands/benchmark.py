"""`tegrasp benchmark`: real-time factor of a full trial and the cost of the sensor systems."""

import json
import statistics
import time

import numpy as np

from tegrasp_drake.commands.scenario_args import add_scenario_arguments, scenario_from_arguments


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "benchmark", help="print the real-time factor of an ideal-grasp trial and the cost of "
        "one tactile-pad evaluation (medians)")
    add_scenario_arguments(parser)
    parser.add_argument("--trials", type=int, default=3, help="full trials to time")
    parser.add_argument("--json", action="store_true")
    parser.set_defaults(func=run)


def time_tactile_pad_evaluation(scenario, repeats: int = 200) -> dict:
    """Median wall time [us] of one TactilePads sample while the box is held."""
    from pydrake.systems.analysis import Simulator
    from tegrasp_drake.experiments.ideal_grasp import build_ideal_grasp_diagram
    diagram, _, segments = build_ideal_grasp_diagram(scenario)
    simulator = Simulator(diagram)
    simulator.AdvanceTo(next(s.t_start for s in segments if s.phase == "hold") + 0.5)
    context = simulator.get_context()
    pads = diagram.GetSubsystemByName("station").GetSubsystemByName("tactile_pads")
    pads_context = pads.GetMyContextFromRoot(context)
    state = pads_context.get_discrete_state().Clone()
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        pads._sample(pads_context, state)
        samples.append((time.perf_counter() - start) * 1e6)
    contacts = pads.GetInputPort("contact_results").Eval(pads_context)
    faces = sum(contacts.hydroelastic_contact_info(i).contact_surface().num_faces()
                for i in range(contacts.num_hydroelastic_contacts()))
    return {"tactile_pad_evaluation_us_median": statistics.median(samples),
            "contact_faces_while_holding": faces}


def run(args) -> int:
    scenario = scenario_from_arguments(args)
    from tegrasp_drake.experiments.ideal_grasp import run_ideal_grasp
    factors = []
    for _ in range(args.trials):
        log, wall = run_ideal_grasp(scenario)
        factors.append(log.meta["sim_time_s"] / wall)
    result = {"object": scenario.object.name, "trials": args.trials,
              "real_time_factor_median": statistics.median(factors),
              "real_time_factors": [round(f, 3) for f in factors],
              "taxel_rate_hz": scenario.tactile.sample_rate_hz,
              **time_tactile_pad_evaluation(scenario)}
    if args.json:
        print(json.dumps(result))
    else:
        for key, value in result.items():
            print(f"{key}: {np.round(value, 3) if isinstance(value, float) else value}")
    return 0
