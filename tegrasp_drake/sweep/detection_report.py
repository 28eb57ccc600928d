"""Detection quality per trigger and controller, and paired comparisons of controllers, from
a sweep's records (docs/sweeps.md, "A sweep": the definitions): per event transition,
detected, false, other and latency [s]; the hit in Hold likewise; McNemar's exact test on
the scenes both controllers ran."""

import collections
import dataclasses

import numpy as np

from tegrasp_drake.control.grasp_modes import Mode
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS, transition_states
from tegrasp_drake.sweep.records import record_result
from tegrasp_drake.sweep.table import exact_mcnemar_p_value

from tegrasp_drake.scenario.trial_result import FALSE_TRIGGER_MARGIN_S  # the judge's margin
EVENT_TRIGGERS = ("memorized_event", "heuristic_event")
MARKERS = (("well_placed", "hold"), ("well_placed", "unload"), ("misplaced", "hold"),
           ("misplaced", "unload"))


@dataclasses.dataclass(frozen=True)
class TriggerRow:
    controller: str
    trigger: str
    trials: int
    detected: int
    false: int
    other: int
    median_latency_s: float | None
    p90_latency_s: float | None


def _event_entries(result, transition):
    source, target = transition_states(transition)
    return [t for t in result.transitions
            if t.from_mode.label == source and t.to_mode.label == target]


def event_trigger_rows(records) -> list[TriggerRow]:
    """One TriggerRow per (controller, event transition) of the records (module doc)."""
    outcomes = collections.defaultdict(list)
    for record in records.values():
        if not record.get("result"):
            continue
        result = record_result(record)
        controller = record["trial"]["controller"]
        for transition in REQUIRED_TRANSITIONS:
            source = transition_states(transition)[0]
            if not any(t.to_mode.label == source for t in result.transitions) and \
                    source != "Reach":
                continue  # never reached the mode that waits for this event
            taken = [t for t in _event_entries(result, transition)
                     if t.trigger.value in EVENT_TRIGGERS]
            physical = result.physical_events.get(transition)
            if not taken:
                outcomes[(controller, transition)].append(("other", None))
            elif physical is None or taken[-1].t < physical - FALSE_TRIGGER_MARGIN_S:
                outcomes[(controller, transition)].append(("false", None))
            else:
                outcomes[(controller, transition)].append(("detected",
                                                           taken[-1].t - physical))
    rows = []
    for (controller, transition), items in sorted(outcomes.items()):
        latencies = [lat for kind, lat in items if kind == "detected"]
        rows.append(TriggerRow(
            controller, transition, len(items), len(latencies),
            sum(kind == "false" for kind, _ in items), sum(kind == "other" for kind, _ in items),
            float(np.median(latencies)) if latencies else None,
            float(np.percentile(latencies, 90)) if latencies else None))
    return rows


@dataclasses.dataclass(frozen=True)
class HitAvoidRow:
    controller: str
    triggers: tuple[str, ...]   # the triggers of its Avoids
    hits_in_hold: int
    detected: int
    missed: int
    false: int                  # of reached_hold
    reached_hold: int
    median_latency_s: float | None
    p90_latency_s: float | None


def _mode_at(transitions, t: float) -> str:
    """The mode the timeline was in at time t [s] (Reach before the first transition)."""
    mode = "Reach"
    for entry in transitions:
        if entry.t > t:
            break
        mode = entry.to_mode.label
    return mode


def hit_avoid_rows(records) -> list[HitAvoidRow]:
    """One HitAvoidRow per controller with a hit in Hold or an Avoid (module doc)."""
    rows = collections.defaultdict(lambda: {"triggers": set(), "hits": 0, "detected": 0,
                                            "missed": 0, "false": 0, "reached": 0,
                                            "latencies": []})
    for record in records.values():
        result = record_result(record) if record.get("result") else None
        if not result or not result.entered(Mode.HOLD):
            continue
        row = rows[record["trial"]["controller"]]
        row["reached"] += 1
        avoids = [t for t in result.transitions if t.to_mode == Mode.AVOID]
        row["triggers"].update(t.trigger.value for t in avoids)
        hit = result.physical_events.get("hit")
        in_hold = hit is not None and _mode_at(result.transitions, hit) == "Hold"
        if any(hit is None or t.t < hit - FALSE_TRIGGER_MARGIN_S for t in avoids):
            row["false"] += 1
        if not in_hold:
            continue
        row["hits"] += 1
        after = [t.t for t in avoids if t.t >= hit - FALSE_TRIGGER_MARGIN_S]
        if after:
            row["detected"] += 1
            row["latencies"].append(after[0] - hit)
        else:
            row["missed"] += 1
    return [HitAvoidRow(controller, tuple(sorted(r["triggers"])), r["hits"], r["detected"],
                        r["missed"], r["false"], r["reached"],
                        float(np.median(r["latencies"])) if r["latencies"] else None,
                        float(np.percentile(r["latencies"], 90)) if r["latencies"] else None)
            for controller, r in sorted(rows.items()) if r["hits"] or r["triggers"]]


