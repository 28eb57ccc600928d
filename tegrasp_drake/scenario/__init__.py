"""What every user imports first: the typed Scenario loaded from YAML, the station it names,
the grasp diagram around it, its simulator, and the trial log its loggers write.

    from tegrasp_drake.scenario import LoadScenario, MakeGraspDiagram, MakeSimulator

scenario.py: Scenario, LoadScenario and validate, the checks that relate fields.
grasp_diagram.py: MakeStation, MakeGraspDiagram, MakeSimulator.
scenario_events.py: the memorized events a scenario's controller reads.
object_placement.py: the object's pose from its marker, offset and yaw.
moved_keys.py: settings' old paths, refused in input and migrated in stored records.
rule_reach.py: which taxel_aware rules one pad alone can fire for an object (the docs' table).
trial_log_writer.py, trial_log_file.py: the trial's loggers and its TrialLog .npz file.
logged_channels.py: a log's channels checked against the taxels and accelerations (Eq. 1-2).
trial_result.py: TrialResult, a trial's outcome and its JSON form (read back with the log).
grasp_outcome.py: the ground-truth judge and the physical events' times.
trial_judge.py: judge_trial, and a stored result checked against it (every log's reader).
physical_event_search.py: where each event transition's physical event is searched from."""

from tegrasp_drake.scenario.grasp_diagram import (AddScenarioController, GraspDiagram,
                                                  MakeGraspDiagram, MakeSimulatedStation,
                                                  MakeSimulator, MakeStation)
from tegrasp_drake.scenario.scenario import (DEFAULT_SCENARIO, LoadScenario, Scenario,
                                             grasp_plan, object_pose, sample_rates_hz,
                                             scenario_to_yaml,
                                             with_controller)
from tegrasp_drake.scenario.trial_log_file import TrialLog, TrialLogError, load_trial_log
