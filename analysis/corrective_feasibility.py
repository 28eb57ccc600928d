"""Why slip and one-finger-first are not memorized corrective events (docs/controller.md, "Memorized
corrective triggers"): Eq. 3 scores, from recorded logs, of

  slip   the slip band (tactile/slip_vibration_band: the film's vibration above 80 Hz, RMS
         over 10 ms) of the corrective slip runs' template windows against every 5 ms of
         Lift of the slip runs and of the ensemble's normal grasps;
  one finger first   a left-first contact window of the second grid's open-loop box logs
         (marker m02) against every open-loop box log's first contact and the ensemble's
         normal first contacts.

    python analysis/corrective_feasibility.py CORRECTIVE_LOGS ENSEMBLE_LOGS GRID_LOGS
"""

import pathlib
import sys

import numpy as np

from tegrasp_drake.commands.script_output import (CORRECTIVE_LOGS_ADVICE, ENSEMBLE_LOGS_ADVICE,
                                                  run_script, script_parser)
from tegrasp_drake.control.controller_config import GraspControllerConfig
from tegrasp_drake.events import tactile_trial_from_log
from tegrasp_drake.events.correlation import event_scores_reference
from tegrasp_drake.events.extraction import cut_window
from tegrasp_drake.recording.corrective_detection import slip_band
from tegrasp_drake.recording.corrective_events import (CORRECTIVE_RUNS, corrective_scenario,
                                                       slip_onset_time)
from tegrasp_drake.scenario.trial_log_file import load_trial_log
from tegrasp_drake.rig.channels import TAXELS_PER_PAD
from tegrasp_drake.tactile.max_normalization import normalize_by_max

sys.path.insert(0, str(pathlib.Path(__file__).parent))
from record_corrective_events import log_path  # noqa: E402

CONFIG = GraspControllerConfig()
LIFT_S = (4.1, 5.6)  # the script's Lift [s]


def band_window(log, start):
    band = slip_band(log, CONFIG.lift_load.slip_band_hz, CONFIG.lift_load.slip_window_s, 1000.0)
    return cut_window(log.t_ra, band, start_s=start, rate_hz=1000.0, length=500, what="band")


def slip(corrective, ensemble):
    runs = [r for r in CORRECTIVE_RUNS if r.transition == "lift_load"]
    logs = {r.label: load_trial_log(log_path(corrective, "box", r)) for r in runs}
    onsets = {r.label: slip_onset_time(logs[r.label], corrective_scenario("box", r)) for r in runs}
    template = normalize_by_max(np.mean([normalize_by_max(
        band_window(logs[r.label], onsets[r.label] - 0.45)) for r in runs
        if r.role == "template"], axis=0))

    def best(log, before=None):
        ends = np.arange(LIFT_S[0], LIFT_S[1], 0.005)
        return max(event_scores_reference(list(band_window(log, end - 0.5)), list(template),
                                          0.25).min() for end in ends
                   if before is None or end < before)
    for r in runs:
        print(f"slip run '{r.label}' ({r.role}): best min-score in Lift "
              f"{best(logs[r.label]):.3f}")
    for k in range(8):
        print(f"normal grasp {k}: best min-score in Lift "
              f"{best(load_trial_log(ensemble / 'box' / f'run{k}.npz')):.3f}")


def first_contact(log):
    true = np.asarray(log.true_taxels)
    left, right = true[:, :TAXELS_PER_PAD].sum(1), true[:, TAXELS_PER_PAD:].sum(1)
    k = np.flatnonzero((left > 0.2) | (right > 0.2))[0]
    return log.t_sa[k], "left" if left[k] > 0.2 else "right"


def contact_window(log, t0):
    trial = tactile_trial_from_log(log)
    sa = cut_window(trial.t_sa, trial.sa, start_s=t0 - 0.45, rate_hz=108.0, length=54,
                    what="SA")
    ra = cut_window(trial.t_ra, trial.ra, start_s=t0 - 0.45, rate_hz=1000.0, length=500,
                    what="RA")
    return [*sa, *ra]


def one_finger(grid, ensemble):
    paths = sorted(grid.glob("open_loop.box.m*.npz"))
    reference = load_trial_log(grid / "open_loop.box.m02.a0.npz")
    template = [normalize_by_max(w) for w in contact_window(reference,
                                                             first_contact(reference)[0])]
    for path in paths + [ensemble / "box" / f"run{k}.npz" for k in range(3)]:
        log = load_trial_log(path)
        t0, side = first_contact(log)
        scores = event_scores_reference(contact_window(log, t0), template, 0.25)
        print(f"{path.name}: first contact {side} at {t0:.3f} s, scores "
              f"{np.round(scores, 3)}")


def main(argv=None) -> int:
    parser = script_parser("corrective_feasibility", __doc__)
    for name, advice in (("corrective_logs", CORRECTIVE_LOGS_ADVICE),
                         ("ensemble_logs", ENSEMBLE_LOGS_ADVICE),
                         ("grid_logs", "give the --logs folder of a `tegrasp sweep`")):
        parser.add_input(name, type=pathlib.Path, what=name.replace("_", " ") + " folder",
                         advice=advice)
    args = parser.parse_args(argv)
    corrective, ensemble, grid = args.corrective_logs, args.ensemble_logs, args.grid_logs
    slip(corrective, ensemble)
    one_finger(grid, ensemble)
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "corrective_feasibility"))
