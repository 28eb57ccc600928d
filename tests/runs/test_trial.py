"""run_trial's one boundary between the simulation and its caller: a Drake failure while the
trial steps is a one-line SimulationFailedError naming the time, not an internal error."""

import pytest

from tegrasp_drake.runs.trial import SimulationFailedError, _step
from tegrasp_drake.rig.typed_yaml import ConfigError


class _Context:
    def get_time(self) -> float:
        return 1.25


def _singular_mass_matrix():
    raise RuntimeError("An internal mass matrix associated with the joint that connects body "
                       "world to body object is not positive-definite. Since the joint allows "
                       "rotation, ensure body object has reasonable non-zero moments.")


def test_a_drake_failure_while_stepping_is_one_line_naming_the_time():
    with pytest.raises(SimulationFailedError) as error:
        _step(_singular_mass_matrix, _Context())
    message = str(error.value)
    assert "\n" not in message and "t = 1.250 s" in message
    assert "not positive-definite" in message and "Since the joint" not in message
    assert "--set" in message  # what to check
    assert isinstance(error.value, ConfigError)  # refused as bad settings are


def test_other_errors_pass_through():
    def broken():
        raise KeyError("a bug")
    with pytest.raises(KeyError):
        _step(broken, _Context())
