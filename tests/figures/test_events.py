"""The Fig. 5c-like figure of memorized events."""

import numpy as np
import pytest
from matplotlib.image import imread

from tegrasp_drake.events.extraction import extract_memorized_events
from tegrasp_drake.figures.events import plot_memorized_events
from tegrasp_drake.figures.figure_files import PNG_DPI
from tegrasp_drake.events.synthetic import SyntheticGraspConfig, synthetic_grasp


def test_plot_saves_a_grid_of_transitions_by_channels(tmp_path):
    events = extract_memorized_events(synthetic_grasp(SyntheticGraspConfig()),
                                      object_name="box", sa_rate_hz=100.0,
                                      ra_rate_hz=1000.0, package_versions={})
    path = plot_memorized_events({"box": events}, tmp_path / "figures" / "events.png")
    image = imread(path)
    # A row of panels per transition under the title, a column per channel.
    assert image.shape[:2] == (round((0.6 + 2.2 * len(events)) * PNG_DPI), 4 * 3 * PNG_DPI)
    assert np.ptp(image[..., :3]) > 0.5  # not a blank canvas


def test_plot_refuses_an_empty_selection(tmp_path):
    with pytest.raises(ValueError, match="no memorized events"):
        plot_memorized_events({}, tmp_path / "events.png")
