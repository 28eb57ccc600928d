"""The annotations of the trial figures: labels that never overlap, and the run's
description read from the log."""

import itertools

import pytest

from tegrasp_drake.figures.figure_files import new_figure
from tegrasp_drake.figures.trial_annotations import Label, stack_labels


def _extents(axis):
    renderer = axis.figure.canvas.get_renderer()
    boxes = []
    for text in axis.texts:
        patch = text.get_bbox_patch()
        if patch is not None:
            text.update_bbox_position_size(renderer)
        boxes.append((patch or text).get_window_extent(renderer))
    return boxes


@pytest.mark.parametrize("boxed", [False, True])
def test_stacked_labels_do_not_overlap(boxed):
    figure = new_figure(8.0, 2.0)
    axis = figure.subplots()
    axis.set_xlim(0.0, 14.0)
    figure.draw_without_rendering()
    # Close transitions, as in a grasp: Reach-Load and Load-Lift 0.37 s apart, and a crowd.
    times = [3.76, 4.13, 4.2, 5.63, 7.0, 7.005, 7.64, 11.69, 13.74]
    labels = [Label(t, f"Transition {k}\nSA 0.90/0.90 RA 1.00/1.00", boxed=boxed)
              for k, t in enumerate(times)]
    levels = stack_labels(axis, labels)
    assert levels >= 2  # they cannot all sit on one line
    for a, b in itertools.combinations(_extents(axis), 2):
        assert not a.overlaps(b)


def test_labels_that_fit_stay_on_one_level():
    figure = new_figure(8.0, 1.0)
    axis = figure.subplots()
    axis.set_xlim(0.0, 14.0)
    figure.draw_without_rendering()
    assert stack_labels(axis, [Label(t, "Hold") for t in (1.0, 5.0, 9.0, 13.0)]) == 1
