"""`tegrasp sweep`: the paper's grasping experiment over objects, markers and controllers.

Runs every trial without a finished record in `--out` (so the same command resumes), then
writes the reports and figures there (docs/sweeps.md); options override the spec file.
Exit codes: 0 all trials finished, 1 some raised or were left unfinished, 2 bad input.
Testing hook: `--trial-function MODULE:ATTR` (hidden from --help) replaces the real trial
function, so the tests run the command with a cheap deterministic trial."""

import argparse
import contextlib
import dataclasses
import importlib
import re
import sys

from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.commands.progress import progress_wanted
from tegrasp_drake.commands.run_folder import logs_folder_problem, other_run_problem
from tegrasp_drake.commands.events_option import check_events_folder
from tegrasp_drake.figures.figure_files import FIGURE_FORMATS
from tegrasp_drake.reports import FIGURE_STEMS, report_starts, write_reports
from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig.api_boundary import bound_arguments
from tegrasp_drake.rig.files import (FOLDER_HELD, error_line, folder_problem,
                                     unprobed_folder_checks)
from tegrasp_drake.rig.echo import shorten, shown
from tegrasp_drake.rig.number_text import count_text
from tegrasp_drake.sweep.runner import (
    BENCHMARK_WORKER_COUNTS,
    RecordPlaceError,
    SchedulerLostError,
    SweepError,
    benchmark_spec,
    benchmark_text,
    check_sweep_folder,
    run_benchmark,
    run_sweep,
    scheduler_address,
    summary_text,
)
from tegrasp_drake.sweep.spec import (
    BUILTIN_OBJECTS,
    CONFIRM_OPTION,
    CONTROLLER_NAMES,
    MAX_CONFIRMED_TRIALS,
    MAX_TRIALS,
    SweepSpec,
    check_sweep_size,
    core_hours,
    marker_names,
    TRIAL_CORE_SECONDS,
    trial_count,
    validate_spec,
)
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tegrasp_drake.rig.typed_yaml import (ConfigError, RefinedSettings, UnreadableFileError,
                                         set_option)
from tegrasp_drake.rig.usage_parser import AppendSettings

DEFAULT_TRIAL_FUNCTION = "tegrasp_drake.sweep.trial_function:run_trial_from_spec"
DEFAULT_OUT = "results/sweep"
# Where `--benchmark` runs the sweep it times.
BENCHMARK_RUNS = (f"{' and then '.join(map(str, BENCHMARK_WORKER_COUNTS))} worker(s), each "
                  "into a temporary folder")

EPILOG = """\
examples:
  tegrasp sweep --out results/sweep            # Table I: 3 objects x 9 markers x 3, 3 controllers
  tegrasp sweep --objects box --controllers memorized --attempts 1 --workers 2 --out out/box
  tegrasp sweep --spec analysis/example_sweep.yaml --scheduler tcp://10.0.0.5:8786
  tegrasp sweep --objects box --set controller.memorized_corrective.events=[hold_avoid] \
      --set disturbance.hit_time_s=7.0 --out out/hit   # memorized Avoid against a hit

Re-running a command into the same --out resumes the sweep: finished trials are kept and
only the missing ones run. Reports: table1.md/.csv, statistics.md/.json, summary.md (the
README's results table) and success_maps.png."""


