#!/bin/sh
# Re-record every events folder of the linkage hand that depends on the ideal grasp's
# script or on the transitions' anchors, and re-choose the thresholds by their rules.
#
#     sh analysis/rerecord_events.sh LOGS_DIR [WORKERS]
#
# Run from the checkout's top folder (it writes events/ and the threshold tables in
# analysis/). LOGS_DIR receives the campaign logs (a log already there is reused: give an
# empty folder after changing the script, the gripper or the sensors). In order:
#   1. events/<object>/     the paper's events of the three built-in objects (one ideal
#                           grasp each; tegrasp record-events)
#   2. events/ensemble/     the taxel_aware controller's ensemble events (8 randomised ideal
#                           grasps per object, the first 5 make the events)
#   3. analysis/ensemble_thresholds.md   their Eq. 3 thresholds, chosen on runs 5-7 by the
#                           written rule; copy the printed pairs into
#                           gripper_hands.LinkageHand.ensemble_thresholds if they changed
#   4. events/corrective/   the box's memorized corrective events (8 open-loop runs)
#   5. analysis/corrective_thresholds.md  their thresholds, by the written rule; copy the
#                           printed pairs into GraspControllerConfig
#                           (lift_load_event_thresholds, hold_avoid_event_thresholds)
# events/prismatic/ (the earlier prismatic hand's, kept for comparison) is not rebuilt here.
# 35 simulated grasps (3 + 24 + 8), each about 10-15 s of wall on an idle core, plus the
# replays that choose the thresholds: with 2 workers it took 28 minutes on a 2-core host
# shared with other jobs (load average 11-14).
set -e
LOGS=${1:?usage: sh analysis/rerecord_events.sh LOGS_DIR [WORKERS]}
WORKERS=${2:-2}
tegrasp record-events --events events --ensemble-runs 0
python analysis/record_ensemble_events.py "$LOGS/ensemble" --runs 8 --template-runs 5 \
    --workers "$WORKERS" --events events
python analysis/choose_ensemble_thresholds.py "$LOGS/ensemble" analysis/ensemble_thresholds.md \
    --runs 5 6 7 --events events
python analysis/record_corrective_events.py "$LOGS/corrective" --object box \
    --workers "$WORKERS" --events events
python analysis/choose_corrective_thresholds.py "$LOGS/corrective" "$LOGS/ensemble" \
    analysis/corrective_thresholds.md --object box --events events
