"""Missed memorized events of a sweep: every wait that ended on its event's timeout, replayed
from the trial's log (`tegrasp sweep --logs LOGS`) with the events and matcher settings the
controller ran with, classified (events/missed_waits.py) and counted per object and class."""

import dataclasses
import pathlib

from tegrasp_drake.control.controller_registry import controller_entry
from tegrasp_drake.control.grasp_controller import event_matcher_config
from tegrasp_drake.events.event_file import MemorizedEventError
from tegrasp_drake.events.missed_waits import (
    MISS_CLASSES, WEAK_DYNAMIC_STIMULUS, MissedWait, classify_missed_wait, event_waits)
from tegrasp_drake.events.ra_noise_floor import rule_sigmas
from tegrasp_drake.events.replay import tactile_trial_from_log
from tegrasp_drake.scenario.moved_keys import migrate_stored_trial
from tegrasp_drake.scenario.scenario import sample_rates_hz
from tegrasp_drake.simulation.film_readout import adc_input
from tegrasp_drake.simulation.pad_vibration_sensor import volts_per_mps2
from tegrasp_drake.sweep.trial_function import load_record_log, trial_events, trial_log_name


@dataclasses.dataclass(frozen=True)
class TrialMiss:
    """One missed wait of a trial; ra_code_mps2 [m/s^2] (None: no converter); ra_rate_hz [Hz]."""
    trial_id: str
    object_name: str
    missed: MissedWait
    ra_code_mps2: float | None
    ra_rate_hz: float

    def within_noise_floor(self) -> bool | None:
        """Whether a failing RA channel stayed within the rule's floor; None without a best tick."""
        return self.missed.failing_ra_within_floor(rule_sigmas(self.ra_rate_hz))


def ra_code_mps2(vibration) -> float | None:
    """One myRIO converter code behind the film's amplifier [m/s^2]; None without one."""
    adc = adc_input(vibration.adc_input)
    if vibration.transducer != "film" or adc is None:
        return None
    return adc.volts_per_code / volts_per_mps2(vibration)


def record_has_waits(record: dict, controller: str) -> bool:
    """Whether `record` ran `controller` and waited in vain for one of its events."""
    result = record.get("result")
    return (record.get("status") == "ok" and result is not None
            and record["trial"]["controller"] == controller
            and bool(event_waits(result["transitions"])))


def trial_misses(record: dict, log_path, events_dir=None) -> list[TrialMiss]:
    """The classified missed waits of one sweep record, its log at `log_path`."""
    trial = record["trial"]
    scenario, events, _ = trial_events(migrate_stored_trial(trial), events_dir)
    if not controller_entry(scenario.controller).event_triggered or events is None:
        return []
    config = event_matcher_config(scenario.controller, gripper_model=scenario.gripper.model,
                                  rates_hz=sample_rates_hz(scenario))
    tactile = tactile_trial_from_log(load_record_log(log_path, record))
    code = ra_code_mps2(scenario.vibration)
    return [TrialMiss(trial["trial_id"], trial["object_name"],
                      classify_missed_wait(tactile, events, wait, config), code,
                      config.ra_rate_hz)
            for wait in event_waits(record["result"]["transitions"])]


def sweep_misses(records: dict, logs_dir, *, controller: str = "memorized",
                 events_dir=None) -> tuple[list[TrialMiss], list[str], int]:
    """(misses, ids of records with waits but no log, trials of `controller` looked at) over a
    results folder's records; ValueError naming the trial when its log or events fail."""
    misses, without_log, trials = [], [], 0
    for trial_id, record in sorted(records.items()):
        if record.get("status") != "ok" or record["trial"]["controller"] != controller:
            continue
        trials += 1
        if not record_has_waits(record, controller):
            continue
        path = pathlib.Path(logs_dir) / trial_log_name(record["trial"], record.get("events"))
        if not path.is_file():
            without_log.append(trial_id)
            continue
        try:
            misses += trial_misses(record, path, events_dir)
        except (ValueError, MemorizedEventError) as error:  # a bad log, missing events, ...
            raise ValueError(f"trial {trial_id} (log {path}): {error}") from None
    return misses, without_log, trials


def _pair(values, digits: int = 2) -> str:
    return "–" if values is None else " / ".join(f"{v:.{digits}f}" for v in values)


def _ra_size(miss: TrialMiss, peaks, sigmas) -> str:
    """Each RA channel's peak: m/s^2, noise sigmas, converter codes."""
    if peaks is None:
        return "–"
    parts = []
    for side, peak, sigma in zip("LR", peaks, sigmas):
        codes = "" if miss.ra_code_mps2 is None else f", {peak / miss.ra_code_mps2:.1f} codes"
        parts.append(f"{side} {peak:.3g} m/s² ({sigma:.1f} σ{codes})")
    return "; ".join(parts)


