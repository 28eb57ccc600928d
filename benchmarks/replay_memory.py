"""Memory and time of `tegrasp replay LOG` on generated run logs of 1 kHz tactile messages.

A log is written here as `tegrasp hardware --log` writes one: a TEGRASP_RUN_INFO, then
`messages` TEGRASP_TACTILE messages 1 ms apart that repeat the synthetic grasp's SA and RA
channels, and the first grasp's transitions. Each figure is measured in a fresh process
(what one process allocated and cached does not count in the next), the median of `repeats`:

- read_bytes_per_message: tracemalloc's peak while read_run_log reads the log [B] / messages
  (what Python and numpy allocate, the same on a loaded machine);
- imports_max_rss_mb: the largest resident set [MB] of a process that only imports what the
  replay imports (pydrake, numpy): what the figures below hold beside the log's;
- read_max_rss_mb, read_wall_s: the process's largest resident set [MB] and wall time [s]
  of read_run_log alone;
- replay_max_rss_mb, replay_wall_s: the same of the whole `tegrasp replay LOG --json`
  (reading, then the matcher re-run on the tactile stream twice), with --replay.

Run `python -m benchmarks.replay_memory [--messages 100000 800000] [--repeats 3] [--replay]`;
the logs go to a temporary folder, or --keep DIR.
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile

import numpy as np

from tegrasp_drake.rig.integer_text import integer_option

TACTILE_PERIOD_S = 1e-3


def write_run_log(path, messages: int) -> pathlib.Path:
    """A run log of `messages` tactile messages (module docstring) at `path`."""
    import lcm
    from tegrasp_drake.hardware.device_log_messages import (RUN_INFO_CHANNEL, TACTILE_CHANNEL,
                                                            TRANSITION_CHANNEL)
    from tegrasp_drake.lcmtypes import lcmt_tegrasp_run_info, lcmt_tegrasp_tactile
    from tegrasp_drake.runs.hardware_run import transition_message
    from tegrasp_drake.events.synthetic import SyntheticGraspConfig, synthetic_grasp
    grasp = SyntheticGraspConfig()
    trial = synthetic_grasp(grasp)
    sa_rows = np.minimum(np.searchsorted(trial.t_sa, trial.t_ra, side="right") - 1,
                         len(trial.sa) - 1)
    times = grasp.transition_times()
    transitions = [(times["reach_load"], "Reach", "Load", "memorized_event"),
                   (times["load_lift"], "Load", "Lift", "memorized_event"),
                   (times["lift_hold"], "Lift", "Hold", "timer"),
                   (times["place_unload"] - 0.2, "Hold", "Place", "timer"),
                   (times["place_unload"], "Place", "Unload", "memorized_event")]
    log = lcm.EventLog(str(path), "w", overwrite=True)
    number = 0

    def write(channel, message, utime):
        nonlocal number
        log.write_event(utime, channel, message.encode())
        number += 1

    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name = "memorized", "box"
    info.versions_json = "{}"
    write(RUN_INFO_CHANNEL, info, 0)
    message = lcmt_tegrasp_tactile()
    message.num_taxels = 12
    pending = 0
    for k in range(messages):
        t = (k + 1) * TACTILE_PERIOD_S
        row = k % len(trial.t_ra)
        sa, ra = trial.sa[sa_rows[row]], trial.ra[row]
        message.utime = message.device_utime = round(t * 1e6)
        message.left_taxel_forces = [sa[0] / 12] * 12
        message.right_taxel_forces = [sa[1] / 12] * 12
        message.left_pad_acceleration = [ra[0], 0.0, 0.0]
        message.right_pad_acceleration = [ra[1], 0.0, 0.0]
        message.arrival_s, message.tick_s = t, t + TACTILE_PERIOD_S
        write(TACTILE_CHANNEL, message, message.utime)
        if pending < len(transitions) and transitions[pending][0] <= t:
            when, source, target, trigger = transitions[pending]
            write(TRANSITION_CHANNEL, transition_message(
                {"t": when, "from": source, "to": target, "trigger": trigger,
                 "reason": f"{source}-{target}"}), message.utime)
            pending += 1
    log.close()
    return pathlib.Path(path)


def write_events(folder) -> pathlib.Path:
    """The box's memorized events, felt in the synthetic grasp the logs repeat."""
    from tegrasp_drake.events import extract_memorized_events, save_memorized_events
    from tegrasp_drake.events.synthetic import SyntheticGraspConfig, synthetic_grasp
    from tegrasp_drake.rig.objects import object_description
    from tegrasp_drake.scenario.scenario import LoadScenario
    events = extract_memorized_events(
        synthetic_grasp(SyntheticGraspConfig()), object_name="box", sa_rate_hz=100.0,
        ra_rate_hz=1000.0, package_versions={},
        object_description=object_description(LoadScenario(name="box").object))
    save_memorized_events(folder, events.values())
    return pathlib.Path(folder)