def add_runner_arguments(parser: argparse.ArgumentParser, *, default_out: str) -> None:
    """Where and how a sweep's trials run: --workers, --out, --scheduler, --no-progress,
    and the reports' --format."""
    parser.add_argument("--workers", type=integer_option, metavar="N",
                        help="local worker processes (default: all cores; at most the "
                        "cores unless --oversubscribe)")
    parser.add_argument("--oversubscribe", action="store_true",
                        help="allow --workers above the number of cores")
    parser.add_argument("--out", default=default_out, metavar="DIR",
                        help=f"results folder; re-running resumes it (default: {default_out})")
    parser.add_argument("--scheduler", metavar="tcp://HOST:PORT", type=scheduler_option,
                        help="run on this Dask distributed scheduler, tcp://HOST:PORT or "
                             "HOST:PORT "
                             "(the 'dask' extra)")
    parser.add_argument("--no-progress", action="store_true",
                        help="no progress bar (there is none off a terminal either)")
    parser.add_argument("--format", choices=FIGURE_FORMATS, default="png",
                        help="the figures' file format (default: %(default)s)")
    parser.add_argument(CONFIRM_OPTION, type=integer_option, metavar="N",
                        help=f"run a study of more than {MAX_TRIALS} trials: N is its count "
                        "of trials and event recordings, which its refusal names (at least "
                        "that many)")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--spec", metavar="FILE.yaml",
                        help="a YAML sweep spec (grid, offsets, randomisation, "
                             "user-defined objects); the paper's experiment without it")
    parser.add_argument("--objects", nargs="+", metavar="NAME",
                        help=f"objects to grasp (built in: {', '.join(BUILTIN_OBJECTS)})")
    parser.add_argument("--controllers", nargs="+", metavar="NAME",
                        help=f"controllers to compare ({', '.join(CONTROLLER_NAMES)})")
    parser.add_argument("--attempts", type=integer_option, metavar="N",
                        help="attempts per marker position (paper: 3)")
    parser.add_argument("--base-seed", type=integer_option, metavar="N",
                        help="seed all trials' randomisation derives from")
    add_runner_arguments(parser, default_out=DEFAULT_OUT)
    parser.add_argument("--dry-run", action="store_true",
                        help="check the spec, the options and the events, print the plan "
                             "(trials, objects, markers, cost) and run nothing")
    parser.add_argument("--benchmark", action="store_true",
                        help="time the memorized sweep with 1 and then 2 workers, each "
                             "into a temporary folder, and print wall times and speed-up "
                             "(--workers, --out and the reports' options are refused)")
    parser.add_argument("--events", metavar="DIR", default=None,
                        help="memorized events folder (default: $TEGRASP_EVENTS_DIR or "
                        "~/.local/share/tegrasp/events, then the package's)")
    parser.add_argument("--logs", metavar="DIR", default=None,
                        help="also save each trial's log (trial.npz format) in DIR, for "
                        "re-scoring offline (analysis/detection_quality.py)")
    parser.add_argument("--set", dest="overrides", action=AppendSettings, default=[],
                        type=set_option, metavar="KEY=VALUE",
                        help="override a field of every trial's scenario, after the spec's "
                        "scenario_overrides, e.g. --set "
                        "controller.memorized_corrective.events=[hold_avoid]")
    parser.add_argument("--trial-function", default=DEFAULT_TRIAL_FUNCTION,
                        help=argparse.SUPPRESS)  # Testing hook, see the module docstring.


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "sweep", help="run the grasping experiment (Table I) over objects and controllers",
        description=__doc__.split("\n\n")[0], epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    add_arguments(parser)
    parser.set_defaults(func=run)


def check_spec_options(args) -> None:
    """OptionError for --attempts or --base-seed outside the range of the spec field it sets
    (declared on SweepSpec): a number that parses but is refused is bad input (exit 1), as
    for --workers, not a spec refused; the study's size is checked with the spec."""
    from tegrasp_drake.rig.ranges import field_range, option_problem
    for option, name in (("--attempts", "attempts"), ("--base-seed", "base_seed")):
        value = getattr(args, name, None)
        problem = None if value is None else option_problem(option, value,
                                                            field_range(SweepSpec, name))
        if problem:
            raise OptionError(problem)


