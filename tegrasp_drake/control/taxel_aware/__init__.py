"""The taxel-aware controller: the paper's rule table extended by rules that read the whole
taxel array (table.py, one module per rule), over what one ContactEstimator senses
(estimator.py)."""

from tegrasp_drake.control.taxel_aware.estimator import (ContactEstimate, ContactEstimator,
                                                         ContactMemory, ContactReading,
                                                         ObjectGeometry, estimator_for_plan)
from tegrasp_drake.control.taxel_aware.table import TAXEL_AWARE_TABLE, rule_table

__all__ = ["ContactEstimate", "ContactEstimator", "ContactMemory", "ContactReading",
           "ObjectGeometry", "TAXEL_AWARE_TABLE", "estimator_for_plan", "rule_table"]
