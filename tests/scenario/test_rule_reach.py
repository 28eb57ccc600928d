"""The one-pad reach tables (scenario/rule_reach.py): what one pad alone can press before
the object tips or slides, read from the scenario, against the counts in force; the docs show
the tables the code computes."""

import dataclasses
import pathlib

import pytest

from tegrasp_drake.control.taxel_aware import TAXEL_AWARE_TABLE
from tegrasp_drake.control.taxel_aware.contact_geometry import one_pad_push
from tegrasp_drake.scenario.rule_reach import (RULE_COUNTS, documented_table, grid_objects,
                                               main, reach_markdown, rule_reach)
from tegrasp_drake.scenario.scenario import LoadScenario

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "controller.md"


def test_the_docs_show_the_tables_the_code_computes():
    assert documented_table(PAGE.read_text()) == reach_markdown(), (
        "run python -m tegrasp_drake.scenario.rule_reach --write docs/controller.md")


def test_the_check_command_finds_a_stale_number(tmp_path, capsys):
    page = tmp_path / "controller.md"
    page.write_text(PAGE.read_text().replace("| 0.60 N |", "| 0.61 N |", 1))
    assert main(["--check", str(page)]) == 1
    assert main(["--write", str(page)]) == 0
    assert page.read_text() == PAGE.read_text()


def test_a_push_tips_where_the_moments_balance_and_slides_at_the_pair_friction():
    # a 1 kg, 40 mm wide object pushed 50 mm up: the weight's moment about the far edge
    # 9.81 x 0.02 = 0.196 N m over the 0.05 m lever is 3.92 N; mu 0.3 slides it at 2.94 N
    push = one_pad_push(weight_n=9.81, object_width_m=0.04, contact_height_m=0.05,
                        table_friction=0.3)
    assert push.tips_n == pytest.approx(3.924)
    assert push.slides_n == pytest.approx(2.943)
    assert push.limit_n == push.slides_n


def test_the_contact_height_and_counts_are_the_scenarios():
    default = rule_reach()
    lower = rule_reach(LoadScenario(controller="taxel_aware",
                                    overrides=["grasp.grasp_height=0.0275"]))
    force = rule_reach(LoadScenario(controller="taxel_aware",
                                    overrides=["gripper.model=prismatic",
                                               "tactile.transducer=force"]))
    box, low_box = default.objects[0], lower.objects[0]
    assert low_box.push.tips_n == pytest.approx(2 * box.push.tips_n)
    assert low_box.push.slides_n == pytest.approx(box.push.slides_n)
    # the capacitive pad's noise raises the counts above the ideal force taxels' settings
    assert default.taxel_contact_n > force.taxel_contact_n
    assert default.contact_force_n > force.contact_force_n
    assert "box" in force.reaches("pad") and "box" not in default.reaches("taxel")


def test_the_mass_columns_are_where_the_limit_meets_the_counts():
    reach = rule_reach()
    for (name, obj), o in zip(grid_objects(), reach.objects):
        for mass, count in ((o.mass_for_taxel_kg, reach.taxel_contact_n),
                            (o.mass_for_pad_kg, reach.contact_force_n)):
            (at,) = rule_reach(objects=[(name, dataclasses.replace(obj, mass=mass))]).objects
            assert at.push.limit_n == pytest.approx(count), name


def test_every_rule_and_guard_the_controller_adds_has_its_count():
    added = {r.name for r in TAXEL_AWARE_TABLE.all_rules()
             if TAXEL_AWARE_TABLE.origin(r.name) == TAXEL_AWARE_TABLE.name}
    guards = {g.name for g in TAXEL_AWARE_TABLE.all_guards()}
    assert set(RULE_COUNTS) == added | guards | {"one_sided"}
    assert TAXEL_AWARE_TABLE.rule("one_sided")