def spec_from_arguments(args) -> SweepSpec:
    """The spec file (or the paper's defaults) with the command-line overrides applied."""
    spec = LoadSweepSpec(args.spec) if args.spec else SweepSpec()
    in_file = len(spec.scenario_overrides)
    overrides = {name: value for name, value in (
        ("objects", args.objects and tuple(args.objects)),
        ("controllers", args.controllers and tuple(args.controllers)),
        ("attempts", args.attempts),
        ("base_seed", args.base_seed)) if value is not None}
    if args.overrides:  # each list checked as written (the spec's, --set's): --set refines
        overrides["scenario_overrides"] = RefinedSettings(spec.scenario_overrides
                                                          + tuple(args.overrides))
    if "objects" in overrides:  # --objects chooses what runs: the spec's other objects do not
        overrides["user_objects"] = {name: config for name, config in spec.user_objects.items()
                                     if name in overrides["objects"]}
    spec = dataclasses.replace(spec, **overrides)
    source = f"{args.spec} with command-line options" if args.spec else "command line"
    validate_spec(spec, source, override_place=lambda k: (
        f"{args.spec}: field 'scenario_overrides[{k}]'" if k < in_file
        else "--set"))
    check_sweep_size(spec, source, args.confirm_trials)
    return spec


def plan_text(spec: SweepSpec, *, left: int | None = None, corrupt: dict | None = None,
              out=None) -> str:
    """What `spec` would run, in a few lines: the count of trials and its cost, the base seed,
    the objects (a user object with its shape, size, mass and friction), the controllers,
    the markers (offsets in mm, normal to the palm and along the stroke) and the draws. In a
    resumed folder `out` (runner.check_sweep_folder): the `left` trials it would run, priced,
    and a line for each `corrupt` record ({path: why}) it would set aside and run again."""
    total = trial_count(spec)
    left = total if left is None else left
    own = spec.user_objects
    objects = ", ".join(
        f"{name} ({own[name].shape} {list(own[name].size)} m, {own[name].mass} kg, "
        f"friction {own[name].friction})" if name in own else name for name in spec.objects)
    markers = " ".join(f"{name} ({dx * 1000:+g}, {dy * 1000:+g})"
                       for name, (dx, dy) in zip(marker_names(spec.grid), spec.grid))
    counted = " x ".join(count_text(n, noun) for n, noun in (
        (len(spec.objects), "object"), (len(spec.grid), "marker"), (spec.attempts, "attempt"),
        (len(spec.controllers), "controller")))
    r = spec.randomisation
    done = (f", {total - left} already finished in {out}, {left} to run,"
            if left != total else ",")
    aside = [f"  corrupt record set aside as NAME.corrupt-<pid> and run again: {path}: {why}"
             for path, why in (corrupt or {}).items()]
    return "\n".join([
        f"sweep plan (nothing run): {count_text(total, 'trial')} ({counted}){done} "
        f"base seed {spec.base_seed}, {core_hours(left)} at {TRIAL_CORE_SECONDS} s "
        "a trial", *aside,
        f"  objects: {objects}",
        f"  controllers: {', '.join(spec.controllers)}",
        f"  markers, mm normal to the palm and along the stroke: {markers}",
        f"  each attempt draws: +-{r.placement_xy_bound_m * 1000:g} mm about its marker, "
        f"+-{r.placement_yaw_bound_deg:g} deg yaw, friction x (1 +- {r.friction_scale_bound:g}),"
        f" mass x (1 +- {r.mass_scale_bound:g}), sensor noise "
        f"{'on' if r.sensor_noise else 'off'}"])


def _check_logs_folder(logs, out) -> None:
    """--logs names a folder this user can write (made if missing), of its own (not a run's
    or an events folder, not --out or its trials: run_folder.logs_folder_problem), before
    any trial; OptionError (bad input, exit 1, as for --out) when it does not."""
    problem = logs_folder_problem(logs, out)
    if problem:
        raise OptionError(problem)
    problem = folder_problem(logs)
    if problem:
        raise OptionError(f"--logs {logs}: {problem}; give a folder you can write for the "
                          "trials' logs")


def unwritten_log_error(logs, unwritten_log: str, left: int | None = None) -> str:
    """The one error line of a sweep that stopped at a --logs copy it could not write
    ("PATH: reason", SweepSummary.unwritten_log), `left` trials unrun."""
    left_words = "" if left is None else f" ({left} trial(s) left for the next run)"
    return (f"{ERROR_LEAD}--logs {logs}: cannot write the trial log {unwritten_log}; "
            f"its trial's result is recorded and the sweep stopped{left_words}: free space "
            "or give another --logs (a recorded trial's log is made again only in a new --out)")


