"""An earlier `tegrasp hardware` run's files, as tests place them where a new run would write:
a log that starts as an LCM log does and a result with the entries every run's result holds
(what `--overwrite` may replace: commands/hardware.earlier_run_file_problem)."""

import json

from tegrasp_drake.runs.hardware_log_reader import LCM_LOG_START

EARLIER_LOG = LCM_LOG_START + b"the earlier run's log"
EARLIER_RESULT = json.dumps({"transitions": [], "faults": [], "log": "run.lcmlog",
                             "device_counters": {}, "earlier": True}) + "\n"
