"""Where the object stands (scenario/object_placement.py): its marker within the arm's
reach, a misplacement near it, and the object on the table."""

import pytest

from tegrasp_drake.rig.ranges import check_ranges
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.object_placement import ObjectPlacementConfig

BOX = ("box", [0.045, 0.045, 0.11])


def test_the_marker_and_the_offset_declare_their_ranges():
    with pytest.raises(ConfigError, match=r"field 'expected_xy\[0\]' must lie in \[-0.9, 0.9\] m "
                       r"\(within the JACO2's 0.9 m reach"):
        check_ranges(ObjectPlacementConfig(expected_xy=[1.2, 0.0]), "here")
    with pytest.raises(ConfigError, match=r"field 'offset' must hold 2 numbers \[m\]"):
        check_ranges(ObjectPlacementConfig(offset=[0.0]), "here")


def test_the_object_must_stand_on_the_table():
    assert ObjectPlacementConfig(offset=[0.01, 0.015]).problem(*BOX) is None
    field, words, value = ObjectPlacementConfig(expected_xy=[0.9, 0.49]).problem(*BOX)
    assert (field, value) == ("offset", [0.0, 0.0])
    assert "puts the object at (0.900, 0.490) m" in words and "off the table top" in words
