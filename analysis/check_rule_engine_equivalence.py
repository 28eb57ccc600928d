"""Do two commits' controllers decide committed scenes the same? Re-runs committed sweep
scenes at a base commit and at this checkout and compares each trial's result dict.

    python analysis/check_rule_engine_equivalence.py --base COMMIT [--out DIR]
        [--scenes FOLDER/trials/CONTROLLER.OBJECT.MARKER.ATTEMPT.json ...]
        [--controllers memorized taxel_aware] [--fresh]

A check for changes that must not change behaviour (the rule table's structure): each
scene (a judging record under analysis/results_*) is run with each controller on its
record's own trial spec and seed, once with the package at --base (extracted with
`git archive` into DIR/tree-COMMIT) and once with this checkout's, each in its own Python
process. The two result dicts must be equal but for the timing fields (TIMING_FIELDS).
Runs are kept in DIR (default out/rule_engine_equivalence), the base's by commit, this
checkout's by its package, events and models, and reused unless --fresh (this checkout's
only when those have no uncommitted change), so each side's runs are made once. Prints, per trial, the rules that decided its
transitions (from this checkout's run) and whether the two agree; exits 1 on a difference.
The records themselves are not compared: the package has changed since they were made.
"""

import hashlib
import json
import os
import pathlib
import subprocess
import sys
import tarfile
import tempfile

from tegrasp_drake.commands.script_output import run_script, script_parser
from tegrasp_drake.rig.files import JSON_OBJECT_START, write_atomically
from tegrasp_drake.scenario.moved_keys import migrate_stored_trial

ROOT = pathlib.Path(__file__).resolve().parent.parent
# Measured on the machine, not decided by the controller.
TIMING_FIELDS = ("cpu_time_s", "wall_time_s", "real_time_factor")
# Eight committed scenes (the judging grids' records on the robot and on the linkage hand),
# chosen for the variety of rules their records show; which rules decide the runs now is
# printed with each.
SCENES = (
    "results_robot/paper_grid/trials/{controller}.box.m00.a0.json",
    "results_robot/paper_grid/trials/{controller}.thick_cylinder.m02.a0.json",
    "results_robot/paper_grid/trials/{controller}.thin_cylinder.m00.a0.json",
    "results_robot/paper_grid/trials/{controller}.thin_cylinder.m20.a2.json",
    "results_linkage/second_grid/trials/{controller}.box.m01.a0.json",
    "results_linkage/second_grid/trials/{controller}.thick_cylinder.m00.a0.json",
    "results_linkage/paper_grid/trials/{controller}.thin_cylinder.m20.a0.json",
    "results_linkage/second_grid/trials/{controller}.box.m12.a0.json",
)
CONTROLLERS = ("memorized", "taxel_aware")

# Run in a child process whose PYTHONPATH holds the tree to test: one trial, its result
# dict and the rules that decided its transitions (None where a commit records none).
WORKER = """
import json, pathlib, sys
import tegrasp_drake
tree = pathlib.Path(sys.argv[1]).resolve()
assert pathlib.Path(tegrasp_drake.__file__).resolve().is_relative_to(tree), tegrasp_drake.__file__
from tegrasp_drake.runs.trial import run_trial
from tegrasp_drake.sweep.trial_function import trial_events
trial = json.load(sys.stdin)
scenario, events, corrective = trial_events(trial)
run = run_trial(scenario, events=events, corrective_events=corrective)
codes = [None if getattr(t, "code", None) is None else str(t.code) for t in run.transitions]
print(json.dumps({"result": run.to_dict(), "rules": codes}))
"""


def git(*args: str) -> str:
    return subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True, text=True,
                          check=True).stdout.strip()


# What a run depends on: the package, its memorized events and its models.
RUN_INPUTS = ("tegrasp_drake", "events", "models")


def tip_label() -> tuple[str, bool]:
    """This checkout's cache folder name, named by the committed trees of RUN_INPUTS (a
    commit that changes none of them keeps it), and whether its runs may be cached (none
    of them has an uncommitted change)."""
    dirty = bool(git("status", "--porcelain", "--", *RUN_INPUTS))
    trees = hashlib.sha256(" ".join(git("rev-parse", f"HEAD:{path}")
                                    for path in RUN_INPUTS).encode()).hexdigest()
    return ("tip-uncommitted", False) if dirty else (f"tip-{trees[:12]}", True)


def extract_tree(commit: str, out: pathlib.Path) -> pathlib.Path:
    """The package at `commit`, extracted once into out/tree-<commit>."""
    sha = git("rev-parse", "--verify", f"{commit}^{{commit}}")
    tree = out / f"tree-{sha[:12]}"
    if not (tree / "tegrasp_drake").is_dir():
        staging = pathlib.Path(tempfile.mkdtemp(prefix="tree-", dir=out))
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", sha],
                                 capture_output=True, check=True).stdout  # bytes
        with tempfile.TemporaryFile() as file:
            file.write(archive)
            file.seek(0)
            with tarfile.open(fileobj=file) as tar:
                tar.extractall(staging, filter="data")
        staging.rename(tree)
    return tree


