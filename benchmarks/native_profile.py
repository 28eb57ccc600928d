"""Where a closed-loop trial's CPU time goes, C++ included. From a checkout:

    python -m benchmarks.native_profile [--rate HZ] [--json] [--scenario FILE]
        [--scenario-name NAME] [--set KEY=VALUE ...]

cProfile (system_costs.py) sees the Python systems' own calls only; the rest of a trial is
C++: the plant's step, the plant outputs that other systems evaluate, Drake's own systems
and the framework's event dispatch and cache invalidation. This command runs the scenario's
memorized trial in a child process under py-spy (`--native`: C++ frames too; the 'bench'
extra) and sorts every sample taken inside Simulator::AdvanceTo by the part of the diagram
it was in: the innermost Python system whose callback Drake was running, else the first of
the plant step's PARTS that the stack shows, else the innermost of Drake's own systems that
the package builds its compiled chains from (COMPILED_SYSTEMS, by class), else the rest of
PARTS. A system's share includes the plant outputs its Evals computed (the taxels' contact
results, say) but not another Python system's calculation that an Eval ran (counted
there). py-spy stops the child for every sample, which inflates its CPU time (by about a
third at the default rate), so the trial runs twice: alone, for
its process CPU time (run_trial's), and under py-spy, for the shares; each share of the
first run's CPU time is given in milliseconds per simulated second. The host's load falls
on the two runs differently: compare shares, and CPU figures only from one run on an idle
host.
"""

import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

from tegrasp_drake.rig.integer_text import integer_option
from benchmarks.arguments import benchmark_parser
from tegrasp_drake.commands.scenario_args import scenario_from_arguments
from tegrasp_drake.scenario.scenario import scenario_to_yaml, with_controller

DEFAULT_RATE_HZ = 250  # samples per second of the profiled run: about 10,000 a trial
INSIDE = "Simulator<double>::AdvanceTo"
_PYTHON_FRAME = re.compile(r"^(?P<function>\S+) \((?P<file>[^:()]+\.py):\d+\)$")

# (part, a substring of some frame of the sample's stack) in order: the first match names
# the part of a sample taken in no callback of this package's Python systems.
PARTS = (
    ("plant step: contact surfaces", "ComputeContactSurfaces"),
    ("plant step: SAP solve", "SapSolver"),
    ("differential IK", "DifferentialInverseKinematics"),
    ("loggers", "VectorLogSink"),
    ("plant step: other", "MultibodyPlant<double>::CalcStep"),
    ("plant step: other", "DiscreteUpdateManager"),
    # The last step's results (contact surfaces among them) freed as the next is stored.
    ("plant step: other", "DiscreteStepMemory"),
    ("plant step: other", "~ContactSurface"),
    ("plant step: other", "~DeformableContact"),
    ("plant outputs read by Drake systems", "multibody::"),
    ("plant outputs read by Drake systems", "geometry::"),
)
FRAMEWORK = "Drake framework and other Drake systems"
# Drake's systems of the compiled chains (film_chain.py, the channels, the slip band, the
# drives' vibration, the sample registers), by the class a sample's C++ frame names, and the
# part each is counted in. A MatrixGain or LinearSystem runs AffineSystem's code.
COMPILED_SYSTEMS = {
    "SymbolicVectorSystem": "SymbolicVectorSystem",
    "TimeVaryingAffineSystem": "LinearSystem, MatrixGain",
    "AffineSystem": "LinearSystem, MatrixGain",
    "LinearSystem": "LinearSystem, MatrixGain",
    "MatrixGain": "LinearSystem, MatrixGain",
    "ZeroOrderHold": "ZeroOrderHold, DiscreteTimeDelay",
    "DiscreteTimeDelay": "ZeroOrderHold, DiscreteTimeDelay",
    "Multiplexer": "Multiplexer, Demultiplexer",
    "Demultiplexer": "Multiplexer, Demultiplexer",
    "Accelerometer": "Accelerometer",
    "RandomSource": "RandomSource",
}
_DRAKE_SYSTEM_FRAME = re.compile(r"drake::systems::(?:sensors::)?(?P<name>\w+?)(?:<double>)?::")
# PARTS ahead of the compiled systems: all but the plant outputs, which a system's Eval runs.
_STEP_PARTS = PARTS[:-2]


def sample_part(frames: list[str]) -> str:
    """The part of the diagram one sample (its frames, outermost first) was taken in: the
    class of the innermost callback of this package that Drake called (a method's Python
    frame entered from C++) within AdvanceTo, else a PARTS entry."""
    inside = next((k for k, frame in enumerate(frames) if INSIDE in frame), None)
    if inside is None:
        return ""
    below = frames[inside + 1:]
    owner, from_python = None, False
    for frame in below:
        match = _PYTHON_FRAME.match(frame)
        if match is None:
            from_python = False
            continue
        function = match["function"]
        if not from_python and "tegrasp_drake" in match["file"] and "." in function:
            owner = function.split(".")[0]
        from_python = True
    if owner is not None:
        return f"Python: {owner}"
    text = ";".join(below)
    step = next((part for part, marker in _STEP_PARTS if marker in text), None)
    if step is not None:
        return step
    for frame in reversed(below):
        match = _DRAKE_SYSTEM_FRAME.match(frame)
        if match is not None and match["name"] in COMPILED_SYSTEMS:
            return f"Drake system: {COMPILED_SYSTEMS[match['name']]}"
    return next((part for part, marker in PARTS if marker in text), FRAMEWORK)