def resolve_trial_function(text: str):
    """Imports `MODULE:ATTR`: MODULE an absolute dotted module name, ATTR a name in it.
    SweepError for another form, or when importing the module (user code) fails anyhow."""
    module_name, _, attribute = text.partition(":")
    if not (all(part.isidentifier() for part in module_name.split("."))
            and attribute.isidentifier()):
        raise SweepError(f"the trial function {shown(text)} is not MODULE:NAME (an absolute "
                         "dotted module name, a colon, a name in it, e.g. mypkg.trials:run)")
    try:
        function = getattr(importlib.import_module(module_name), attribute)
    except Exception as error:  # the module is the user's code: any error importing it
        raise SweepError(f"cannot load the trial function {text}: "
                         f"{type(error).__name__}: {error}") from None
    if not callable(function):
        raise SweepError(f"the trial function {text} is not callable")
    return function


# The transport a --scheduler address may name. distributed also speaks tls:// (which needs
# certificates: this command takes no option for them), ucx:// (an extra package), ws:// and
# wss://; tegrasp is built and tested against `dask scheduler`'s default, tcp://. inproc://
# names a scheduler inside this process, which the command line starts none of.
DASK_PROTOCOLS = ("tcp",)
OTHER_DASK_PROTOCOLS = ("tls", "ucx", "ws", "wss")


SCHEDULER_FORM = "give tcp://HOST:PORT or HOST:PORT, e.g. tcp://127.0.0.1:8786"

# A HOST's name (RFC 1123): dot-separated labels of letters, digits and inner hyphens, each
# at most 63 characters, 253 in all; or an IP address (an IPv6 one in brackets).
_HOST_LABEL = re.compile(r"^(?!-)[A-Za-z0-9-]{1,63}(?<!-)$")


def _host_problem(host: str, bracketed: bool) -> str | None:
    """Why `host` (of tcp://HOST:PORT; `bracketed`: written [HOST]) names no host, or None."""
    import ipaddress
    try:
        address = ipaddress.ip_address(host)
    except ValueError:
        address = None
    if bracketed:
        return None if address is not None and address.version == 6 else (
            f"HOST [{shown(host)[1:-1]}] is not an IPv6 address")
    if address is not None:
        return None
    labels = host.removesuffix(".").split(".")
    if len(host) > 253 or not all(_HOST_LABEL.match(label) for label in labels):
        return (f"HOST {shown(host)} is not a host name (letters, digits, '-' and '.') nor "
                "an IP address")
    return None


def _scheduler_parts(address: str):
    """(URL parts, HOST, PORT text) of `address` read as tcp://HOST:PORT (HOST:PORT without
    a protocol: scheduler_address), or (None, words) when it has no such form
    (scheduler_form_problem); (None, None) for another protocol, whose address
    scheduler_problem refuses by its protocol, not its form."""
    import urllib.parse
    if not address.strip():
        return None, "the address is blank"
    address = scheduler_address(address)
    scheme, separator, _ = address.partition("://")
    if not scheme:
        return None, "it has no PROTOCOL before its :// (a Dask scheduler's is tcp://)"
    if scheme.lower() not in DASK_PROTOCOLS:
        return None, None
    try:
        parts = urllib.parse.urlsplit(address)
    except ValueError:  # an unclosed '[' of an IPv6 HOST, or no IPv6 address in [...]
        if "]" in address:
            return None, "its [HOST] is not an IPv6 address"
        return None, "its HOST has a '[' without its ']'"
    where = parts.netloc.rpartition("@")[2]
    bracketed = where.startswith("[")
    if bracketed:
        host, _, rest = where[1:].partition("]")
        if rest and not rest.startswith(":"):
            return None, f"{shown(rest)} follows its [HOST] where ':PORT' belongs"
        port = rest[1:] if rest else None
    else:
        host, colon, port = where.partition(":")
        port = port if colon else None
    if not host:
        return None, "it has no HOST"
    if not port:
        return None, "it has no port"
    if not (port.isascii() and port.isdecimal()):
        return None, f"port {shown(port)} is not a number"
    problem = _host_problem(host, bracketed)
    if problem:
        return None, problem
    return parts, host, port


