"""One event-recording campaign: open-loop grasps of one object, each cut into memorized
events, the template runs' windows combined per transition by their mean (docs/controller.md,
"Events from an ensemble of grasps"). Run k is seeded base + k, each base at or above
1_000_000, apart from every sweep's seeds."""

import dataclasses
import logging
import pathlib
import typing
from collections.abc import Callable, Mapping

import numpy as np

from tegrasp_drake.events import extract_memorized_events, tactile_trial_from_log
from tegrasp_drake.events.extraction import recording_ra_floor
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.ra_noise_floor import rule_sigmas
from tegrasp_drake.rig.objects import object_description
from tegrasp_drake.runs.ideal_grasp import run_ideal_grasp
from tegrasp_drake.scenario.trial_log_file import LogNotWritten, load_trial_log, save_log_copy
from tegrasp_drake.scenario.trial_log_writer import package_versions
from tegrasp_drake.tactile.max_normalization import normalize_by_max

logger = logging.getLogger(__name__)

ENSEMBLE_BASE_SEED = 1_000_000
CORRECTIVE_BASE_SEED = 2_000_000


class RecordEventsError(RuntimeError):
    """A run did not show a physical event; the message says which and what to change."""


@dataclasses.dataclass(frozen=True)
class CampaignRun:
    """One open-loop grasp of a campaign."""
    label: str                      # names the run (and its log file)
    scenario: typing.Any            # the run's Scenario (its random_seed is the run's seed)
    role: str = "template"          # "template": makes the events; "held_out": thresholds
    duration_s: float | None = None  # simulated time [s]; None: the script and a margin


# When a run's physical events happen: {transition: time [s] or None (not seen)}.
EventTimes = Callable[[typing.Any, typing.Any], Mapping[str, float | None]]


def simulate_run(run: CampaignRun, *, log_path=None, progress=None):
    """The run's TrialLog: read from `log_path` if there, else simulated (and saved there);
    LogNotWritten carrying the simulated log when it cannot be saved there (a full disk, a
    folder that cannot be made), so the simulation is not lost with it."""
    if log_path is not None and pathlib.Path(log_path).is_file():
        return load_trial_log(log_path)
    log, wall = run_ideal_grasp(run.scenario, duration=run.duration_s, progress=progress)
    logger.info("%s: %.1f s wall", run.label, wall)
    if log_path is not None:
        log.meta["campaign_run"] = run.label
        save_log_copy(log.save, log_path, log)
    return log


def cut_events(log, run: CampaignRun, times: Mapping[str, float | None], *,
               object_name: str, nominal_object,
               pre_transition_s: float | Mapping[str, float] | None = None,
               note: str | None = None, advice: Callable[[str], str] | None = None,
               quiet_ra_s: float | None = None) -> dict[str, MemorizedEvent]:
    """The run's events cut `pre_transition_s` [s] before each physical event at `times` (None:
    the paper's), tagged with `nominal_object` and `note`; quiet_ra_s: the log's start that
    measures the RA noise floor. RecordEventsError names missing events."""
    missing = [name for name, time in times.items() if time is None]
    if missing:
        words = (f"{run.label} of '{object_name}' (seed {run.scenario.random_seed}) shows "
                 f"no physical event for {', '.join(missing)}")
        if advice is not None:
            words += ": " + "; ".join(advice(name) for name in missing)
        raise RecordEventsError(words)
    scenario = run.scenario
    ra_floor = None
    if quiet_ra_s is not None:
        ra_floor = recording_ra_floor(tactile_trial_from_log(log), quiet_s=quiet_ra_s,
                                      sigmas=rule_sigmas(scenario.vibration.sample_rate_hz))
        logger.info("%s: RA noise floor of the recording's first %.1f s: %s m/s^2",
                    run.label, quiet_ra_s, np.round(ra_floor, 4).tolist())
    cut = {}
    for transition, time in times.items():
        pre = (pre_transition_s.get(transition) if isinstance(pre_transition_s, Mapping)
               else pre_transition_s)
        try:
            cut.update(extract_memorized_events(
                tactile_trial_from_log(log, {transition: time}), object_name=object_name,
                sa_rate_hz=scenario.tactile.sample_rate_hz,
                ra_rate_hz=scenario.vibration.sample_rate_hz,
                **({} if pre is None else {"pre_transition_s": pre}),
                scenario=(note if note is not None
                          else f"{run.label} seed {scenario.random_seed}"),
                package_versions=package_versions(),
                object_description=object_description(nominal_object),
                ra_floor=ra_floor))
        except ValueError as error:  # a window off the log, or a channel with no signal
            raise RecordEventsError(
                f"{run.label} of '{object_name}' (seed {scenario.random_seed}): {error} (a "
                "noise-free sensor reads exactly zero on a pad that is not touched: record "
                "without that run, e.g. --ensemble-runs 0, or give the sensors noise)"
            ) from None
    return cut


