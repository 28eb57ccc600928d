"""The contact-geometry benchmark's parts (benchmarks/geometry.py): which variants change an
object's plant, and the instants its taxel forces are compared at."""

from benchmarks.geometry import VARIANTS, _contact_times, _plant_key
from tegrasp_drake.scenario.scenario import LoadScenario


def _keys(scenario, folder) -> dict:
    return {name: _plant_key(variant) for name, make in VARIANTS.items()
            if (variant := make(scenario, folder)) is not None}


def test_the_box_setting_changes_the_box_and_not_a_cylinder(tmp_path):
    box = _keys(LoadScenario(name="box"), tmp_path)
    cylinder = _keys(LoadScenario(name="thick_cylinder"), tmp_path)
    assert box["box_12_triangles"] != box["reference"]
    assert cylinder["box_12_triangles"] == cylinder["reference"]
    assert "cylinder_facets_10mm" not in box  # a box has no facets to coarsen
    assert cylinder["cylinder_facets_10mm"] != cylinder["reference"]
    assert box["table_half_space"] != box["reference"]


def test_taxels_are_compared_through_the_contact_phases_only():
    timeline = [(0.0, "reach"), (1.0, "close"), (1.05, "lift"), (1.1, "hold"),
                (1.2, "place"), (1.25, "unload")]
    times = _contact_times(timeline)
    assert times[0] == 1.0 and times[-1] < 1.25
    assert len(times) == 25  # 0.25 s every 10 ms

