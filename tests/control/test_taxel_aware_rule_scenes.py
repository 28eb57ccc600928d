"""Every rule and guard the taxel_aware controller runs on the 2F-85 linkage hand, beyond the
paper's, has a closed-loop scene there that names it: one of the linkage scenes
(test_taxel_aware_linkage_scenes.SCENES, whose expected transitions carry rule codes) or a
test of its own (OWN_SCENE_TESTS). The rules kept to the prismatic hand are not run there
(docs/controller.md, "Rules kept to the prismatic hand"). No simulation: the scenes' data
and the tests' names only."""

import ast
import pathlib

from tegrasp_drake.control.taxel_aware import TAXEL_AWARE_TABLE
from tegrasp_drake.control.transition_logic import PAPER_TABLE
from tests.control.test_taxel_aware_linkage_scenes import SCENES

ROOT = pathlib.Path(__file__).resolve().parents[2]
LINKAGE_SCENES = "tests/control/test_taxel_aware_linkage_scenes.py"
SCENE_TEST = f"{LINKAGE_SCENES}::test_the_scene_is_decided_by_its_rules_and_grasped"
LIFT = ("tests/control/test_taxel_aware_lift.py::"
        "test_the_rod_pushed_along_the_stroke_is_lifted_once_gripped_and_stays_held")

# Rule or guard -> the linkage test whose scene it decides (or holds back) in.
OWN_SCENE_TESTS = {
    "grip_settling": LIFT,
    "touch_confirmed": LIFT,
    "touch_unconfirmed": (f"{LINKAGE_SCENES}::"
                          "test_a_reach_load_match_no_pad_touch_confirms_does_not_load"),
    "regrasp_set_down": (f"{LINKAGE_SCENES}::"
                         "test_a_regrasp_opens_only_once_the_place_move_has_set_the_object_down"),
    "place_set_down": (f"{LINKAGE_SCENES}::"
                       "test_a_place_opens_only_once_the_place_move_has_set_the_object_down"),
}


def names(table) -> set:
    return {item.name for item in (*table.all_rules(), *table.all_guards())}


def scene_codes() -> set:
    """The rule codes the linkage scenes expect in their transitions."""
    return {code for _, expect in SCENES.values() for _, _, code in expect.steps}


def test_every_rule_the_linkage_hand_runs_beyond_the_papers_has_a_linkage_scene():
    added = names(TAXEL_AWARE_TABLE.for_hand("linkage")) - names(PAPER_TABLE)
    named = (scene_codes() | set(OWN_SCENE_TESTS)) - names(PAPER_TABLE)
    assert sorted(added - named) == [], "no linkage scene names these"
    assert sorted(named - added) == [], "these have a scene but the linkage hand runs none"


def test_the_scene_tests_named_exist():
    for test in {SCENE_TEST, *OWN_SCENE_TESTS.values()}:
        path, name = test.split("::")
        tree = ast.parse((ROOT / path).read_text())
        functions = {node.name for node in tree.body if isinstance(node, ast.FunctionDef)}
        assert name in functions, test
