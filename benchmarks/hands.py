"""What the linkage hand costs against the prismatic one, side by side in one run.

    python -m benchmarks.hands [--repeats 3]

For each hand: the memorized closed-loop trial of the default scenario (the box on its
marker) with that hand's own memorized events, and the plant-alone floor (the station's plant
replaying that trial's plant inputs). Hands alternate within each repeat; medians of process
CPU time are printed (wall time too, for a loaded host the CPU time is the steadier), with the
linkage-over-prismatic ratios and the floor's cost per plant step.
"""

import argparse
import dataclasses
import statistics

from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.events.events_folder import load_memorized_events
from benchmarks.plant_floor import record_plant_inputs, run_plant_floor
from tegrasp_drake.scenario.scenario import LoadScenario, with_controller
from tegrasp_drake.runs.trial import run_trial
from tegrasp_drake.rig import paths

HANDS = {"prismatic": "prismatic", "linkage": ""}  # hand -> its events' sub-folder


def hand_scenario(hand: str):
    scenario = with_controller(LoadScenario(), "memorized")
    return dataclasses.replace(scenario,
                               gripper=dataclasses.replace(scenario.gripper, model=hand))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=integer_option, default=3)
    repeats = parser.parse_args().repeats
    scenarios = {hand: hand_scenario(hand) for hand in HANDS}
    events = {hand: load_memorized_events(paths.package_events_dir() / folder, "box")
              for hand, folder in HANDS.items()}
    inputs = {hand: record_plant_inputs(scenarios[hand], events=events[hand]) for hand in HANDS}
    runs = {(hand, kind): [] for hand in HANDS for kind in ("trial", "floor")}
    for _ in range(repeats):
        for hand in HANDS:
            result = run_trial(scenarios[hand], events=events[hand]).result
            assert result["hold_success"] and result["unload_success"], hand
            runs[hand, "trial"].append((result["sim_time_s"], result["wall_time_s"],
                                        result["cpu_time_s"]))
            floor = run_plant_floor(scenarios[hand], inputs[hand])
            runs[hand, "floor"].append((floor.sim_time_s, floor.wall_time_s, floor.cpu_time_s))
    medians = {}
    print(f"{'':22s} {'sim s':>7s} {'wall s':>7s} {'CPU s':>7s} {'sim/CPU':>8s}")
    for (hand, kind), samples in runs.items():
        sim, wall, cpu = (statistics.median(s[k] for s in samples) for k in range(3))
        medians[hand, kind] = (sim, wall, cpu)
        print(f"{hand + ' ' + kind:22s} {sim:7.2f} {wall:7.2f} {cpu:7.2f} {sim / cpu:8.2f}")
    for kind in ("trial", "floor"):
        ratio = statistics.median(
            (link[2] / link[0]) / (prism[2] / prism[0])
            for link, prism in zip(runs["linkage", kind], runs["prismatic", kind]))
        print(f"linkage / prismatic {kind} CPU per simulated second (median of repeats): "
              f"{ratio:.2f}")
    for hand in HANDS:
        sim, _, cpu = medians[hand, "floor"]
        steps = sim / scenarios[hand].plant_config.time_step
        print(f"{hand}: plant-alone floor {cpu / steps * 1e3:.3f} ms CPU per plant step; "
              f"trial over floor {medians[hand, 'trial'][2] / medians[hand, 'trial'][0]:.3f}"
              f" / {cpu / sim:.3f} = "
              f"{(medians[hand, 'trial'][2] / medians[hand, 'trial'][0]) / (cpu / sim):.2f}")


if __name__ == "__main__":
    main()
