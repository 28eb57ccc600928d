"""Which Hold -> Avoid transitions of a sweep were the friction creep of a held grasp rather
than a hit (docs/model.md, "Friction creep"): the solver's regularised friction lets fingers
held off their pins slide along the object, the locked drive unloads, and the film reads
the falling grip through its high-pass as a steady level above the hit threshold.

    python analysis/hold_creep.py RESULTS LOGS [--out OUT.md]

RESULTS: a sweep's results folder; LOGS: its `tegrasp sweep --logs` folder. For every
trial with an Avoid, the Hold before each Avoid (from its start, or the last Avoid's end,
to the Avoid) is read from the log:

  - grip rate [N/s]: the slope of the two pads' mean true normal force (a least-squares
    line over the Hold);
  - film level and peak [m/s^2]: the median and the largest of the larger RA channel over
    the Hold;
  - closed [counts]: how far the 2F-85's reported position gPO moved on while it reported
    the object held (gOBJ = 2): a locked screw moves only when the grip unloads (a count
    is 0.33 mm; over a 0.3 s Hold the creep rarely closes one).

An Avoid is counted as creep when its Hold's grip fell (rate below zero) and the film's
level is at least half its peak: a steady reading, what a ramp gives through the film's
high-pass (about 3.3 m/s^2 per N/s of grip on the default film); a hit is a transient of
tens of milliseconds, its Hold's median at the noise and its peak far above.
The sweeps here script no hits (`disturbance.hit_time_s` < 0), so every Avoid is a false
one; the report says how many are creep and how many are something else.
"""

import pathlib
import sys

import numpy as np

from tegrasp_drake.commands.script_output import (SWEEP_LOGS_ADVICE, SWEEP_RESULTS_ADVICE,
                                                  load_sweep_records, run_script,
                                                  script_parser, write_report)
from tegrasp_drake.sweep.trial_function import load_record_log, trial_log_name

G_OBJ, G_PO = 3, 6  # gripper_status columns: the object status and the position [counts]
OBJECT_HELD_CLOSING = 2  # gOBJ: stopped on an object while closing


def hold_creep(log, start_s: float, end_s: float) -> dict:
    """Grip rate [N/s], film level and peak [m/s^2], drive closing [counts] and whether
    they are the creep's, over [start_s, end_s)."""
    on_sa = (log.t_sa >= start_s) & (log.t_sa < end_s)
    grip = log.true_taxels[on_sa].reshape(-1, 2, 12).sum(axis=2).mean(axis=1)
    rate = float(np.polyfit(log.t_sa[on_sa], grip, 1)[0]) if on_sa.sum() >= 3 else 0.0
    on_ra = (log.t_ra >= start_s) & (log.t_ra < end_s)
    film = np.abs(log.channels[on_ra, 2:]).max(axis=1) if on_ra.any() else np.zeros(1)
    level, peak = float(np.median(film)), float(film.max())
    on_slow = (log.t_slow >= start_s) & (log.t_slow < end_s)
    status = log.gripper_status[on_slow]
    held = status[status[:, G_OBJ] == OBJECT_HELD_CLOSING, G_PO]
    closed = int(held.max() - held.min()) if len(held) else 0
    return {"grip_rate_n_per_s": rate, "film_mps2": level, "film_peak_mps2": peak,
            "closed_counts": closed, "creep": rate < 0.0 and level >= 0.5 * peak}


def trial_holds(record: dict, log) -> list[dict]:
    """hold_creep of the Hold before each Avoid of one trial's record."""
    holds, start = [], None
    for t in record["result"]["transitions"]:
        if t["to"] == "Hold":
            start = t["t"]
        elif t["from"] == "Hold" and t["to"] == "Avoid" and start is not None:
            holds.append({"t": t["t"], **hold_creep(log, start, t["t"])})
    return holds


TITLE = "# Hold -> Avoid: friction creep or something else"  # the report's first line


def main(argv=None) -> int:
    parser = script_parser("hold_creep", __doc__)
    parser.add_input("results", type=pathlib.Path, what="results folder",
                     advice=SWEEP_RESULTS_ADVICE)
    parser.add_input("logs", type=pathlib.Path, what="logs folder", advice=SWEEP_LOGS_ADVICE)
    parser.add_output("--out", type=pathlib.Path, default=None, title=TITLE)
    args = parser.parse_args(argv)
    loaded = load_sweep_records("hold_creep", args.results)
    ran = [r for r in loaded.records.values() if r.get("result") is not None]
    if not ran:
        raise SystemExit(f"hold_creep: {args.results} holds no trial record with a result "
                         "(trials/*.json); give the --out folder of a `tegrasp sweep`")
    avoided = {r["trial_id"]: (r, args.logs / trial_log_name(r["trial"], r.get("events")))
               for r in ran if any(t["to"] == "Avoid" for t in r["result"]["transitions"])}
    missing = [trial_id for trial_id, (_, path) in avoided.items() if not path.exists()]
    if avoided and len(missing) == len(avoided):
        raise SystemExit(f"hold_creep: {args.logs} holds none of the logs of the "
                         f"{len(avoided)} trials with an Avoid (e.g. "
                         f"{next(iter(avoided.values()))[1].name}); give the --logs folder of "
                         "the sweep that wrote the records")
    rows = []
    for trial_id, (record, path) in avoided.items():
        if trial_id not in missing:
            log = load_record_log(path, record)  # TrialLogError: another trial's log
            rows.extend((trial_id, hold) for hold in trial_holds(record, log))
    creep = sum(1 for _, h in rows if h["creep"])
    lines = [TITLE, "",
             f"{len(rows)} Avoids in {len({r for r, _ in rows})} of {len(ran)} trials: "
             f"{creep} with the "
             "creep signature (grip falling, the film at a steady level), "
             f"{len(rows) - creep} without.", "",
             "| trial | Avoid at [s] | grip rate [N/s] | film level, peak [m/s^2] "
             "| drive closed [counts] | creep |", "|---|---|---|---|---|---|"]
    for trial, h in sorted(rows, key=lambda r: (r[0], r[1]["t"])):
        lines.append(f"| {trial} | {h['t']:.2f} | {h['grip_rate_n_per_s']:.2f} | "
                     f"{h['film_mps2']:.1f}, {h['film_peak_mps2']:.1f} | {h['closed_counts']} | "
                     f"{'yes' if h['creep'] else 'no'} |")
    if missing:
        lines += ["", f"No log for {len(missing)} trials: {', '.join(sorted(missing))}."]
    text = "\n".join(lines) + "\n"
    if args.out:
        write_report(args.out, text, script="hold_creep")
    sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "hold_creep"))
