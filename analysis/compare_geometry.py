"""Pair a sweep on a cheaper representation (a coarser contact geometry, cheaper sensing)
with the same sweep on the reference one: outcomes by exact McNemar, every changed trial, and
the event latencies.

    python analysis/compare_geometry.py [--label NAME] OUT.md REFERENCE_FOLDER VARIANT_FOLDER

The folders hold `tegrasp sweep` records (`trials/*.json`) of the same trials (the same spec
and base seed; a trial id names the controller, object, marker and attempt, and its seeds
follow from them), one run on each representation (e.g. analysis/geometry_contract_paper.yaml
against analysis/results_linkage/paper_grid); --label names the variant's column (default
"coarse"). Per controller: held (Hold) and held and unloaded on each, paired, with the exact
McNemar p-value of each; each trial whose outcome changed, with both runs' failure classes
and its largest latency change; and per transition the median detection latency on each
(over the trials where the event was detected) and the median and largest paired difference (over the trials where both
were). The contract (docs/sweeps.md, "Coarser contact geometry"): no significant change in
outcomes, every changed trial explained, median latencies within 10 ms.
"""

import pathlib
import statistics
import sys

sys.path.insert(0, str(pathlib.Path(__file__).parent))

from compare_hands import failure_class, load_folders  # noqa: E402

from tegrasp_drake.commands.script_output import (  # noqa: E402
    SWEEP_RESULTS_ADVICE, run_script, script_parser, write_report)
from tegrasp_drake.scenario.trial_result import TrialResult  # noqa: E402
from tegrasp_drake.sweep.table import exact_mcnemar_p_value  # noqa: E402
from tegrasp_drake.sweep.table import succeeded as _succeeded  # noqa: E402

PHASES = {"hold": "held", "unload": "held and unloaded"}
TRANSITIONS = ("reach_load", "load_lift", "place_unload")


def succeeded(result: dict, phase: str) -> bool:
    """A record's result (its JSON form) succeeded in `phase` (sweep.table.succeeded)."""
    return _succeeded(TrialResult.from_dict(result), phase)


def _ms(value) -> str:
    return "–" if value is None else f"{1000 * value:+.0f}" if value else "0"


def _median(values):
    return statistics.median(values) if values else None


def latency_rows(pairs, label: str = "coarse") -> list[str]:
    """Per transition: each side's median latency [s] and the paired differences."""
    rows = ["| transition | reference median [s] (n) | {label} median [s] (n) | paired median "
            "difference [ms] (n) | largest paired difference [ms] |".format(label=label),
            "|---|---|---|---|---|"]
    for transition in TRANSITIONS:
        sides = [[pair[side]["detection_latency_s"].get(transition) for pair in pairs]
                 for side in (1, 2)]
        done = [[v for v in side if v is not None] for side in sides]
        both = [b - a for a, b in zip(*sides) if a is not None and b is not None]
        medians = [_median(values) for values in done]
        largest = max(both, key=abs) if both else None
        rows.append(f"| {transition} | "
                    + " | ".join("–" if m is None else f"{m:.3f} ({len(v)})"
                                 for m, v in zip(medians, done))
                    + f" | {_ms(_median(both))} ({len(both)}) | {_ms(largest)} |")
    return rows


def _largest_latency_change(reference, coarse) -> str:
    changes = [(coarse["detection_latency_s"].get(t), reference["detection_latency_s"].get(t))
               for t in TRANSITIONS]
    differences = [b - a for b, a in changes if a is not None and b is not None]
    return _ms(max(differences, key=abs)) if differences else "–"


def title(label: str) -> str:
    """The report's first line, by which an earlier report at OUT is known."""
    return f"# {label} against the reference, paired trial by trial"


def report(reference: dict, coarse: dict, label: str = "coarse") -> str:
    common = sorted(set(reference) & set(coarse))
    lines = [title(label), "",
             f"{len(common)} paired trials (reference {len(reference)}, {label} {len(coarse)} "
             "records).", ""]
    for controller in sorted({reference[t][0]["controller"] for t in common}):
        pairs = [(reference[t][0], reference[t][1], coarse[t][1]) for t in common
                 if reference[t][0]["controller"] == controller]
        lines += [f"## {controller}", "", f"| outcome | reference | {label} | only reference "
                  f"| only {label} | exact McNemar p |", "|---|---|---|---|---|---|"]
        for phase, words in PHASES.items():
            a = [succeeded(r, phase) for _, r, _ in pairs]
            b = [succeeded(c, phase) for _, _, c in pairs]
            only_a = sum(x and not y for x, y in zip(a, b))
            only_b = sum(y and not x for x, y in zip(a, b))
            lines.append(f"| {words} | {sum(a)}/{len(a)} | {sum(b)}/{len(b)} | {only_a} | "
                         f"{only_b} | {exact_mcnemar_p_value(only_a, only_b):.3g} |")
        lines += ["", *latency_rows(pairs, label), ""]
        changed = [(t, r, c) for t, r, c in pairs
                   if any(succeeded(r, p) != succeeded(c, p) for p in PHASES)]
        if changed:
            lines += [f"| trial | offset [mm] (normal, stroke) | reference | {label} | largest "
                      "latency change [ms] |", "|---|---|---|---|---|"]
            for trial, r, c in changed:
                offset = ", ".join(f"{1000 * v:+.0f}" for v in (trial["marker_dx_m"],
                                                                 trial["marker_dy_m"]))
                lines.append(f"| {trial['trial_id']} | {offset} | {failure_class(r)} | "
                             f"{failure_class(c)} | {_largest_latency_change(r, c)} |")
            lines.append("")
        else:
            lines += ["No trial changed its outcome.", ""]
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = script_parser("compare_geometry", __doc__)
    parser.add_output("out", type=pathlib.Path, title=lambda args: title(args.label),
                      help="the Markdown report to write")
    parser.add_input("reference", type=pathlib.Path, what="reference folder",
                     advice=SWEEP_RESULTS_ADVICE, help="records on the reference representation")
    parser.add_input("coarse", type=pathlib.Path, what="coarse folder",
                     advice=SWEEP_RESULTS_ADVICE,
                     help="records on the cheaper representation (the variant)")
    parser.add_argument("--label", default="coarse",
                        help="the variant's name in the report (default: coarse)")
    args = parser.parse_args(argv)
    reference, coarse = load_folders([args.reference, args.coarse], "compare_geometry",
                                     ["reference folder", "coarse folder"])
    text = report(reference, coarse, args.label)
    write_report(args.out, text + "\n", script="compare_geometry")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "compare_geometry"))
