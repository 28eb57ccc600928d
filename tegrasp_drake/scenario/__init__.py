"""What every user imports first: the typed Scenario loaded from YAML, the station it
names, the grasp diagram around that station, its simulator, and the trial log its
loggers write.

    from tegrasp_drake.scenario import LoadScenario, MakeGraspDiagram, MakeSimulator
"""

from tegrasp_drake.scenario.grasp_diagram import (AddScenarioController, GraspDiagram,
                                                  MakeGraspDiagram, MakeSimulatedStation,
                                                  MakeSimulator, MakeStation)
from tegrasp_drake.scenario.scenario import (DEFAULT_SCENARIO, LoadScenario, Scenario,
                                             grasp_plan, object_pose, sample_rates_hz,
                                             scenario_to_yaml,
                                             with_controller)
from tegrasp_drake.scenario.trial_log_file import TrialLog, TrialLogError, load_trial_log
