"""The cost of each Python LeafSystem in a trial: calls per trial and time per call.

One trial runs under cProfile. A system's callbacks are the functions defined in its class
body or its base classes' in this package (methods and the lambdas of its output ports)
that Drake called from C++. Per class: those calls, and the time spent in them with their
Python callees, less the time in the port Evals they made (an Eval may run another
system's calculation, counted there, or the plant's), which is given apart.
cProfile's own overhead inflates small callbacks, so compare these figures with each other,
and take the trial's real-time factor from an unprofiled run.
"""

import cProfile
import inspect
import pstats

from pydrake.systems.framework import Diagram, LeafSystem

PACKAGE = "tegrasp_drake"


def python_leaf_systems(diagram: Diagram) -> list:
    """Every LeafSystem of this package in `diagram`, sub-diagrams included."""
    found = []
    for system in diagram.GetSystems():
        if isinstance(system, Diagram):
            found.extend(python_leaf_systems(system))
        elif isinstance(system, LeafSystem) and type(system).__module__.startswith(PACKAGE):
            found.append(system)
    return found


def _class_lines(cls) -> tuple[str, int, int]:
    lines, first = inspect.getsourcelines(cls)
    return inspect.getsourcefile(cls), first, first + len(lines)


def _is_called_from_cpp(caller) -> bool:
    return caller[0] == "~"  # cProfile files built-ins (pydrake's C++ entry points) under "~"


def _is_eval(key) -> bool:
    return key[0] == "~" and key[2].endswith("pydrake.systems.framework.Eval>")


def system_costs(stats: pstats.Stats, classes) -> dict:
    """{class name: {"calls", "own_s", "us_per_call", "eval_calls", "eval_s"}} per class in
    `classes`, from profile `stats`: calls is how often C++ called into the class's
    callbacks; own_s the time in them less the time in the Evals they made (an Eval may
    compute another system's output, counted there, or the plant's); eval_s that time."""
    spans = [(cls.__name__, _class_lines(base)) for cls in classes for base in cls.__mro__
             if base is cls or base.__module__.startswith(PACKAGE)]
    costs = {name: {"calls": 0, "total_s": 0.0, "eval_calls": 0, "eval_s": 0.0}
             for name, _ in spans}
    evals = [callers for key, (_, _, _, _, callers) in stats.stats.items() if _is_eval(key)]

    def owner(filename, line):
        return next((name for name, (source, first, last) in spans
                     if filename == source and first <= line < last), None)

    for (filename, line, _), (_, _, _, _, callers) in stats.stats.items():
        name = owner(filename, line)
        if name is None:
            continue
        for caller, (_, calls, _, cumulative) in callers.items():
            if _is_called_from_cpp(caller):
                costs[name]["calls"] += calls
                costs[name]["total_s"] += cumulative
    for callers in evals:
        for (filename, line, _), (_, calls, _, cumulative) in callers.items():
            name = owner(filename, line)
            if name is not None:
                costs[name]["eval_calls"] += calls
                costs[name]["eval_s"] += cumulative
    for cost in costs.values():
        cost["own_s"] = cost.pop("total_s") - cost["eval_s"]
        cost["us_per_call"] = 1e6 * cost["own_s"] / cost["calls"] if cost["calls"] else 0.0
    return costs


def eval_calls(stats: pstats.Stats) -> int:
    """How many times Python called an input port's Eval (what the systems read; cProfile
    does not see an output port's Eval called from Python)."""
    return sum(calls for (filename, _, name), (_, calls, _, _, _) in stats.stats.items()
               if filename == "~" and name.endswith("pydrake.systems.framework.Eval>"))


def profile_trial(scenario, *, events=None) -> dict:
    """One closed-loop trial of `scenario` under cProfile: its simulated and profiled time,
    the input-port Evals from Python, and each Python system's calls and cost (system_costs)."""
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    from tegrasp_drake.runs.trial import run_trial
    grasp = MakeGraspDiagram(scenario, events=events)
    classes = {type(system) for system in python_leaf_systems(grasp.diagram)}
    profiler = cProfile.Profile()
    profiler.enable()
    result = run_trial(scenario, events=events).result
    profiler.disable()
    stats = pstats.Stats(profiler)
    costs = system_costs(stats, classes)
    python_s = sum(cost["own_s"] for cost in costs.values())
    return {"sim_time_s": result["sim_time_s"], "profiled_cpu_time_s": result["cpu_time_s"],
            "python_systems_s": python_s, "eval_calls": eval_calls(stats),
            "systems": dict(sorted(costs.items(), key=lambda item: -item[1]["own_s"]))}
