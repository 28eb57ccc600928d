"""Pair two hands' sweep records trial by trial: success rates, McNemar, changed trials.

    python analysis/compare_hands.py OUT.md LINKAGE_FOLDER PRISMATIC_FOLDER [PRISMATIC_FOLDER ...]

The folders hold `tegrasp sweep` records (`trials/*.json`) of the same trials (the same
spec and base seed: a trial id names the controller, object, marker and attempt, and its
seeds follow from them), one run on each hand. For every controller in both: Table I's
columns (well-placed and misplaced, hold and hold-and-unload) per object on each hand, the
exact McNemar test on hold-and-unload over the paired trials, and each trial whose outcome
changed, with each run's failure class (sweep/failure_classes.py). Then the linkage run's
failures by class.
"""

import collections
import pathlib
import sys

from tegrasp_drake.commands.script_output import (SWEEP_RESULTS_ADVICE, load_sweep_records,
                                                  run_script, script_parser, write_report)
from tegrasp_drake.scenario.trial_result import TrialResult
from tegrasp_drake.rig.echo import shown
from tegrasp_drake.sweep.failure_classes import failure_class as trial_failure_class
from tegrasp_drake.sweep.table import exact_mcnemar_p_value


def load_folders(folders, script: str = "compare_hands", names=None) -> list[dict]:
    """Each folder's {trial_id: (trial, result)} of finished records (sweep.load_records),
    all read before a word is said: SystemExit naming the first folder with a corrupt record
    (script_output.load_sweep_records) or with no finished record, by the script's argument
    (`names`, one a folder: "linkage folder"; "results folder" without)."""
    names = names or ["results folder"] * len(folders)
    loaded = [(folder, load_sweep_records(script, folder, name))
              for folder, name in zip(folders, names)]
    finished = [{trial_id: (record["trial"], record["result"])
                 for trial_id, record in records.records.items()
                 if record.get("status") == "ok"} for _, records in loaded]
    for (folder, _), records in zip(loaded, finished):
        if not records:
            raise SystemExit(f"{script}: {folder} holds no finished trial record "
                             "(trials/*.json with status ok); give the --out folder of a "
                             "`tegrasp sweep`")
    return finished


def success(result) -> bool:
    return bool(result["hold_success"] and result["unload_success"])


def failure_class(result) -> str:
    """A record's result (its JSON form) as its failure class (sweep/failure_classes.py),
    "held and unloaded" for a trial that was."""
    return trial_failure_class(TrialResult.from_dict(result)) or "held and unloaded"


def rates(pairs, side: int) -> str:
    """'hold% / unload%' of one hand's results in (trial, prismatic, linkage) rows."""
    if not pairs:
        return "-"
    held = sum(p[side]["hold_success"] for p in pairs) / len(pairs)
    unloaded = sum(success(p[side]) for p in pairs) / len(pairs)
    return f"{100 * held:.0f} / {100 * unloaded:.0f}"


def report(prismatic: dict, linkage: dict) -> str:
    common = sorted(set(prismatic) & set(linkage))
    controllers = sorted({prismatic[t][0]["controller"] for t in common})
    lines = [f"{len(common)} paired trials (prismatic {len(prismatic)}, linkage {len(linkage)} "
             "records).", ""]
    for controller in controllers:
        ids = [t for t in common if prismatic[t][0]["controller"] == controller]
        rows = [(prismatic[t][0], prismatic[t][1], linkage[t][1]) for t in ids]
        lines += [f"## {controller}", "",
                  "| object | placed | trials | prismatic hold / unload % | linkage hold / unload % |",
                  "|---|---|---|---|---|"]
        for name in sorted({r[0]["object_name"] for r in rows}):
            for placed, well in (("well", True), ("misplaced", False)):
                pairs = [(r[1], r[2]) for r in rows
                         if r[0]["object_name"] == name and r[0]["well_placed"] == well]
                lines.append(f"| {name} | {placed} | {len(pairs)} | {rates(pairs, 0)} | "
                             f"{rates(pairs, 1)} |")
        only_prismatic = sum(success(r[1]) and not success(r[2]) for r in rows)
        only_linkage = sum(success(r[2]) and not success(r[1]) for r in rows)
        lines += ["", f"Held and unloaded: prismatic {sum(success(r[1]) for r in rows)}/"
                      f"{len(rows)}, linkage {sum(success(r[2]) for r in rows)}/{len(rows)}; "
                      f"only prismatic {only_prismatic}, only linkage {only_linkage}, exact "
                      f"McNemar p = {exact_mcnemar_p_value(only_prismatic, only_linkage):.3g}.",
                  ""]
        changed = [r for r in rows if success(r[1]) != success(r[2])]
        if changed:
            lines += ["| trial | offset [mm] (normal, stroke) | prismatic | linkage |",
                      "|---|---|---|---|"]
            for trial, before, after in changed:
                offset = (f"{1000 * trial['marker_dx_m']:+.0f}, "
                          f"{1000 * trial['marker_dy_m']:+.0f}")
                lines.append(f"| {trial['trial_id']} | {offset} | {failure_class(before)} | "
                             f"{failure_class(after)} |")
            lines.append("")
    classes = collections.Counter(
        (linkage[t][0]["controller"], failure_class(linkage[t][1])) for t in linkage
        if not success(linkage[t][1]))
    lines += ["## The linkage run's failures by class", "", "| controller | class | trials |",
              "|---|---|---|"]
    lines += [f"| {c} | {k} | {n} |" for (c, k), n in sorted(classes.items())]
    return "\n".join(lines) + "\n"


TITLE = "# Prismatic against linkage hand"  # the report's first line


def main(argv=None) -> int:
    parser = script_parser("compare_hands", __doc__)
    parser.add_output("out", type=pathlib.Path, title=TITLE)
    parser.add_input("linkage", type=pathlib.Path, what="linkage folder",
                     advice=SWEEP_RESULTS_ADVICE)
    parser.add_input("prismatic", type=pathlib.Path, nargs="+", what="prismatic folder",
                     advice=SWEEP_RESULTS_ADVICE)
    args = parser.parse_args(argv)
    linkage, *prismatic_runs = load_folders(
        [args.linkage, *args.prismatic], names=["linkage folder"]
        + ["prismatic folder"] * len(args.prismatic))
    seen = {args.linkage.resolve(): "linkage folder"}
    for folder in args.prismatic:  # one hand's trials read as the other's pair with themselves
        if folder.resolve() in seen:
            parser.refuse(f"prismatic folder {shown(str(folder))} is the "
                          f"{seen[folder.resolve()]} given before it; give each hand's own "
                          "`tegrasp sweep --out` folder, each once")
        seen[folder.resolve()] = "prismatic folder"
    prismatic = {}
    for records in prismatic_runs:
        prismatic.update(records)
    text = f"{TITLE}\n\n{report(prismatic, linkage)}"
    write_report(args.out, text, script="compare_hands")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "compare_hands"))
