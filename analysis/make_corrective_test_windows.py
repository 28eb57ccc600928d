"""Cut the recorded channels that tests/recording/test_corrective_events.py replays
(tests/data/corrective_windows.npz) from the corrective and ensemble logs.

    python analysis/make_corrective_test_windows.py CORRECTIVE_LOGS ENSEMBLE_LOGS

Held-out runs only (none made a corrective template): the hit "+y 15 N 1.3 s into Hold",
the slip "friction 0.012", and the ensemble's normal grasp of the box, run 6; the windows
around the script's Lift and Hold (corrective_events.LIFT_START_S ...). The committed
file was cut from the prismatic hand's runs with the earlier 1.3 s Load phase (Lift
4.1-5.6 s, the hit at 7.4 s): remaking it changes tests/recording/test_corrective_events.py's
times and events folder with it.
"""

import pathlib
import sys

import numpy as np

from tegrasp_drake.commands.script_output import (CORRECTIVE_LOGS_ADVICE, ENSEMBLE_LOGS_ADVICE,
                                                  run_script, script_parser)
from tegrasp_drake.events import tactile_trial_from_log
from tegrasp_drake.rig.files import temporary_sibling
from tegrasp_drake.rig.npz_headers import NPZ_START
from tegrasp_drake.scenario.trial_log_file import load_trial_log

sys.path.insert(0, str(pathlib.Path(__file__).parent))
from record_corrective_events import log_path  # noqa: E402

OUT = pathlib.Path(__file__).parents[1] / "tests" / "data" / "corrective_windows.npz"


def cut(log, name, start, end, arrays):
    trial = tactile_trial_from_log(log)
    sa = (trial.t_sa >= start) & (trial.t_sa <= end)
    ra = (trial.t_ra >= start) & (trial.t_ra <= end)
    slow = (log.t_slow >= start) & (log.t_slow <= end)
    arrays.update({f"{name}_t_sa": trial.t_sa[sa], f"{name}_sa": trial.sa[sa],
                   f"{name}_t_ra": trial.t_ra[ra], f"{name}_ra": trial.ra[ra],
                   f"{name}_t_slow": log.t_slow[slow], f"{name}_arm_q": log.arm_q[slow],
                   f"{name}_object_state": log.object_state[slow]})


def main(argv=None) -> int:
    from tegrasp_drake.recording.corrective_events import (CORRECTIVE_RUNS, HOLD_END_S,
                                                           LIFT_END_S, LIFT_START_S)
    parser = script_parser("make_corrective_test_windows", __doc__)
    parser.add_input("corrective_logs", type=pathlib.Path, what="corrective logs folder",
                     advice=CORRECTIVE_LOGS_ADVICE)
    parser.add_input("ensemble_logs", type=pathlib.Path, what="ensemble logs folder",
                     advice=ENSEMBLE_LOGS_ADVICE)
    args = parser.parse_args(argv)
    corrective, ensemble = args.corrective_logs, args.ensemble_logs
    runs = {run.label: run for run in CORRECTIVE_RUNS}
    arrays = {}
    cut(load_trial_log(log_path(corrective, "box", runs["hit +y 15 N 1.3 s into Hold"])),
        "hit", LIFT_END_S + 0.7, LIFT_END_S + 1.9, arrays)
    cut(load_trial_log(log_path(corrective, "box", runs["friction 0.012"])), "slip",
        LIFT_START_S - 0.6, LIFT_END_S, arrays)
    normal = load_trial_log(ensemble / "box" / "run6.npz")
    cut(normal, "normal_lift", LIFT_START_S - 0.6, LIFT_END_S, arrays)
    cut(normal, "normal_hold", LIFT_END_S, HOLD_END_S, arrays)
    with (temporary_sibling(OUT, start=NPZ_START) as temporary, open(temporary, "wb") as f):
        np.savez_compressed(f, **arrays)  # whole or not at all: the tests read it
    print(f"wrote {OUT} ({OUT.stat().st_size} bytes)")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "make_corrective_test_windows"))