def scheduler_form_problem(address: str) -> str | None:
    """Why `address` does not parse as a scheduler address PROTOCOL://HOST:PORT (a command
    line that does not parse: exit 2), in words that follow "--scheduler 'ADDRESS': ", or
    None; what it names (a protocol, a port's range) is scheduler_problem's."""
    parsed = _scheduler_parts(address)
    return f"{parsed[1]}; {SCHEDULER_FORM}" if parsed[0] is None and parsed[1] else None


def scheduler_option(text: str) -> str:
    """argparse's type of --scheduler: the address as given (HOST:PORT is tcp://HOST:PORT:
    runner.scheduler_address), or a usage error (exit 2) when it does not parse
    (scheduler_form_problem); '' is left to the refusal of empty values,
    text holding a control character to usage_parser.argument_text_problem (exit 2)."""
    from tegrasp_drake.rig.typed_yaml import text_problem
    problem = scheduler_form_problem(text) if text and not text_problem(text) else None
    if problem:  # argparse puts "argument --scheduler: " before it
        raise argparse.ArgumentTypeError(f"{shown(text)}: {problem}")
    return text


def scheduler_problem(address: str) -> str | None:
    """Why `address` is not a Dask scheduler address tcp://HOST:PORT, or None: one that does
    not parse (scheduler_form_problem), or names what no scheduler is reached at. The
    protocol is read case-insensitively, as connect_scheduler passes it on (in lower case)."""
    if not address.strip():
        return "is empty"
    address = scheduler_address(address)
    form = scheduler_form_problem(address)
    if form:
        return f"is not an address: {form}"
    protocol = address.partition("://")[0].lower()
    if protocol in OTHER_DASK_PROTOCOLS:
        return (f"names the protocol {protocol}://; tegrasp connects to a Dask scheduler "
                "over tcp:// only (a `dask scheduler` started without --protocol listens on "
                "it), e.g. tcp://127.0.0.1:8786")
    if protocol not in DASK_PROTOCOLS:
        return ("is not a scheduler address PROTOCOL://HOST:PORT (PROTOCOL tcp), "
                "e.g. tcp://127.0.0.1:8786")
    parts, _, port_text = _scheduler_parts(address)
    port = int(port_text) if len(port_text) <= 6 else 1 << 20
    if port == 0:  # port 0 asks the system for any free port when listening: no destination
        return ("names port 0, which no scheduler listens on; give the port `dask scheduler` "
                "prints (8786 unless --port)")
    if port > 65535:
        return (f"names port {shorten(port_text)}, past the last TCP port (65535); give the "
                "port `dask scheduler` prints (8786 unless --port)")
    extra = [name for name, value in (("a path", parts.path), ("a query", parts.query),
                                      ("a fragment", parts.fragment),
                                      ("a user", parts.username)) if value]
    if extra:
        host_and_port = parts.netloc.split("@")[-1]
        return (f"has {' and '.join(extra)} beside PROTOCOL://HOST:PORT, which a Dask "
                f"scheduler address does not take; give {parts.scheme}://{host_and_port}")
    return None


class OptionError(SweepError):
    """A command-line option's value refused: bad input (exit 1), unlike a spec refused
    (exit 2); str() is the one line to print."""


@dataclasses.dataclass
class Refusal:
    """What refusals_said caught: the command's exit code, None while nothing was refused."""
    exit_code: int | None = None


