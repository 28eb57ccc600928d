"""How a taxel's force is drawn: bar length and colour."""

import numpy as np
import pytest

from tegrasp_drake.simulation.taxel_force_display import (TaxelForceDisplayConfig,
                                                          taxel_bar_length, taxel_force_color)

CONFIG = TaxelForceDisplayConfig()


def test_bar_grows_with_force_above_the_threshold():
    assert taxel_bar_length(0.0, CONFIG) == taxel_bar_length(0.5 * CONFIG.visible_threshold_n,
                                                             CONFIG)
    assert taxel_bar_length(2.0, CONFIG) == pytest.approx(2.0 * CONFIG.meters_per_newton)
    assert taxel_bar_length(4.0, CONFIG) == pytest.approx(2 * taxel_bar_length(2.0, CONFIG))


def test_colour_darkens_with_force_and_saturates_at_full_scale():
    forces = np.linspace(0.0, CONFIG.full_scale_n, 9)
    brightness = [sum(taxel_force_color(f, CONFIG.full_scale_n)) for f in forces]
    assert all(np.diff(brightness) < 0)
    assert taxel_force_color(3 * CONFIG.full_scale_n, CONFIG.full_scale_n) == \
        taxel_force_color(CONFIG.full_scale_n, CONFIG.full_scale_n)
    assert all(0.0 <= c <= 1.0 for f in forces for c in taxel_force_color(f, CONFIG.full_scale_n))
