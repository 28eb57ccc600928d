"""The grip force's rise on first contact in trial logs: 10-90 % rise time, peak and held
force per pad against the force setting (the 2F-85's drive, robotiq/drive.py).

    python analysis/grip_rise.py TRIAL.npz [TRIAL.npz ...]

Reads the true taxel forces (summed per pad) and the gripper's command and status. The
held force is the mean over 20-40 ms after the status first reports the fingers stopped on
the object (gOBJ 2), before the lift loads the pads; the rise runs from the first touch
(either pad above 0.05 N) to 10 % and 90 % of the held force.
"""

import json
import sys

import numpy as np

from tegrasp_drake.commands.script_output import run_script, script_parser
from tegrasp_drake.rig.channels import TAXELS_PER_PAD
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.scenario.trial_log_file import load_trial_log


def grip_rise_of_log(path: str) -> dict:
    log = load_trial_log(path)  # TrialLogError naming the file for one that is no trial log
    t, taxels = log.t_sa, log.true_taxels
    pads = np.stack([taxels[:, :TAXELS_PER_PAD].sum(axis=1),
                     taxels[:, TAXELS_PER_PAD:].sum(axis=1)], axis=1)
    force = pads.min(axis=1)  # the lesser pad: the grip both pads share
    touch = float(t[np.argmax(pads.max(axis=1) > 0.05)])
    stopped = log.gripper_status[:, ru.STATUS_OBJ] == ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING
    t_stop = float(log.t_slow[np.argmax(stopped & (log.t_slow > touch))])
    settle = (t >= t_stop + 0.02) & (t < t_stop + 0.04)
    held = float(force[settle].mean())
    window = (t >= touch) & (t < t_stop + 0.04)
    crossing = lambda level: float(t[window][np.argmax(force[window] >= level)])
    setting = float(ru.force_from_byte(log.gripper_command[np.argmax(
        log.t_slow >= touch), ru.COMMAND_FORCE]))
    return {"log": path, "touch_s": touch, "setting_n": setting, "held_n": held,
            "peak_n": float(force[window].max()),
            "rise_10_90_ms": 1e3 * (crossing(0.9 * held) - crossing(0.1 * held)),
            "touch_to_90_ms": 1e3 * (crossing(0.9 * held) - touch),
            "current_when_held": float(log.gripper_status[np.argmax(
                log.t_slow >= t_stop + 0.02), ru.STATUS_CU])}


def main(argv=None) -> int:
    parser = script_parser("grip_rise", __doc__)
    parser.add_argument("logs", nargs="+", help="trial logs (tegrasp trial --out's trial.npz)")
    for path in parser.parse_args(argv).logs:
        print(json.dumps(grip_rise_of_log(path)))
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "grip_rise"))
