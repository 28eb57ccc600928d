"""Judge the memorized hit trigger against the heuristic one in closed-loop trials that no
template or threshold choice saw (other hits, the default seed), and a normal grasp for
false triggers; writes a markdown table.

    python analysis/judge_corrective_triggers.py OUT.md [--workers 2]
"""

import pathlib
import sys
from concurrent.futures import ProcessPoolExecutor

# Hits that no template, threshold choice or earlier judge saw. (The first judge, of the
# first rule's thresholds SA, RA > 0.98: analysis/corrective_trials_first_rule.md, hits
# +y 18 N at 7.2 s and -y 22 N at 6.9 s.)
HITS = (("hit +y 17 N at 7.1 s", 17.0, 7.1), ("hit -y 21 N at 7.3 s", -21.0, 7.3),
        ("no hit", None, None))
TRIGGERS = {"memorized": ["controller.memorized_corrective.events=[hold_avoid]"],
            "heuristic": []}


def one(job):
    label, force, time, trigger = job
    from tegrasp_drake.scenario.scenario import LoadScenario
    from tegrasp_drake.runs.trial import run_trial
    overrides = list(TRIGGERS[trigger])
    if force is not None:
        overrides += [f"disturbance.hit_time_s={time}",
                      f"disturbance.hit_force_n=[0.0, {force}, 0.0]"]
    result = run_trial(LoadScenario(name="box", overrides=overrides)).result
    avoid = [e for e in result["transitions"] if e["to"] == "Avoid"]
    return label, time, trigger, result, avoid


# The table's header row, its first line, by which an earlier table at OUT is known.
HEADER = ("| situation | trigger | Avoid at (after the hit) | Avoid's trigger | direction | "
          "Avoids | hold / unload | final mode, tilt, placement error | wall [s] |")


def main(argv=None) -> int:
    from tegrasp_drake.commands.script_output import script_parser
    parser = script_parser("judge_corrective_triggers", __doc__)
    parser.add_output("out", type=pathlib.Path, title=HEADER)
    parser.add_workers()
    args = parser.parse_args(argv)
    jobs = [(label, force, time, trigger) for label, force, time in HITS
            for trigger in TRIGGERS]
    lines = [HEADER,
             "|---|---|---|---|---|---|---|---|---|"]
    with ProcessPoolExecutor(args.workers) as pool:
        for label, time, trigger, result, avoid in pool.map(one, jobs):
            if avoid:
                first = avoid[0]
                at = (f"{first['t']:.3f} s ({1000 * (first['t'] - time):.0f} ms)"
                      if time is not None else f"{first['t']:.3f} s (false)")
                how, direction = first["trigger"], first.get("direction")
            else:
                at, how, direction = "none", "-", "-"
            lines.append(f"| {label} | {trigger} | {at} | {how} | {direction} | {len(avoid)} | "
                         f"{result['hold_success']} / {result['unload_success']} | "
                         f"{result['final_mode']}, {result['final_tilt_deg']:.1f} deg, "
                         f"{1000 * result['placement_error_m']:.0f} mm | "
                         f"{result['wall_time_s']:.0f} |")
            print(lines[-1], flush=True)
    from tegrasp_drake.commands.script_output import write_report
    from tegrasp_drake.rig.files import MARKDOWN_TABLE_START
    write_report(args.out, "\n".join(lines) + "\n", script="judge_corrective_triggers",
                 start=MARKDOWN_TABLE_START)
    return 0


if __name__ == "__main__":
    from tegrasp_drake.commands.script_output import run_script
    sys.exit(run_script(main, "judge_corrective_triggers"))
