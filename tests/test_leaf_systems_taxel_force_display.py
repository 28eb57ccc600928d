"""Fixed-input test of TaxelForceDisplay: after a publish, Meshcat holds each pad's group at
the pad's pose and each taxel's bar at the length and colour its force gives (read back
from Meshcat's own messages, as Drake's Meshcat tests do)."""

import functools

import msgpack
import numpy as np
import pytest
from pydrake.geometry import Meshcat
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.tree import BodyIndex

from tegrasp_drake.simulation.tactile_pads import PadGeometry
from tegrasp_drake.simulation.taxel_force_display import (TaxelForceDisplay,
                                                          TaxelForceDisplayConfig)

CONFIG = TaxelForceDisplayConfig(meters_per_newton=0.0025, full_scale_n=8.0,
                                 visible_threshold_n=0.05)
X_BP = {"left": RigidTransform(RollPitchYaw(0.3, 0.0, 0.0), [0.0, 0.01, 0.02]),
        "right": RigidTransform([0.0, -0.01, 0.02])}
PADS = {"left": PadGeometry(None, BodyIndex(1), X_BP["left"]),
        "right": PadGeometry(None, BodyIndex(2), X_BP["right"])}
X_WB = [RigidTransform(), RigidTransform(RollPitchYaw(0.0, 0.0, 0.5), [0.4, 0.1, 0.2]),
        RigidTransform([0.4, -0.1, 0.2])]
LEFT_FORCES = np.zeros(12)
LEFT_FORCES[[0, 5, 7, 11]] = [0.04, 2.0, 4.0, 20.0]  # N: below the threshold, 1/4 scale,
# 1/2 scale, beyond full scale


@functools.cache
def _published() -> Meshcat:
    meshcat = Meshcat()
    display = TaxelForceDisplay(meshcat=meshcat, pads=PADS, config=CONFIG, prefix="taxels")
    context = display.CreateDefaultContext()
    context.SetTime(0.25)
    display.GetInputPort("body_poses").FixValue(context, X_WB)
    display.GetInputPort("left_taxel_forces").FixValue(context, LEFT_FORCES)
    display.GetInputPort("right_taxel_forces").FixValue(context, np.full(12, 1.0))
    display.ForcedPublish(context)
    return meshcat


def _property(path: str, name: str):
    return msgpack.unpackb(_published()._GetPackedProperty(path, name))["value"]


def test_each_pads_group_is_posed_at_the_pad_frame():
    for finger, body in (("left", 1), ("right", 2)):
        message = msgpack.unpackb(_published()._GetPackedTransform(f"/taxels/{finger}"))
        matrix = np.reshape(message["matrix"], (4, 4)).T  # three.js: column-major
        np.testing.assert_allclose(matrix, (X_WB[body] @ X_BP[finger]).GetAsMatrix4(),
                                   rtol=0, atol=1e-12)


# Colour anchors (ColorBrewer YlOrRd) at 0, 1/3, 2/3 and 1 of full scale.
YELLOW, ORANGE, RED, DARK_RED = ((0.996, 0.851, 0.463), (0.992, 0.553, 0.235),
                                 (0.890, 0.102, 0.110), (0.502, 0.000, 0.149))


def _between(a, b, fraction):
    return [x + fraction * (y - x) for x, y in zip(a, b)]


@pytest.mark.parametrize("finger, taxel, length, rgb", [
    ("left", 0, 0.0005, (0.55, 0.57, 0.62)),  # 0.04 N: the grey tile
    ("left", 3, 0.0005, (0.55, 0.57, 0.62)),  # 0 N
    ("left", 5, 0.005, _between(YELLOW, ORANGE, 0.75)),  # 2 N = 0.25 of scale
    ("left", 7, 0.010, _between(ORANGE, RED, 0.5)),  # 4 N = 0.5 of scale
    ("left", 11, 0.050, DARK_RED),  # 20 N: length grows on, the colour saturates
    ("right", 4, 0.0025, _between(YELLOW, ORANGE, 0.375)),  # 1 N = 0.125 of scale
])
def test_each_bar_has_the_length_and_colour_of_its_force(finger, taxel, length, rgb):
    path = f"/taxels/{finger}/taxel_{taxel:02d}"
    np.testing.assert_allclose(_property(path, "scale"), [1.0, 1.0, length], rtol=1e-12)
    np.testing.assert_allclose(_property(f"{path}/bar", "color"), [*rgb, 1.0], rtol=0,
                               atol=1e-12)
