"""Public constructors and builders refuse what the loaders refuse: a choice field handed to
a builder, a transition that does not change mode, a result's latency longer than any run."""

import pytest

from tegrasp_drake.rig.typed_yaml import ConfigError


# Rule: a builder given a config checks its choices as the loader does, not only its ranges
# (scheduling='rr' went on to open the devices).
@pytest.mark.parametrize("mutate", [False, True], ids=["built", "changed-after"])
def test_a_hardware_config_with_an_unknown_scheduling_is_refused_by_the_builder(mutate):
    from tegrasp_drake import MakeHardwareStation
    from tegrasp_drake.hardware.config import HardwareStationConfig
    with pytest.raises(ConfigError, match="field 'scheduling' must be one of 'fifo', 'nice', "
                                          "'normal', got str 'rr'"):
        if mutate:
            config = HardwareStationConfig()
            config.scheduling = "rr"
        else:
            config = HardwareStationConfig(scheduling="rr")
        MakeHardwareStation(config)