def _floor_text(miss: TrialMiss) -> str:
    within = miss.within_noise_floor()
    return "–" if within is None else ("within" if within else "above")


# The count of the weak dynamic stimuli whose failing RA stayed within the noise floor.
WITHIN_FLOOR = "of which RA within the noise floor"
COUNT_COLUMNS = (WEAK_DYNAMIC_STIMULUS, WITHIN_FLOOR) + MISS_CLASSES[1:]


def _floor_sigmas_text(misses: list[TrialMiss]) -> str:
    """The noise floor's k at the misses' RA rates (1 kHz when none)."""
    rates = sorted({m.ra_rate_hz for m in misses}) or [1000.0]
    return " or ".join(f"{rule_sigmas(rate):.2f}" for rate in rates)


def class_counts(misses: list[TrialMiss]) -> dict[str, dict[str, int]]:
    """{object: {column: missed waits}} for the COUNT_COLUMNS (the classes, and the weak
    dynamic stimuli within the RA noise floor), every column present."""
    counts = {}
    for miss in misses:
        per_object = counts.setdefault(miss.object_name, dict.fromkeys(COUNT_COLUMNS, 0))
        per_object[miss.missed.miss_class] += 1
        if miss.missed.miss_class == WEAK_DYNAMIC_STIMULUS and miss.within_noise_floor():
            per_object[WITHIN_FLOOR] += 1
    return counts


def report_markdown(misses: list[TrialMiss], without_log: list[str], trials: int,
                    controller: str, title: str) -> str:
    """The report: one row per missed wait, then the counts per object and class."""
    lines = [f"# {title}", "",
             f"{trials} {controller} trials; {len(misses)} waits for a memorized event "
             f"ended on its timeout, in {len({m.trial_id for m in misses})} trials.", "",
             "Each wait is replayed through the controller's EventMatcher with the event "
             "held expected. Best: the scores at the tick where both SA passed and the "
             "lower RA score is highest (its time), or, where SA never passed, the SA "
             "scores at the tick closest to both passing. RA peak at best: each RA "
             "window's peak at that tick in m/s², in noise sigmas above the channel's "
             "mean over the first quiet seconds, and in converter codes; RA peak in wait: "
             "the same over the whole wait. Floor: \"within\" when an RA channel that "
             "failed at the best tick read no more than the RA noise floor's mean + "
             f"{_floor_sigmas_text(misses)} σ over the whole wait (noise alone crosses it "
             "in one trial of a thousand; events/ra_noise_floor.py). "
             f"Class \"{WEAK_DYNAMIC_STIMULUS}\": both SA passed at some tick but an RA "
             "channel stayed below its threshold at every such tick.", ""]
    if without_log:
        lines += [f"No log for {len(without_log)} trials with waits (not counted): "
                  + ", ".join(without_log), ""]
    lines += ["| Trial | Wait | Reason | Thresholds SA / RA | Best SA L / R | "
              "Best RA L / R (at) | RA peak at best | RA peak in wait | Floor | Class |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for miss in misses:
        m = miss.missed
        at = "" if m.best_tick_s is None else f" ({m.best_tick_s:.3f} s)"
        lines.append(
            f"| {miss.trial_id} | {m.wait.transition} {m.wait.start_s:.2f}–{m.wait.end_s:.2f} "
            f"s | {m.wait.reason} | {_pair(m.thresholds)} | {_pair(m.best_sa, 3)} | "
            f"{_pair(m.best_ra, 3)}{at} | {_ra_size(miss, m.ra_peak, m.ra_peak_sigmas())} | "
            f"{_ra_size(miss, m.ra_wait_peak, m.ra_wait_peak_sigmas())} | {_floor_text(miss)} "
            f"| {m.miss_class} |")
    lines += ["", "## Missed waits per object and class", "",
              "| Object | " + " | ".join(COUNT_COLUMNS) + " |",
              "|---|" + "---|" * len(COUNT_COLUMNS)]
    counts = class_counts(misses)
    for name, per_class in sorted(counts.items()):
        lines.append(f"| {name} | " + " | ".join(str(per_class[c]) for c in COUNT_COLUMNS)
                     + " |")
    total = {c: sum(per[c] for per in counts.values()) for c in COUNT_COLUMNS}
    lines += ["| all | " + " | ".join(str(total[c]) for c in COUNT_COLUMNS) + " |", ""]
    return "\n".join(lines)


def weak_stimulus_trials(misses: list[TrialMiss]) -> int:
    """Trials with at least one wait classed as a weak dynamic stimulus."""
    return len({m.trial_id for m in misses if m.missed.miss_class == WEAK_DYNAMIC_STIMULUS})

