"""The committed events/ are record-events' output (events issue acceptance)."""

import numpy as np
import pytest

from tegrasp_drake.rig import paths
from tegrasp_drake.experiments.record_events import record_events
from tegrasp_drake.events import load_memorized_events
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS

pytestmark = pytest.mark.slow


@pytest.mark.parametrize("object_name", sorted(BUILTIN_OBJECTS))
def test_rerunning_record_events_reproduces_the_committed_files(object_name):
    committed = load_memorized_events(paths.events_dir(), object_name)
    recorded = record_events(object_name)
    assert set(recorded) == set(committed)
    for transition, event in recorded.items():
        np.testing.assert_allclose(event.sa, committed[transition].sa, rtol=0, atol=1e-12)
        np.testing.assert_allclose(event.ra, committed[transition].ra, rtol=0, atol=1e-12)
