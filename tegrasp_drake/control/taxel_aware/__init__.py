"""The taxel-aware controller: corrections from the whole taxel array, as a rule table
(table.py) over what one ContactEstimator senses (estimator.py), one module per rule."""

from tegrasp_drake.control.taxel_aware.decision import (Failed, Lift, Load, Reason, Regrasp,
                                                        ReReach, Rule, Situation)
from tegrasp_drake.control.taxel_aware.estimator import (ContactEstimate, ContactEstimator,
                                                         ContactMemory, ContactReading,
                                                         ObjectGeometry, estimator_for_plan)
from tegrasp_drake.control.taxel_aware.table import ANY_MODE, TABLE, next_mode, rows

__all__ = ["ANY_MODE", "TABLE", "ContactEstimate", "ContactEstimator", "ContactMemory",
           "ContactReading", "Failed", "Lift", "Load", "ObjectGeometry", "Reason", "Regrasp",
           "ReReach", "Rule", "Situation", "estimator_for_plan", "next_mode", "rows"]