def parts_from_raw(text: str) -> dict[str, int]:
    """{part: samples} of py-spy's raw output (one 'frame;frame;... count' line per stack),
    the samples inside AdvanceTo only."""
    counts: dict[str, int] = {}
    for line in text.splitlines():
        stack, _, count = line.rpartition(" ")
        if not stack or not count.isdigit():
            continue
        part = sample_part(stack.split(";"))
        if part:
            counts[part] = counts.get(part, 0) + int(count)
    return counts


# The child: run_trial on a scenario file; writes its simulated and process CPU time to a
# file (py-spy prints on the same stdout).
_CHILD = """
import json, pathlib, sys
from tegrasp_drake.runs.trial import run_trial
from tegrasp_drake.scenario.scenario import scenario_from_yaml
result = run_trial(scenario_from_yaml(pathlib.Path(sys.argv[1]).read_text())).result
pathlib.Path(sys.argv[2]).write_text(json.dumps(
    {"cpu_s": result["cpu_time_s"], "sim_time_s": result["sim_time_s"]}))
"""


def _run_child(command: list[str], scenario_file: pathlib.Path, times: pathlib.Path):
    """Runs the child (under `command`, e.g. py-spy's, or none); its exit status and stderr."""
    child = subprocess.run([*command, sys.executable, "-c", _CHILD, str(scenario_file),
                            str(times)], capture_output=True, text=True, check=False)
    return child.returncode == 0 and times.exists(), child.stderr


def profile_native(scenario, *, rate_hz: int = DEFAULT_RATE_HZ) -> dict:
    """The memorized trial of `scenario` run twice in child processes, once alone for its
    CPU time and once under py-spy for the shares: {"sim_time_s", "cpu_s", "samples",
    "parts": {part: {"share", "ms_per_sim_s"}}}."""
    py_spy = shutil.which("py-spy") or str(pathlib.Path(sys.executable).parent / "py-spy")
    if not os.access(py_spy, os.X_OK):
        raise SystemExit("benchmarks.native_profile: error: py-spy is not installed: "
                         "pip install '.[bench]' (or py-spy==0.4.3), then run it again")
    scenario = with_controller(scenario, "memorized")
    with tempfile.TemporaryDirectory() as folder:
        scenario_file = pathlib.Path(folder, "scenario.yaml")
        scenario_file.write_text(scenario_to_yaml(scenario))
        times = pathlib.Path(folder, "times.json")
        ok, stderr = _run_child([], scenario_file, times)
        if not ok:
            last = (stderr.strip().splitlines() or ["no output"])[-1]
            raise SystemExit(f"benchmarks.native_profile: error: the trial failed: {last}")
        measured = json.loads(times.read_text())
        raw = pathlib.Path(folder, "samples.txt")
        ok, stderr = _run_child([py_spy, "record", "--native", "--rate", str(rate_hz),
                                 "--format", "raw", "--output", str(raw), "--"],
                                scenario_file, pathlib.Path(folder, "profiled.json"))
        if not ok or not raw.exists():
            last = (stderr.strip().splitlines() or ["no output"])[-1]
            raise SystemExit(f"benchmarks.native_profile: error: py-spy could not profile "
                             f"the trial ({last}); it needs permission to trace its child "
                             "(ptrace)")
        counts = parts_from_raw(raw.read_text())
    total = sum(counts.values())
    return {"sim_time_s": measured["sim_time_s"], "cpu_s": measured["cpu_s"],
            "samples": total,
            "parts": {part: {"share": n / total,
                             "ms_per_sim_s": 1e3 * measured["cpu_s"] * n / total
                             / measured["sim_time_s"]}
                      for part, n in sorted(counts.items(), key=lambda item: -item[1])}}


def format_report(result: dict) -> str:
    """The profile as a plain-text table."""
    real_time = result["sim_time_s"] / result["cpu_s"]
    lines = [f"memorized trial, {result['sim_time_s']:.2f} s simulated, "
             f"{result['cpu_s']:.2f} CPU s unprofiled ({real_time:.2f}x real time), "
             f"{result['samples']} samples inside AdvanceTo under py-spy",
             f"{'part':<44} {'share':>7} {'CPU ms per sim s':>17}"]
    for part, figures in result["parts"].items():
        lines.append(f"{part:<44} {100 * figures['share']:>6.1f}% "
                     f"{figures['ms_per_sim_s']:>17.0f}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "must be 1: one profiled trial a run",
                              default_repeats=1)
    parser.add_argument("--rate", type=integer_option, default=DEFAULT_RATE_HZ, metavar="HZ",
                        help=f"py-spy's samples per second (default {DEFAULT_RATE_HZ})")
    args = parser.parse_args(argv)
    if args.repeats != 1:
        parser.error(f"--repeats {args.repeats}: this benchmark profiles one trial a run; "
                     "run it again for another")
    if args.rate < 1:
        parser.error(f"--rate {args.rate}: give at least 1 sample per second")
    result = profile_native(scenario_from_arguments(args), rate_hz=args.rate)
    print(json.dumps(result) if args.json else format_report(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