def run_scene(tree: pathlib.Path, trial: dict, path: pathlib.Path, fresh: bool) -> dict:
    """The worker's output for `trial` with the package in `tree`, cached at `path`."""
    if path.exists() and not fresh:
        return json.loads(path.read_text())
    env = dict(os.environ, PYTHONPATH=str(tree))
    done = subprocess.run([sys.executable, "-c", WORKER, str(tree)], input=json.dumps(trial),
                          capture_output=True, text=True, env=env, cwd=tree)
    if done.returncode != 0:
        raise SystemExit(f"the trial {trial['trial_id']} failed in {tree}:\n"
                         f"{done.stderr.strip()[-2000:]}")
    output = json.loads(done.stdout.strip().splitlines()[-1])
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomically(path, json.dumps(output, indent=1), start=JSON_OBJECT_START)
    return output


def _keeps_codes(result: dict) -> bool:
    """Whether the result's timeline names the rule of a transition (its `code`)."""
    return any("code" in entry for entry in result.get("transitions", ()))


def _without_codes(result: dict) -> dict:
    return {**result, "transitions": [{key: value for key, value in entry.items()
                                       if key != "code"}
                                      for entry in result.get("transitions", ())]}


def differences(base: dict, tip: dict) -> list[str]:
    """The result fields (timing aside) whose values differ. When one side's timeline keeps
    the deciding rules' codes and the other's does not (a base from before timelines kept
    them), the transitions are compared without them; the rules are printed from the tip."""
    if _keeps_codes(base) != _keeps_codes(tip):
        base, tip = _without_codes(base), _without_codes(tip)
    keys = (set(base) | set(tip)) - set(TIMING_FIELDS)
    return sorted(key for key in keys if base.get(key) != tip.get(key))


def main(argv=None) -> int:
    parser = script_parser("check_rule_engine_equivalence", __doc__)
    parser.add_argument("--base", required=True, help="the commit to compare against")
    parser.add_output("--out", folder=True, type=pathlib.Path,
                      default=ROOT / "out" / "rule_engine_equivalence")
    parser.add_argument("--scenes", nargs="+", default=list(SCENES),
                        help="records under analysis/, {controller} standing for each controller")
    parser.add_argument("--controllers", nargs="+", default=list(CONTROLLERS))
    parser.add_argument("--only", choices=("base", "tip"), default=None,
                        help="make one side's runs only (no comparison)")
    parser.add_argument("--fresh", action="store_true", help="re-run cached trials")
    args = parser.parse_args(argv)
    records = [(scene, controller, ROOT / "analysis" / scene.format(controller=controller))
               for scene in args.scenes for controller in args.controllers]
    missing = [str(path) for *_, path in records if not path.is_file()]
    if missing:
        raise SystemExit(f"no such record: {', '.join(missing)}; give records under analysis/")
    args.out.mkdir(parents=True, exist_ok=True)
    base_tree = extract_tree(args.base, args.out)
    trees = {"base": base_tree, "tip": ROOT}
    tip, cacheable = tip_label()
    folders = {"base": base_tree.name.replace("tree-", "base-"), "tip": tip}
    fresh = {"base": args.fresh, "tip": args.fresh or not cacheable}
    sides = (args.only,) if args.only else ("base", "tip")
    failures = 0
    for scene, controller, record in records:
        trial = json.loads(record.read_text())["trial"]
        # This checkout reads the stored record through its migration; the base as stored.
        trials = {"base": trial, "tip": migrate_stored_trial(trial)}
        name = record.stem
        # Cached by the record's path: two results folders hold records of the same name.
        cache = "--".join(record.relative_to(ROOT / "analysis").parts)
        runs = {side: run_scene(trees[side], trials[side], args.out / folders[side] / cache,
                                fresh[side])
                for side in sides}
        rules = sorted({rule for rule in runs[sides[-1]]["rules"] if rule})
        if len(runs) < 2:
            print(f"{name}: ran ({', '.join(rules) or 'no rule names'})", flush=True)
            continue
        diff = differences(runs["base"]["result"], runs["tip"]["result"])
        failures += bool(diff)
        verdict = "identical" if not diff else "DIFFERENT: " + ", ".join(diff)
        final = runs["tip"]["result"]["final_mode"]
        print(f"{name}: {verdict}; {len(runs['tip']['result']['transitions'])} transitions, "
              f"{final}; rules: {', '.join(rules) or '-'}", flush=True)
    if len(sides) == 2:
        print(f"{len(records) - failures} of {len(records)} trials identical (timing fields "
              f"{', '.join(TIMING_FIELDS)} aside)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(run_script(main, "check_rule_engine_equivalence"))
