"""Trial benchmark: the real-time factor of full ideal-grasp trials, the cost of one
tactile-pad evaluation while the object is held, and the cost of the films' update per plant
step in free motion and while holding (`tegrasp benchmark` prints them)."""

import statistics
import time

from tegrasp_drake.experiments.grasp_diagram import MakeSimulator
from tegrasp_drake.experiments.ideal_grasp import MakeIdealGraspDiagram, run_ideal_grasp


def _median_call_us(update, context, repeats: int) -> float:
    """Median wall time [us] of update(context, a copy of the context's discrete state)."""
    state = context.get_discrete_state().Clone()
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        update(context, state)
        samples.append((time.perf_counter() - start) * 1e6)
    return statistics.median(samples)


def time_tactile_pad_evaluation(scenario, repeats: int = 200) -> dict:
    """Median wall time [us] of one TactilePads sample while the box is held."""
    grasp = MakeIdealGraspDiagram(scenario)
    diagram, segments = grasp.diagram, grasp.controller.segments
    simulator = MakeSimulator(diagram, scenario)
    simulator.AdvanceTo(next(s.t_start for s in segments if s.phase == "hold") + 0.5)
    pads = diagram.GetSubsystemByName("station").GetSubsystemByName("tactile_pads")
    pads_context = pads.GetMyContextFromRoot(simulator.get_context())
    contacts = pads.GetInputPort("contact_results").Eval(pads_context)
    faces = sum(contacts.hydroelastic_contact_info(i).contact_surface().num_faces()
                for i in range(contacts.num_hydroelastic_contacts()))
    return {"tactile_pad_evaluation_us_median": _median_call_us(pads._sample, pads_context,
                                                                repeats),
            "contact_faces_while_holding": faces}


def time_pad_film_update(scenario, repeats: int = 500) -> dict:
    """Median wall time [us] of one PadFilms update (both pads, one plant step) during the
    reach (free motion) and while the box is held (texture and contact forces read)."""
    grasp = MakeIdealGraspDiagram(scenario)
    diagram, segments = grasp.diagram, grasp.controller.segments
    simulator = MakeSimulator(diagram, scenario)
    films = diagram.GetSubsystemByName("station").GetSubsystemByName("pad_films")
    result = {}
    for label, phase in (("free_motion", "reach"), ("holding", "hold")):
        simulator.AdvanceTo(next(s.t_start for s in segments if s.phase == phase) + 0.5)
        context = films.GetMyContextFromRoot(simulator.get_context())
        result[f"pad_film_update_us_median_{label}"] = _median_call_us(films._update, context,
                                                                       repeats)
    return result


def run_trial_benchmark(scenario, trials: int = 3) -> dict:
    """The real-time factors of `trials` ideal-grasp trials (and their median), the taxel
    rate, `time_tactile_pad_evaluation`'s and `time_pad_film_update`'s figures."""
    factors = []
    for _ in range(trials):
        log, wall = run_ideal_grasp(scenario)
        factors.append(log.meta["sim_time_s"] / wall)
    return {"object": scenario.object.name, "trials": trials,
            "real_time_factor_median": statistics.median(factors),
            "real_time_factors": [round(f, 3) for f in factors],
            "taxel_rate_hz": scenario.tactile.sample_rate_hz,
            **time_tactile_pad_evaluation(scenario), **time_pad_film_update(scenario)}
