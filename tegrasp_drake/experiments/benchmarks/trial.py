"""Trial benchmark: the real-time factor of full ideal-grasp trials, and the cost of one
tactile-pad evaluation while the object is held (`tegrasp benchmark` prints them)."""

import statistics
import time

from tegrasp_drake.experiments.grasp_diagram import MakeSimulator
from tegrasp_drake.experiments.ideal_grasp import MakeIdealGraspDiagram, run_ideal_grasp


def time_tactile_pad_evaluation(scenario, repeats: int = 200) -> dict:
    """Median wall time [us] of one TactilePads sample while the box is held."""
    grasp = MakeIdealGraspDiagram(scenario)
    diagram, segments = grasp.diagram, grasp.controller.segments
    simulator = MakeSimulator(diagram, scenario)
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


def run_trial_benchmark(scenario, trials: int = 3) -> dict:
    """The real-time factors of `trials` ideal-grasp trials (and their median), the taxel
    rate and `time_tactile_pad_evaluation`'s figures."""
    factors = []
    for _ in range(trials):
        log, wall = run_ideal_grasp(scenario)
        factors.append(log.meta["sim_time_s"] / wall)
    return {"object": scenario.object.name, "trials": trials,
            "real_time_factor_median": statistics.median(factors),
            "real_time_factors": [round(f, 3) for f in factors],
            "taxel_rate_hz": scenario.tactile.sample_rate_hz,
            **time_tactile_pad_evaluation(scenario)}
