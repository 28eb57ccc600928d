"""Hardware-loop benchmark: the whole controller diagram on MakeHardwareStation in real time
against the three emulators (each in its own process), measured from the run's log.

- latency, frame arrival -> matcher input: for every tick that showed a new tactile frame,
  the host's monotonic time when the tick's values were built (TEGRASP_TACTILE `tick_s`,
  the tick at which the matcher's update reads them) minus when the reader thread got
  the frame's last byte (`arrival_s`). It covers the queue, the playout buffer and the
  wait for the next 1 kHz tick.
- loop period: the differences of consecutive ticks' `tick_s` (1 ms nominal).
- real-time rate of the run, and the device counters.

Run: `python -m benchmarks.hardware_loop [--duration 10] [--trial NPZ]`; without a
trial, the myRIO replays the drivers benchmark's synthetic pressing and vibration.
"""

import argparse
import dataclasses
import os
import pathlib
import tempfile

import numpy as np

from tegrasp_drake.rig.number_text import number_option
from tegrasp_drake.emulators.myrio_emulator import save_tactile_recording
from benchmarks.drivers import Percentiles, synthetic_trial


def loop_figures(log) -> dict:
    """{"latency": Percentiles, "period": Percentiles, "ticks": int} of a RunLog."""
    tactile = log.tactile
    shown = tactile["tick_s"]
    new = np.flatnonzero(np.diff(tactile["device_t"]) > 0) + 1
    latency = shown[new] - tactile["arrival_s"][new]
    return {"latency": Percentiles.of(latency[np.isfinite(latency)]),
            "period": Percentiles.of(np.diff(shown)), "ticks": len(shown)}


def save_synthetic_trial(path, duration: float):
    """The synthetic trial as the arrays `tegrasp emulate myrio --trial` reads, each pad's
    vibration along x only."""
    trial = synthetic_trial(duration)
    along_x = dataclasses.replace(trial, left_acceleration=trial.left_acceleration[:, 0])
    return save_tactile_recording(path, along_x)


def run_hardware_benchmark(duration: float = 10.0, *, trial=None, overrides=(),
                           lcm_port: int = 7990, log_path=None, verbose: bool = True) -> dict:
    from tegrasp_drake.emulators.emulator_process import EmulatedDevices
    from tegrasp_drake.runs.hardware_run import run_on_hardware
    from tegrasp_drake.runs.hardware_log_reader import read_run_log
    from tegrasp_drake.scenario.scenario import LoadScenario
    with tempfile.TemporaryDirectory() as folder:
        trial = trial or save_synthetic_trial(pathlib.Path(folder) / "trial.npz", duration)
        url = f"udpm://239.255.76.67:{lcm_port + os.getpid() % 7}?ttl=0"
        # The myRIO streams on its own clock from the arm's first command, as the real one
        # free-runs; the watchdog is lenient so that a loaded host's hiccup does not end
        # the run early (the figures are what is measured).
        with EmulatedDevices(lcm_url=url, trial=trial, myrio_sync="start") as devices:
            watchdog = devices.config.watchdog
            watchdog.arm_timeout = watchdog.gripper_timeout = watchdog.tactile_timeout = 1.0
            result = run_on_hardware(LoadScenario(name="box", overrides=overrides),
                                     config=devices.config,
                                     log_path=log_path or pathlib.Path(folder) / "bench.lcmlog",
                                     duration=duration, out=lambda line: None)
        figures = loop_figures(read_run_log(result.log_path))
    figures.update(realtime_rate=result.realtime_rate, faults=[str(f) for f in result.faults],
                   counters=result.device_counters, sim_time=result.sim_time,
                   transitions=result.transitions)
    if verbose:
        modes = " -> ".join(["Reach"] + [t["to"] for t in result.transitions])
        print(f"Hardware loop, {result.sim_time:.1f} s against the emulators ({modes}), "
              f"real-time rate {result.realtime_rate:.3f}, {len(result.faults)} faults")
        print(f"  tactile frame arrival -> matcher input: {figures['latency']}")
        print(f"  1 kHz loop period:                      {figures['period']}")
    return figures


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=number_option, default=10.0)
    parser.add_argument("--trial", default=None, help="a TrialLog .npz to replay")
    parser.add_argument("--log", default=None, help="keep the run's LCM log here")
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE", help="override a field of the box scenario")
    args = parser.parse_args(argv)
    run_hardware_benchmark(args.duration, trial=args.trial, overrides=args.overrides,
                           log_path=args.log)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