@contextlib.contextmanager
def refusals_said():
    """The refusals of a command that runs sweeps (sweep, transfer, sensitivity), each said
    in one line on stderr, `tegrasp: error: ...` (ERROR_LEAD), with its exit code set on the
    Refusal yielded: 1 for bad input (OptionError), an output folder that cannot take a
    record (RecordPlaceError), a spec file that cannot be read (UnreadableFileError: missing,
    a folder or device, no permission, an I/O error) and a scheduler lost mid-run
    (SchedulerLostError: the unfinished trials run again with the same command), 2 for a
    spec refused (ConfigError, SweepError). Memorized events that cannot be read
    (MemorizedEventError, e.g. a damaged DIR/events) end the command as bad input,
    `tegrasp: error: ...` (exit 1)."""
    from tegrasp_drake.events import MemorizedEventError
    refusal = Refusal()
    try:
        yield refusal
    except (OptionError, SchedulerLostError, RecordPlaceError, UnreadableFileError) as error:
        print(f"{ERROR_LEAD}{error_line(str(error))}", file=sys.stderr)
        refusal.exit_code = 1
    except (ConfigError, SweepError) as error:
        print(f"{ERROR_LEAD}{error_line(str(error))}", file=sys.stderr)
        refusal.exit_code = 2
    except MemorizedEventError as error:
        raise SystemExit(f"{ERROR_LEAD}{error}") from None


def check_runner_arguments(args, command: str) -> None:
    """OptionError for a bad --workers (check_workers), --confirm-trials, --out (also one
    holding another command's run: run_folder.other_run_problem) or --scheduler address,
    before any trial runs or any event is recorded; `command` is the one run (sweep, transfer,
    sensitivity); scheduler_connection then asks the scheduler whether it answers."""
    check_workers(args)
    if args.confirm_trials is not None and not 1 <= args.confirm_trials <= MAX_CONFIRMED_TRIALS:
        raise OptionError(f"{CONFIRM_OPTION} {args.confirm_trials}: give the study's count of "
                         f"trials, at least 1 and at most {MAX_CONFIRMED_TRIALS} (a refusal of a "
                         "large study names it; split a larger one)")
    if args.scheduler is not None:
        problem = scheduler_problem(args.scheduler)
        if problem:
            raise OptionError(f"--scheduler {shown(args.scheduler)} {problem}")
    if not str(args.out).strip():
        raise OptionError(f"--out {shown(args.out)} is empty; give a folder you can write")
    problem = folder_problem(args.out)
    if problem:
        raise OptionError(f"--out {args.out}: {problem}; give a folder you can write")
    problem = not getattr(args, "benchmark", False) and other_run_problem(args.out, command)
    if problem:  # a benchmark writes into folders of its own
        raise OptionError(problem)


def check_report_files(args, command: str, reports: dict[str, str],
                       figure_stems: tuple[str, ...]) -> None:
    """OptionError when --out holds a file under the name of one of the command's text
    `reports` (file name -> how it starts) that is not that report (rig.report_files), or
    under one of its figures' names (`figure_stems`, in --format) that is not a figure of
    that format (figure_files.figure_replace_problem): the user's own file, which the
    command's reports would replace. Asked before anything runs."""
    from pathlib import Path
    from tegrasp_drake.figures.figure_files import figure_path, figure_replace_problem
    from tegrasp_drake.rig.report_files import foreign_report_problem
    problem = foreign_report_problem(args.out, reports, command)
    if problem:
        raise OptionError(problem)
    for stem in figure_stems:
        path = figure_path(args.out, stem, args.format)
        problem = figure_replace_problem(path)
        if problem:
            raise OptionError(f"--out {Path(args.out)}: {path.name} {problem.split(';')[0]}, and a "
                              f"{command} run replaces its {path.name}; move it out of the "
                              "folder, or give another --out")


