"""When the closed-loop Load-Lift fires and with how much grip the lift starts.

    python analysis/measure_load_lift.py [--events events]
        [--objects box thick_cylinder thin_cylinder] [--seed 600] [--workers 2]
        [--set KEY=VALUE ...] [--json OUT.json]

Runs one trial of the memorized controller (the scenario's) per object and marker (the centre and three misplaced markers of the
paper's grid, offsets in the scenario's placement.offset [m]) on development seeds (--seed,
--seed + 1, ...) and prints, per trial: the Reach-Load, Load-Lift and Place-Unload times
and triggers, the lift's grip fraction (runs/trial.py lift_grip_fraction: the weaker pad's
true force at the Load -> Lift transition over the settled grip), the first contact and
grip-settled times, and the final state. The closed-loop check of the Load-Lift anchor
(recording/paper_events.py): the lift should start with the grip settled.
"""

import dataclasses
import json
import pathlib
import sys
from concurrent.futures import ProcessPoolExecutor

from tegrasp_drake.commands.script_output import (EVENTS_ADVICE, refuse_unusable_folders,
                                                  refuse_unusable_output, run_script,
                                                  script_parser)
from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig.paths import package_events_dir
from tegrasp_drake.rig.ranges import SEED_RANGE
from tegrasp_drake.rig.files import JSON_ARRAY_START, write_atomically
from tegrasp_drake.rig.typed_yaml import set_option
from tegrasp_drake.rig.usage_parser import AppendSettings

# The keys of every row, by which an earlier --json file of this script is known.
ROW_KEYS = ("object", "offset_mm", "seed", "reach_load", "load_lift", "place_unload",
            "final_mode")
MARKERS_M = ((0.0, 0.0), (0.01, 0.0), (0.0, 0.015), (-0.01, -0.015))


def trial_row(job) -> dict:
    object_name, offset, seed, events_dir, overrides = job
    from tegrasp_drake.runs.trial import run_trial
    from tegrasp_drake.scenario.scenario import LoadScenario
    from tegrasp_drake.scenario.scenario_events import load_controller_events
    base = LoadScenario(name=object_name, overrides=list(overrides))
    scenario = dataclasses.replace(base, random_seed=seed, placement=dataclasses.replace(
        base.placement, offset=list(offset)))
    events = load_controller_events(scenario, events_dir)
    trial = run_trial(scenario, events=events)
    result = trial.result
    steps = {f"{e.from_mode.label}-{e.to_mode.label}": (round(e.t, 3), e.trigger.name.lower())
             for e in reversed(trial.transitions)}
    physical = result["physical_events"]
    row = {"object": object_name, "offset_mm": [round(1000 * v) for v in offset],
           "seed": seed, "reach_load": steps.get("Reach-Load"),
           "load_lift": steps.get("Load-Lift"), "place_unload": steps.get("Place-Unload"),
           "lift_grip_fraction": result["lift_grip_fraction"],
           "first_contact": physical.get("reach_load"),
           "grip_settled": physical.get("load_lift"),
           "final_mode": result["final_mode"], "hold": result["hold_success"],
           "unload": result["unload_success"]}
    print(json.dumps(row), flush=True)
    return row


def main(argv=None) -> int:
    parser = script_parser("measure_load_lift", __doc__)
    parser.add_input("--events", default=str(package_events_dir()), what="--events folder",
                     advice=EVENTS_ADVICE)
    parser.add_argument("--objects", nargs="+",
                        default=["box", "thick_cylinder", "thin_cylinder"])
    parser.add_number("--seed", type=integer_option, default=600, allowed=SEED_RANGE)
    parser.add_workers()
    parser.add_argument("--set", dest="overrides", action=AppendSettings, default=[],
                        type=set_option, metavar="KEY=VALUE",
                        help="override a scenario field of every trial")
    parser.add_output("--json", type=pathlib.Path, default=None, rows=ROW_KEYS,
                      help="write the rows here (an existing file only if it is such rows)")
    args = parser.parse_args(argv)
    from tegrasp_drake.scenario.scenario import LoadScenario
    from tegrasp_drake.scenario.scenario_events import load_controller_events
    for name in args.objects:  # the events every trial reads, refused before any simulates
        load_controller_events(LoadScenario(name=name, overrides=list(args.overrides)),
                               args.events)
    if args.json:
        refuse_unusable_folders("measure_load_lift", args.json.parent)
    jobs = [(name, offset, args.seed + k, args.events, tuple(args.overrides))
            for name in args.objects for k, offset in enumerate(MARKERS_M)]
    with ProcessPoolExecutor(args.workers) as pool:
        rows = list(pool.map(trial_row, jobs))
    print("| object | offset mm | seed | Reach-Load s | Load-Lift s (trigger) | "
          "grip at lift | Place-Unload s (trigger) | final |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        rl = r["reach_load"][0] if r["reach_load"] else None
        ll, pu = (f"{r[step][0]:.3f} ({r[step][1]})" if r[step] else "-"
                  for step in ("load_lift", "place_unload"))
        fraction = (f"{r['lift_grip_fraction']:.2f}" if r["lift_grip_fraction"] is not None
                    else "-")
        print(f"| {r['object']} | {tuple(r['offset_mm'])} | {r['seed']} | {rl} | {ll} | "
              f"{fraction} | {pu} | {r['final_mode']} |")
    if args.json:  # the check again, for a file put there during the trials
        refuse_unusable_output("measure_load_lift", args.json, rows=ROW_KEYS)
        write_atomically(args.json, json.dumps(rows, indent=1), start=JSON_ARRAY_START)
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "measure_load_lift"))
