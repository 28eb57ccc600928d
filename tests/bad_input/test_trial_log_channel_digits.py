"""A logged channel that differs from its Eq. 1 sum past the tolerance but not in its first six
digits is named with both numbers to their last digit, never as "12 ... sum to 12"."""

import numpy as np

from tests.bad_input.probes import channels_of, refused_log, trial_log


def test_a_channel_off_in_its_seventh_digit_is_shown_to_its_last(tmp_path):
    with np.load(trial_log(tmp_path / "whole.npz")) as whole:
        arrays = {name: whole[name] for name in whole.files if name != "meta"}
    channels = channels_of(arrays)
    assert channels[40, 1] == 12.0  # twelve taxels of 1 N
    channels[40, 1] = 12.000001
    message = refused_log(tmp_path, channels=channels)
    assert "column 1 (sa_right) holds 12.000001, but the pad's 12 taxels" in message, message
    assert "sum to 12.0 (Eq. 1)" in message, message
