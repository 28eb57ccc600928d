"""A trial function that tells which process imported its module (no tests here): the fork
server that starts a sweep's workers, when it preloads it, or each worker."""

import os

from tests.fake_trials import fake_trial

IMPORTED_IN_PID = os.getpid()


def import_reporting_trial(trial):
    """fake_trial's result plus the process that imported this module and the one running."""
    return {**fake_trial(trial), "imported_in_pid": IMPORTED_IN_PID, "worker_pid": os.getpid()}