@contextlib.contextmanager
def output_folder_held(args, command: str):
    """Holds --out for the rest of the command (rig.files.held_folder, the lock every run
    into a folder takes; the runs' own holds of it share this one), from before its runs
    read the folder to after the last report is written, so a second run into it is refused
    at once while this one reads, runs or writes its reports, and this one is refused while
    another does: OptionError (one line, exit 1), in the words a trial's refusal uses. --out
    is made if missing; the folders that made are removed again, if still empty, when the
    block fails. The folder is asked again, under the hold, whether it holds another
    command's run (other_run_problem): one may have ended there since the first check."""
    from pathlib import Path
    from tegrasp_drake.rig.files import (FolderHeldError, absent_folders, held_folder,
                                         made_folders_removed_if_empty)
    out = Path(args.out)
    made = absent_folders(out)
    with made_folders_removed_if_empty(made), contextlib.ExitStack() as stack:
        out.mkdir(parents=True, exist_ok=True)
        try:
            stack.enter_context(held_folder(out, shared=True))
        except FolderHeldError:
            raise OptionError(f"--out {args.out}: {FOLDER_HELD}; wait for it to end, or give "
                              "another --out") from None
        problem = other_run_problem(args.out, command)
        if problem:
            raise OptionError(problem)
        yield


@contextlib.contextmanager
def scheduler_connection(args, command: str):
    """The command's one connection to --scheduler (None without it), which its sweeps run
    on: entered, once the Dask extra is found, it says on stderr (unless --quiet) what it
    connects to and for how long at most, as distributed retries an address where nothing
    listens until its timeout (31 s for tcp://127.0.0.1:1 when measured), then connects
    (OptionError when the Dask extra is missing or the scheduler does not answer) and,
    unless asked for debug output (-vv shows distributed's own logs), holds distributed's
    loggers; left, it closes the client and then gives the loggers back (the client logs
    while it closes too). Entered after check_runner_arguments, so
    that nothing after the connection refuses an option."""
    if args.scheduler is None:
        yield None
        return
    from tegrasp_drake.sweep.runner import (DASK_ANSWER_BOUND_S, connect_scheduler,
                                            hold_dask_logs)

    def announce():
        if not getattr(args, "quiet", False):
            print(f"tegrasp {command}: connecting to the Dask scheduler at "
                  f"{shorten(args.scheduler)} (at most {DASK_ANSWER_BOUND_S:.0f} s) ...",
                  file=sys.stderr, flush=True)
    try:
        client = connect_scheduler(args.scheduler, announce)
    except SweepError as error:
        raise OptionError(str(error)) from None
    restore_logs = hold_dask_logs() if getattr(args, "verbose", 0) < 2 else None
    try:
        yield client
    finally:
        try:
            client.close()
        finally:
            if restore_logs is not None:
                restore_logs()


def check_workers(args) -> None:
    """OptionError unless --workers is at least 1 and, without --oversubscribe, at most the
    cores this process may run on."""
    if args.workers is None:
        return
    from tegrasp_drake.rig.ranges import option_problem
    from tegrasp_drake.sweep.runner import WORKER_COUNT, cores_problem
    problem = option_problem("--workers", args.workers, WORKER_COUNT)
    if problem:
        raise OptionError(problem)
    problem = cores_problem(args.workers, getattr(args, "oversubscribe", False))
    if problem:
        raise OptionError(f"--workers {args.workers}: {problem}")


def check_benchmark_options(args) -> None:
    """OptionError naming the runner options --benchmark does not use (BENCHMARK_RUNS)."""
    if not args.benchmark:
        return
    unused = [option for option, given in (
        ("--scheduler", args.scheduler is not None), ("--workers", args.workers is not None),
        ("--oversubscribe", args.oversubscribe), ("--out", args.out != DEFAULT_OUT),
        ("--format", args.format != "png"), (CONFIRM_OPTION, args.confirm_trials is not None))
        if given]
    if unused:
        raise OptionError(f"--benchmark times the local process pool on {BENCHMARK_RUNS} "
                          f"and writes no reports: drop {', '.join(unused)}")


def run(args) -> int:
    with contextlib.ExitStack() as held:  # --out, from the sweep's first read to its reports
        if args.dry_run:  # writes nothing, its checks of --out, --logs and trials/ included
            held.enter_context(unprobed_folder_checks())
        return _run(args, held)