def _measure_in_this_process(what: str, log: str, events: str) -> dict:
    """One measurement (module docstring) in this process, as a dict of figures."""
    import importlib
    import resource
    import time
    import tracemalloc
    from tegrasp_drake.runs.hardware_log_reader import read_run_log
    importlib.import_module("tegrasp_drake.runs.hardware_log_replay")  # what replay imports
    if what == "imports":
        return {"imports_max_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}
    if what == "traced":
        tracemalloc.start()
        run = read_run_log(log)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        return {"read_bytes_per_message": peak / sum(run.message_counts.values())}
    start = time.perf_counter()
    if what == "read":
        read_run_log(log)
    else:
        from tegrasp_drake import cli
        import contextlib
        import io
        with contextlib.redirect_stdout(io.StringIO()):
            code = cli.main(["replay", log, "--events", events, "--json"])
        assert code == 0, code
    wall = time.perf_counter() - start
    rss_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # Linux: kB
    return {f"{what}_max_rss_mb": rss_mb, f"{what}_wall_s": wall}


def _measure(what: str, log, events) -> dict:
    child = subprocess.run(
        [sys.executable, "-m", "benchmarks.replay_memory", "--measure", what, str(log),
         str(events)], check=True, capture_output=True, text=True)
    return json.loads(child.stdout.splitlines()[-1])


def run_replay_memory_benchmark(messages=(100_000, 800_000), *, repeats: int = 3,
                                replay: bool = False, folder=None) -> dict:
    """{messages: {figure: median over repeats}} (module docstring)."""
    results = {}
    with tempfile.TemporaryDirectory() as scratch:
        folder = pathlib.Path(folder or scratch)
        events = write_events(folder / "events")
        for count in messages:
            log = write_run_log(folder / f"tactile_{count}.lcmlog", count)
            kinds = ("imports", "traced", "read") + (("replay",) if replay else ())
            samples = [_measure(kind, log, events) for _ in range(repeats) for kind in kinds]
            figures = {name for sample in samples for name in sample}
            results[count] = {name: statistics.median(s[name] for s in samples if name in s)
                              for name in sorted(figures)}
            results[count]["log_mb"] = log.stat().st_size / 1e6
    return results


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--messages", type=integer_option, nargs="+",
                        default=[100_000, 800_000])
    parser.add_argument("--repeats", type=integer_option, default=3)
    parser.add_argument("--replay", action="store_true",
                        help="also measure the whole `tegrasp replay` (minutes at 800,000)")
    parser.add_argument("--keep", default=None, help="write the logs here and keep them")
    parser.add_argument("--measure", nargs=3, metavar=("WHAT", "LOG", "EVENTS"),
                        help=argparse.SUPPRESS)  # one measurement, in a child process
    args = parser.parse_args(argv)
    if args.measure:
        print(json.dumps(_measure_in_this_process(*args.measure)))
        return
    if args.keep:
        pathlib.Path(args.keep).mkdir(parents=True, exist_ok=True)
    results = run_replay_memory_benchmark(args.messages, repeats=args.repeats,
                                          replay=args.replay, folder=args.keep)
    for count, figures in results.items():
        print(f"{count} tactile messages:")
        for name, value in figures.items():
            print(f"  {name:26s} {value:10.3f}")


if __name__ == "__main__":
    main()
