"""What processing the film's 1 kHz samples in blocks saves (controller.sensor_block_s).

In one run, alternating within each repeat: the memorized closed-loop trial with the
tactile systems taking one sample per update (sensor_block_s 0) and in blocks (the
scenario's sensor_block_s, or 10 ms when it takes one sample per update): real-time factors (medians) and the
per-repeat ratio of their CPU times; then one profiled trial of each, the cost per
simulated second of each Python system that the blocks change; and the slip band alone
(a stream of random samples -> AddSlipVibrationBand, its sample register included), CPU
microseconds per 1 kHz tick both ways (the matcher's: benchmarks/matcher.py).

Run `python -m benchmarks.sensor_blocks` to print them.
"""

import argparse
import dataclasses
import statistics
import time

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from tegrasp_drake.rig.integer_text import integer_option
from benchmarks.system_costs import profile_trial
from benchmarks.trial import time_trial
from tegrasp_drake.scenario.scenario import LoadScenario, with_controller
from tegrasp_drake.tactile.sample_block import BLOCK_PERIOD_S, block_samples
from tegrasp_drake.tactile.slip_vibration_band import AddSlipVibrationBand

RATE_HZ = 1000.0  # the film's samples
BAND_SECONDS = 3.0  # simulated per slip band measurement

# The systems whose updates the blocks change (system_costs.py names them by class).
BLOCK_SYSTEMS = ("EventMatcher", "SlipVibrationBand", "MechanoreceptorChannels")


def with_sensor_block(scenario, block_s: float):
    """`scenario` with the memorized controller taking samples in blocks of block_s [s]."""
    memorized = with_controller(scenario, "memorized")
    return dataclasses.replace(memorized, controller=dataclasses.replace(
        memorized.controller, sensor_block_s=block_s))


def compare_sensor_blocks(scenario, *, repeats: int = 3, profile: bool = True) -> dict:
    """{"per_sample": ..., "blocks": ..., "cpu_ratio": per-sample CPU time over the blocks'
    (median of the repeats), "systems": {variant: {system: us per simulated second}}}."""
    block_s = scenario.controller.sensor_block_s or BLOCK_PERIOD_S
    variants = {"per_sample": with_sensor_block(scenario, 0.0),
                "blocks": with_sensor_block(scenario, block_s)}
    runs = {name: [] for name in variants}
    for _ in range(repeats):
        for name, variant in variants.items():
            runs[name].append(time_trial(variant))
    result = {name: {key: statistics.median(run[key] for run in variant_runs)
                     for key in ("rtf_cpu", "rtf_wall", "cpu_time_s", "wall_time_s")}
              for name, variant_runs in runs.items()}
    result["cpu_ratio"] = statistics.median(
        a["cpu_time_s"] / b["cpu_time_s"] for a, b in zip(runs["per_sample"], runs["blocks"]))
    result["block_s"] = variants["blocks"].controller.sensor_block_s
    result["slip_band_tick_us"] = {
        "per_sample": slip_band_tick_us(1),
        "blocks": slip_band_tick_us(block_samples(RATE_HZ, block_s))}
    if profile:
        result["systems"] = {}
        for name, variant in variants.items():
            profiled = profile_trial(variant)
            result["systems"][name] = {
                system: {"calls": cost["calls"],
                         "ms_per_sim_s": 1e3 * cost["own_s"] / profiled["sim_time_s"]}
                for system, cost in profiled["systems"].items()}
    return result


def slip_band_tick_us(block: int, *, repeats: int = 5) -> float:
    """Median CPU microseconds per 1 kHz tick of a random 6-axis stream filtered by
    AddSlipVibrationBand in blocks of `block` samples (1: per tick), after 0.1 s."""
    samples = np.random.default_rng(0).normal(size=(int(BAND_SECONDS * RATE_HZ) + 1, 6))
    breaks = np.arange(len(samples)) / RATE_HZ

    def measure():
        builder = DiagramBuilder()
        source = builder.AddSystem(TrajectorySource(
            PiecewisePolynomial.ZeroOrderHold(breaks, samples.T)))
        AddSlipVibrationBand(builder, source.get_output_port(), band_hz=80.0, window_s=0.01,
                             sample_rate_hz=RATE_HZ, block_samples=block)
        simulator = Simulator(builder.Build())
        simulator.AdvanceTo(0.1)
        start = time.process_time()
        simulator.AdvanceTo(BAND_SECONDS - 0.01)
        return (time.process_time() - start) / ((BAND_SECONDS - 0.11) * RATE_HZ) * 1e6
    return statistics.median(measure() for _ in range(repeats))


def format_sensor_blocks(result: dict) -> str:
    """The comparison as plain-text tables."""
    lines = [f"tactile samples per update: one (per_sample) or blocks of "
             f"{result['block_s'] * 1e3:g} ms; medians; cpu ratio = per-sample CPU time / "
             f"blocks' (per repeat, median) = {result['cpu_ratio']:.3f}",
             f"{'variant':<12} {'rtf cpu':>8} {'rtf wall':>9}"]
    for name in ("per_sample", "blocks"):
        lines.append(f"{name:<12} {result[name]['rtf_cpu']:>8.3f} "
                     f"{result[name]['rtf_wall']:>9.3f}")
    if "slip_band_tick_us" in result:
        band = result["slip_band_tick_us"]
        lines += ["", f"slip band alone, CPU per 1 kHz tick: {band['per_sample']:.1f} us per "
                  f"sample, {band['blocks']:.1f} us in blocks"]
    if "systems" in result:
        lines += ["", "profiled (cProfile), own time per simulated second [ms/s] and calls",
                  f"{'system':<26} {'per_sample':>11} {'calls':>7} {'blocks':>8} {'calls':>7}"]
        per_sample, blocks = result["systems"]["per_sample"], result["systems"]["blocks"]
        for system in per_sample:
            a, b = per_sample[system], blocks.get(system, {"ms_per_sim_s": 0.0, "calls": 0})
            lines.append(f"{system:<26} {a['ms_per_sim_s']:>11.1f} {a['calls']:>7} "
                         f"{b['ms_per_sim_s']:>8.1f} {b['calls']:>7}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scenario-name", default="box")
    parser.add_argument("--seed", type=integer_option, default=600)
    parser.add_argument("--repeats", type=integer_option, default=3)
    parser.add_argument("--no-profile", action="store_true")
    args = parser.parse_args(argv)
    if args.repeats < 1:
        parser.error(f"--repeats {args.repeats}: give at least 1 run per variant")
    scenario = dataclasses.replace(LoadScenario(name=args.scenario_name),
                                   random_seed=args.seed)
    print(format_sensor_blocks(compare_sensor_blocks(scenario, repeats=args.repeats,
                                                     profile=not args.no_profile)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
