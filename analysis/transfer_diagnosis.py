"""Which channel's Eq. 3 score falls short, per transition, in trials run with events
memorized elsewhere (docs/transfer.md, "What breaks transfer").

    python analysis/transfer_diagnosis.py EVENTS_DIR RUN_DIR... [--ra-envelope-hz F]

Each RUN_DIR is a `tegrasp trial --out` folder (trial.npz, result.json); EVENTS_DIR the
events folder its trial read. For every memorized event and every mode that waited for it,
the logged channels are scored offline (the reference Eq. 3, events/correlation.py) every
5 ms: "best" is each channel's highest score while the mode waited, "together" the four
scores at the tick where all four came nearest their thresholds (the smallest margin over
SA 0.9 and RA 0.7 at its largest), "match" whether that tick passes. --ra-envelope-hz
scores with the RA envelope on both sides (events/ra_envelope.py).
"""

import argparse
import json
import pathlib
import sys

import numpy as np

from tegrasp_drake.events.correlation import event_scores_reference
from tegrasp_drake.events.event_matcher import EventMatcherConfig, event_templates
from tegrasp_drake.events.events_folder import load_memorized_events
from tegrasp_drake.events.ra_envelope import enveloped_event, ra_envelope
from tegrasp_drake.events.replay import tactile_trial_from_log
from tegrasp_drake.scenario.trial_log_file import load_trial_log
from tegrasp_drake.rig.channels import RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.tactile.sampling import samples_per_window

WAITING_MODE = {"reach_load": "Reach", "load_lift": "Load", "place_unload": "Place"}
STEP_S = 0.005  # the matcher's tick (controller.update_period_s)


def mode_periods(transitions: list[dict]) -> list[tuple[str, float, float]]:
    """(mode, entered, left) [s] of each mode the trial passed through, from Reach."""
    periods, mode, entered = [], "Reach", 0.0
    for transition in transitions:
        periods.append((mode, entered, transition["t"]))
        mode, entered = transition["to"], transition["t"]
    return periods


def diagnose(run: pathlib.Path, events_dir, ra_envelope_hz: float) -> dict:
    log = tactile_trial_from_log(load_trial_log(run / "trial.npz"))  # SA at the taxel times
    result = json.loads((run / "result.json").read_text())
    config = EventMatcherConfig()
    sa_rate = 1.0 / float(np.median(np.diff(log.t_sa)))
    ra_rate = 1.0 / float(np.median(np.diff(log.t_ra)))
    sa, ra = np.asarray(log.sa, dtype=float).T, np.asarray(log.ra, dtype=float).T
    if ra_envelope_hz:
        ra = ra_envelope(ra, ra_envelope_hz, ra_rate)
    thresholds = np.array([config.sa_threshold] * len(SA_CHANNELS)
                          + [config.ra_threshold] * len(RA_CHANNELS))
    report = {}
    for transition, event in load_memorized_events(events_dir, result["object"]).items():
        if ra_envelope_hz:
            event = enveloped_event(event, ra_envelope_hz)
        n_sa = samples_per_window(event.window_s, sa_rate)
        n_ra = samples_per_window(event.window_s, ra_rate)
        templates = (list(event_templates(event, SA_CHANNELS, n_sa))
                     + list(event_templates(event, RA_CHANNELS, n_ra)))
        best, together = np.full(4, -1.0), None
        for mode, entered, left in mode_periods(result["transitions"]):
            if mode != WAITING_MODE[transition]:
                continue
            for t in np.arange(entered + STEP_S, left + 1e-9, STEP_S):
                i = int(np.searchsorted(log.t_sa, t, "right"))
                j = int(np.searchsorted(log.t_ra, t, "right"))
                if i < n_sa or j < n_ra:
                    continue
                live = list(sa[:, i - n_sa:i]) + list(ra[:, j - n_ra:j])
                scores = event_scores_reference(live, templates, config.min_contrast)
                best = np.maximum(best, scores)
                margin = float(np.min(scores - thresholds))
                if together is None or margin > together[0]:
                    together = (margin, float(t), scores)
        if together is not None:
            report[transition] = {"best": best.round(3).tolist(), "at_s": round(together[1], 3),
                                  "together": together[2].round(3).tolist(),
                                  "match": together[0] > 0.0}
    return {"run": run.name, "final_mode": result["final_mode"], "transitions": report}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("events", help="the events folder the trials read")
    parser.add_argument("runs", nargs="+", help="trial folders (tegrasp trial --out)")
    parser.add_argument("--ra-envelope-hz", type=float, default=0.0)
    args = parser.parse_args(argv)
    for run in map(pathlib.Path, args.runs):
        if not (run / "trial.npz").is_file() or not (run / "result.json").is_file():
            print(f"transfer_diagnosis.py: error: {run} holds no trial.npz and result.json "
                  "(give folders that `tegrasp trial --out` wrote)", file=sys.stderr)
            return 2
        print(json.dumps(diagnose(run, args.events, args.ra_envelope_hz)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