def combine_runs(runs: list[Mapping[str, MemorizedEvent]], *, note: str
                 ) -> dict[str, MemorizedEvent]:
    """Per transition, the runs' windows' mean, max-normalised; its time is the runs' mean."""
    if not runs:
        raise ValueError("a campaign needs at least one template run")
    combined = {}
    for transition in runs[0]:
        members = [run[transition] for run in runs]
        combined[transition] = dataclasses.replace(
            members[0], sa=normalize_by_max(np.mean([e.sa for e in members], axis=0)),
            ra=normalize_by_max(np.mean([e.ra for e in members], axis=0)),
            transition_time_s=float(np.mean([e.transition_time_s for e in members])),
            scenario=f"{note}; mean of {len(members)} runs")
    return combined


def record_campaign(runs: typing.Sequence[CampaignRun], event_times: EventTimes, *,
                    object_name: str, nominal_object,
                    pre_transition_s: float | Mapping[str, float] | None = None, note: str,
                    log_dir=None, progress_of_run=None) -> dict[str, MemorizedEvent]:
    """The campaign's events: every run simulated (its log kept in or reused from
    `log_dir`/<label>.npz), cut and combined. progress_of_run(k): run k's callback or None.

    A log that cannot be written in `log_dir` (a full disk, a folder that cannot be made)
    costs only that file: its run is cut from the log in memory, the campaign goes on (each
    later run's log is tried in turn) and ends in LogNotWritten carrying the events, naming
    the first log it could not write and the OS reason, for the caller to keep and report."""
    templates, unwritten = [], None
    for k, run in enumerate(runs):
        try:
            log = simulate_run(run, log_path=run_log_path(log_dir, run),
                               progress=progress_of_run(k) if progress_of_run else None)
        except LogNotWritten as not_written:  # the run stands; only its log file is lost
            log, unwritten = not_written.result, unwritten or not_written
            logger.info("%s: its log %s was not written: %s", run.label,
                        not_written.path, not_written.reason)
        events = cut_events(log, run, event_times(log, run.scenario),
                            object_name=object_name, nominal_object=nominal_object,
                            pre_transition_s=pre_transition_s)
        if run.role == "template":
            templates.append(events)
    combined = combine_runs(templates, note=note)
    if unwritten is not None:
        raise LogNotWritten(combined, unwritten.path, unwritten.reason)
    return combined


def first_unwritten_log(pool, function: Callable, jobs) -> LogNotWritten | None:
    """Runs `function` over `jobs` on the executor `pool` (a campaign's logs, made in
    parallel); at the first log that cannot be written, cancels the jobs not started (their
    logs would be lost too) and returns its LogNotWritten; None when every log was written."""
    try:
        list(pool.map(function, jobs))
    except LogNotWritten as unwritten:
        pool.shutdown(cancel_futures=True)
        return unwritten
    return None


def unwritten_log_words(unwritten: LogNotWritten) -> str:
    """A campaign's log that could not be written, and what to do, for its one error line."""
    return (f"cannot write the run log {unwritten.path} ({unwritten.reason}): free space or "
            "give another logs folder; the logs written so far are reused by the next run")


def run_log_path(log_dir, run: CampaignRun) -> pathlib.Path | None:
    """Where a run's log is kept: `log_dir`/<label, spaces as '_', no commas>.npz."""
    if log_dir is None:
        return None
    return pathlib.Path(log_dir) / (run.label.replace(" ", "_").replace(",", "") + ".npz")