def _run(args, held: contextlib.ExitStack) -> int:
    with refusals_said() as refused:
        check_benchmark_options(args)  # before the scheduler is asked whether it answers
        check_runner_arguments(args, "sweep")
        if not args.benchmark:  # a benchmark writes into folders of its own, no reports
            check_report_files(args, "sweep", report_starts(), FIGURE_STEMS)
        check_spec_options(args)
        with scheduler_connection(args, "sweep") as scheduler:
            spec = spec_from_arguments(args)
            trial_function = resolve_trial_function(args.trial_function)
            check_events_folder(args.events)
            if args.trial_function == DEFAULT_TRIAL_FUNCTION:
                from tegrasp_drake.sweep.spec import expand_trials
                from tegrasp_drake.sweep.trial_function import (SweepEventsError,
                                                                check_sweep_events)
                try:
                    check_sweep_events([t.to_dict() for t in expand_trials(spec)], args.events)
                except SweepEventsError as error:  # an event file missing or damaged: bad input, 1
                    print(f"{ERROR_LEAD}{error_line(str(error))}", file=sys.stderr)
                    return 1
            if args.events:
                trial_function = bound_arguments(trial_function, events_dir=args.events)
            if args.logs:
                _check_logs_folder(args.logs, args.out)
                trial_function = bound_arguments(trial_function, log_dir=args.logs)
            if args.dry_run and args.benchmark:
                print(plan_text(benchmark_spec(spec)))
                print(f"  the benchmark runs it on {BENCHMARK_RUNS}")
                return 0
            if args.dry_run:  # refused as the real run would refuse it, before any trial
                left, corrupt, in_use = check_sweep_folder(spec, trial_function, args.out)
                print(plan_text(spec, left=left, corrupt=corrupt, out=args.out))
                if in_use:
                    print(f"tegrasp: warning: --out {args.out} is in use: {FOLDER_HELD}; the "
                          "plan counts the records finished so far, and a real run is refused "
                          "until it ends", file=sys.stderr)
                return 0
            progress = not args.no_progress and progress_wanted(args)
            if args.benchmark:
                runs, identical = run_benchmark(spec, trial_function, progress=progress)
                print(benchmark_text(runs, identical))
                if runs[-1].unwritten_log is not None:
                    print(unwritten_log_error(args.logs, runs[-1].unwritten_log),
                          file=sys.stderr)
                    return 1
                return 0 if identical and not any(run.errors for run in runs) else 1
            held.enter_context(output_folder_held(args, "sweep"))
            summary = run_sweep(spec, trial_function, args.out, workers=args.workers,
                                scheduler=scheduler, progress=progress,
                                confirmed_trials=args.confirm_trials)
    if refused.exit_code is not None:
        return refused.exit_code
    print(summary_text(summary))
    try:
        for path in write_reports(args.out, summary.trial_ids, figure_format=args.format):
            print(f"wrote {path}")
    except ValueError as error:  # no trial of the sweep left a record: no reports
        print(f"{ERROR_LEAD}{error_line(str(error))}", file=sys.stderr)
        return 1
    if summary.unwritten_log is not None:  # a file that cannot be written: exit 1
        print(unwritten_log_error(args.logs, summary.unwritten_log, len(summary.unfinished)),
              file=sys.stderr)
        return 1
    return 1 if summary.errors or summary.unfinished else 0


if __name__ == "__main__":
    # `python -m tegrasp_drake.commands.sweep [options]` is `tegrasp sweep [options]`, run in
    # this process by the command line's own entry (`python -m tegrasp_drake`): its error
    # boundary, exit codes and handling of SIGTERM and SIGHUP, which a main of this module's
    # own lacked (a SIGTERM ended the process by the signal, exit -15, its staging left).
    import os
    original = list(getattr(sys, "orig_argv", []))
    flags = original[1:original.index("-m")] if "-m" in original else []
    os.execv(sys.executable, [sys.executable, *flags, "-m", "tegrasp_drake", "sweep",
                              *sys.argv[1:]])