def corrective_counts(records) -> dict[str, collections.Counter]:
    """{controller: Counter(action: trials in which it started)}."""
    counts = collections.defaultdict(collections.Counter)
    for record in records.values():
        if record.get("result"):
            counts[record["trial"]["controller"]].update(
                set(record_result(record).corrective_actions))
    return counts


def _success(record, column: str) -> bool:
    result = record_result(record)
    return bool(result.hold_success if column == "hold" else result.unload_success)


@dataclasses.dataclass(frozen=True)
class PairedComparison:
    first: str
    second: str
    marker: tuple[str, str]
    pairs: int
    first_rate: float
    second_rate: float
    only_first: int
    only_second: int
    p_value: float


def paired_comparison(records, first: str, second: str,
                      marker: tuple[str, str]) -> PairedComparison:
    """McNemar comparison of two controllers' success on one marker (module doc)."""
    placement, column = marker
    by_pair = collections.defaultdict(dict)
    for record in records.values():
        if record.get("result") is None:
            continue
        trial = record["trial"]
        if trial["well_placed"] != (placement == "well_placed"):
            continue
        by_pair[trial["pair_id"]][trial["controller"]] = _success(record, column)
    pairs = [(p[first], p[second]) for p in by_pair.values() if first in p and second in p]
    a = sum(x and not y for x, y in pairs)
    b = sum(y and not x for x, y in pairs)
    n = len(pairs)
    return PairedComparison(first, second, marker, n,
                            sum(x for x, _ in pairs) / n if n else 0.0,
                            sum(y for _, y in pairs) / n if n else 0.0, a, b,
                            exact_mcnemar_p_value(a, b))


def report_markdown(records, controllers, reference: str | None, title: str) -> str:
    """The detection-quality and paired-comparison report of a sweep, as Markdown."""
    def ms(value):
        return "–" if value is None else f"{1000 * value:.0f} ms"
    lines = [f"# {title}\n", "## Success (trials)\n",
             "| controller | " + " | ".join(" ".join(m) for m in MARKERS) + " |",
             "|---|" + "---|" * len(MARKERS)]
    for controller in controllers:
        cells = []
        for placement, column in MARKERS:
            mine = [r for r in records.values() if r.get("result") is not None
                    and r["trial"]["controller"] == controller
                    and r["trial"]["well_placed"] == (placement == "well_placed")]
            wins = sum(_success(r, column) for r in mine)
            cells.append(f"{100 * wins / len(mine):.0f} % ({wins}/{len(mine)})" if mine
                         else "–")
        lines.append(f"| {controller} | " + " | ".join(cells) + " |")
    lines += ["\n## Event triggers (per trial that reached the waiting mode)\n",
             "| controller | transition | trials | detected | false | other trigger / none "
             "| median latency | p90 latency |", "|---|---|---|---|---|---|---|---|"]
    for row in event_trigger_rows(records):
        if row.controller in controllers and row.detected + row.false > 0:
            lines.append(f"| {row.controller} | {row.trigger} | {row.trials} | {row.detected} | "
                         f"{row.false} | {row.other} | {ms(row.median_latency_s)} | "
                         f"{ms(row.p90_latency_s)} |")
    hit_rows = [row for row in hit_avoid_rows(records) if row.controller in controllers]
    if hit_rows:
        lines += ["\n## Hit in Hold -> Avoid\n",
                  "| controller | Avoid trigger | hits in Hold | detected | missed | false (of "
                  "trials in Hold) | median latency | p90 latency |",
                  "|---|---|---|---|---|---|---|---|"]
        for row in hit_rows:
            lines.append(f"| {row.controller} | {', '.join(row.triggers) or '–'} | "
                         f"{row.hits_in_hold} | {row.detected} | {row.missed} | "
                         f"{row.false} of {row.reached_hold} | {ms(row.median_latency_s)} | "
                         f"{ms(row.p90_latency_s)} |")
    lines += ["\n## Corrective actions (trials in which each started)\n",
              "| controller | actions |", "|---|---|"]
    counts = corrective_counts(records)
    for controller in controllers:
        text = ", ".join(f"{a} {n}" for a, n in sorted(counts.get(controller, {}).items()))
        lines.append(f"| {controller} | {text or 'none'} |")
    if reference is None:  # no controller to pair against: said, not an empty table
        return "\n".join(lines + [
            "\n## Paired success (McNemar, exact)\n",
            "No open_loop trials in these results to pair against; give --reference with a "
            "controller they hold."]) + "\n"
    lines += [f"\n## Paired success against {reference} (McNemar, exact)\n",
              "| controller | marker | pairs | its rate | reference rate | only it | "
              "only reference | p |", "|---|---|---|---|---|---|---|---|"]
    for controller in controllers:
        if controller == reference:
            continue
        for marker in MARKERS:
            c = paired_comparison(records, controller, reference, marker)
            if c.pairs:
                lines.append(f"| {controller} | {' '.join(marker)} | {c.pairs} | "
                             f"{100 * c.first_rate:.1f} % | {100 * c.second_rate:.1f} % | "
                             f"{c.only_first} | {c.only_second} | {c.p_value:.3g} |")
    return "\n".join(lines) + "\n"
