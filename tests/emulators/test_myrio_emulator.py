"""The myRIO emulator's recordings: a trial log's pad signals, saved and loaded."""

import numpy as np
import pytest

from tegrasp_drake.emulators.myrio_emulator import (
    TactileRecording, TactileRecordingError, load_tactile_recording, save_tactile_recording)


def test_saved_recording_loads_back_with_one_axis_vibration_along_x(tmp_path):
    t = np.linspace(0.0, 1.0, 11)
    forces = np.outer(t, np.arange(12.0))
    vibration = np.sin(t)
    recording = TactileRecording(t, forces, 2 * forces, t, np.column_stack(
        [vibration, -vibration, 0 * vibration]), vibration)
    loaded = load_tactile_recording(save_tactile_recording(tmp_path / "r.npz", recording))
    np.testing.assert_array_equal(loaded.force_times, t)
    np.testing.assert_array_equal(loaded.left_forces, forces)
    np.testing.assert_array_equal(loaded.right_forces, 2 * forces)
    np.testing.assert_array_equal(loaded.left_acceleration, recording.left_acceleration)
    np.testing.assert_array_equal(loaded.right_acceleration[:, 0], vibration)
    np.testing.assert_array_equal(loaded.right_acceleration[:, 1:], 0.0)


def test_a_file_without_the_pad_signals_is_named(tmp_path):
    path = tmp_path / "other.npz"
    np.savez(path, t=np.zeros(3))
    with pytest.raises(TactileRecordingError, match="other.npz"):
        load_tactile_recording(path)
