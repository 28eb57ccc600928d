"""Sweep specs: YAML loading, validation errors, and the expansion into paired trials."""

import dataclasses
import math
import textwrap
from pathlib import Path

import pytest

from tegrasp_drake.sweep.spec import (
    PAPER_CONTROLLERS,
    RandomisationConfig,
    SweepSpec,
    TrialSpec,
    expand_trials,
    marker_names,
    product_grid,
)
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tegrasp_drake.rig.objects import ObjectConfig
from tegrasp_drake.rig.typed_yaml import ConfigError


def write_yaml(tmp_path, text):
    path = tmp_path / "sweep.yaml"
    path.write_text(textwrap.dedent(text))
    return path


# --- The paper's defaults -----------------------------------------------------------


def test_default_spec_is_the_papers_experiment():
    trials = expand_trials(SweepSpec())
    assert {t.controller for t in trials} == set(PAPER_CONTROLLERS)
    for controller in PAPER_CONTROLLERS:
        mine = [t for t in trials if t.controller == controller]
        assert len(mine) == 81  # 3 objects x 9 markers x 3 attempts
        assert sum(t.well_placed for t in mine) == 9
    centre = [t for t in trials if t.well_placed]
    assert {t.marker for t in centre} == {"m11"}
    assert {(t.marker_dx_m, t.marker_dy_m) for t in trials} == {
        (dx, dy) for dx in (-0.010, 0.0, 0.010) for dy in (-0.015, 0.0, 0.015)}


def test_trial_ids_are_unique_and_readable():
    trials = expand_trials(SweepSpec())
    assert len({t.trial_id for t in trials}) == len(trials)
    assert trials[0].trial_id == "memorized/box/m00/a0"
    assert trials[0].pair_id == "box/m00/a0"


# --- Expansion: deterministic and paired --------------------------------------------


def test_expansion_is_deterministic():
    assert expand_trials(SweepSpec(base_seed=7)) == expand_trials(SweepSpec(base_seed=7))


def test_every_controller_gets_the_same_scenes_and_seeds():
    by_pair = {}
    for trial in expand_trials(SweepSpec()):
        scene = dataclasses.replace(trial, trial_id="", controller="")
        by_pair.setdefault(trial.pair_id, set()).add(scene)
    assert len(by_pair) == 81
    assert all(len(scenes) == 1 for scenes in by_pair.values())


def test_a_scene_does_not_depend_on_the_rest_of_the_sweep():
    def scene_key(t):
        return (t.object_name, t.marker_dx_m, t.marker_dy_m, t.attempt)

    alone = expand_trials(SweepSpec(objects=("thin_cylinder",), controllers=("open_loop",),
                                    grid=((0.01, 0.015),), attempts=3))
    full = {scene_key(t): t for t in expand_trials(SweepSpec())}
    for trial in alone:
        assert full[scene_key(trial)].perturbation == trial.perturbation
        assert full[scene_key(trial)].seed == trial.seed


def test_attempts_objects_and_base_seeds_differ():
    trials = expand_trials(SweepSpec(controllers=("memorized",)))
    assert len({t.seed for t in trials}) == len(trials)
    assert len({t.perturbation for t in trials}) == len(trials)
    other = expand_trials(SweepSpec(controllers=("memorized",), base_seed=1))
    assert all(a.seed != b.seed for a, b in zip(trials, other))


def test_perturbations_stay_within_their_bounds():
    randomisation = RandomisationConfig(placement_xy_bound_m=0.003,
                                        placement_yaw_bound_deg=5.0,
                                        friction_scale_bound=0.1, mass_scale_bound=0.2)
    trials = expand_trials(SweepSpec(randomisation=randomisation, attempts=20))
    p = [t.perturbation for t in trials]
    assert max(abs(x.dx_m) for x in p) <= 0.003 and max(abs(x.dy_m) for x in p) <= 0.003
    assert max(abs(x.yaw_rad) for x in p) <= math.radians(5.0)
    assert all(0.9 <= x.friction_scale <= 1.1 and 0.8 <= x.mass_scale <= 1.2 for x in p)
    # Not degenerate: the draws spread over most of the range.
    assert max(x.dx_m for x in p) > 0.002 and min(x.mass_scale for x in p) < 0.85


def test_trial_spec_survives_a_dict_round_trip():
    spec = SweepSpec(objects=("mug",), user_objects={
        "mug": ObjectConfig(name="mug", shape="cylinder", size=[0.04, 0.1], mass=0.3,
                            friction=0.6)})
    for trial in expand_trials(spec)[:3]:
        assert TrialSpec.from_dict(trial.to_dict()) == trial
        assert trial.to_dict()["object_definition"]["size"] == [0.04, 0.1]


def test_a_record_of_the_old_object_fields_reads_as_the_same_object():
    """Records written when a sweep's object had size_m, mass_kg and friction_coefficient
    still turn into their trial, with the object's ObjectConfig."""
    spec = SweepSpec(objects=("mug",), user_objects={
        "mug": ObjectConfig(name="mug", shape="cylinder", size=[0.04, 0.1], mass=0.3,
                            friction=0.6)})
    trial = expand_trials(spec)[0]
    old = trial.to_dict()
    old["object_definition"] = {"shape": "cylinder", "size_m": [0.04, 0.1], "mass_kg": 0.3,
                                "friction_coefficient": 0.6}
    assert TrialSpec.from_dict(old) == trial


def test_marker_names_index_sorted_offsets():
    assert marker_names(product_grid((-0.01, 0.0, 0.01), (-0.015, 0.0, 0.015))) == [
        "m00", "m01", "m02", "m10", "m11", "m12", "m20", "m21", "m22"]
    wide = product_grid([0.001 * k for k in range(11)], (0.0,))
    assert marker_names(wide)[10] == "m1000"


# --- YAML ----------------------------------------------------------------------------


def test_yaml_spec_with_product_grid_and_user_object(tmp_path):
    path = write_yaml(tmp_path, """
        objects: [box, mug]
        controllers: [memorized, open_loop]
        attempts: 2
        base_seed: 42
        grid: {normal_offsets_m: [0.0], stroke_offsets_m: [-0.02, 0.0, 0.02]}
        randomisation: {placement_xy_bound_m: 0.001, sensor_noise: false}
        user_objects:
          mug: {shape: cylinder, size: [0.04, 0.1], mass: 0.3, friction: 0.6}
        """)
    spec = LoadSweepSpec(path)
    assert spec.grid == ((0.0, -0.02), (0.0, 0.0), (0.0, 0.02))
    assert spec.randomisation == RandomisationConfig(placement_xy_bound_m=0.001,
                                                     sensor_noise=False)
    trials = expand_trials(spec)
    assert len(trials) == 2 * 2 * 3 * 2
    mug = [t for t in trials if t.object_name == "mug"]
    assert mug[0].object_definition == ObjectConfig(name="mug", shape="cylinder",
                                                    size=[0.04, 0.1], mass=0.3, friction=0.6)
    assert not any(t.sensor_noise for t in trials)


def test_yaml_spec_with_a_list_of_markers(tmp_path):
    spec = LoadSweepSpec(write_yaml(tmp_path, "grid: [[0, 0], [0.005, -0.01]]\n"))
    assert spec.grid == ((0.0, 0.0), (0.005, -0.01))
    assert spec.objects == SweepSpec().objects


def test_an_empty_yaml_file_is_refused_not_run_as_the_papers_experiment(tmp_path):
    """An empty file is a mistake (a truncated copy, the wrong file), not a request for the
    243-trial experiment, which leaving out --spec gives."""
    with pytest.raises(ConfigError, match="the sweep spec is empty"):
        LoadSweepSpec(write_yaml(tmp_path, ""))


@pytest.mark.parametrize("text, field, words", [
    ("colour: red\n", "colour", "unknown field"),
    ("grid: []\n", "grid", "empty"),
    ("grid: {normal_offsets_m: [], stroke_offsets_m: [0.0]}\n",
     "grid.normal_offsets_m", "empty"),
    ("grid: {normal_offsets_m: [0.0]}\n", "grid.stroke_offsets_m", "missing"),
    ("grid: [[0, 0], [0, 0]]\n", "grid", "twice"),
    ("grid: [[0, 0, 0]]\n", "grid", "pair"),
    ("grid: 3\n", "grid", "expected"),
    ("objects: [box, teapot]\n", "objects", "unknown object 'teapot'"),
    ("objects: []\n", "objects", "empty"),
    ("objects: box\n", "objects", "list of names"),
    ("controllers: [memorized, pid]\n", "controllers", "unknown controller 'pid'"),
    ("attempts: three\n", "attempts", "integer"),
    ("attempts: true\n", "attempts", "integer"),
    ("attempts: 0\n", "attempts", "positive"),
    ("base_seed: -1\n", "base_seed", "must lie in [0, 4294967295]"),
    ("randomisation: {mass_scale_bound: 1.5}\n", "randomisation.mass_scale_bound", "[0, 1)"),
    ("randomisation: {sensor_noise: 1}\n", "randomisation.sensor_noise", "true or false"),
    ("randomisation: {wobble: 1}\n", "randomisation.wobble", "unknown field"),
    ("user_objects: {box: {shape: box, size: [0.1, 0.1, 0.1], mass: 1}}\n",
     "user_objects.box", "built-in"),
    ("user_objects: {cup: {shape: cone, size: [0.1], mass: 1}}\n",
     "user_objects.cup.shape", "unknown shape"),
    ("user_objects: {cup: {shape: box, size: [0.1, 0.1], mass: 1}}\n",
     "user_objects.cup.size", "3 positive sizes"),
    ("user_objects: {cup: {shape: box, size: [0.04, 0.04, 0.1]}}\n",
     "user_objects.cup.mass", "missing"),
    ("user_objects: {'a.b': {shape: box, size: [0.1, 0.1, 0.1], mass: 1}}\n",
     "user_objects.a.b", "must be letters, digits"),
    ("user_objects: {cup: {shape: box, size_m: [0.1, 0.1, 0.1], mass: 1}}\n",
     "user_objects.cup.size_m", "rename size_m to size, mass_kg to mass"),
    ("user_objects: {cup: {shape: box, file: cup.sdf}}\n",
     "user_objects.cup.file", "unknown field"),
    ("scenario_overrides: [controller.memorized_corrective.events]\n",
     "scenario_overrides[0]", "key=value"),
    ("scenario_overrides: ['object.name=thin_cylinder']\n",
     "scenario_overrides[0]", "set per trial"),
    ("scenario_overrides: ['controller.name=heuristic']\n",
     "scenario_overrides[0]", "set per trial"),
    ("scenario_overrides: ['placement.offset=[0.0, 0.01]']\n",
     "scenario_overrides[0]", "set per trial"),
    ("scenario_overrides: ['controller.memorized_corrective.events=[hold_smash]']\n",
     "scenario_overrides[0]", "hold_smash"),
    ("scenario_overrides: ['controller.wobble=1']\n", "scenario_overrides[0]", "wobble"),
])
def test_invalid_yaml_names_file_and_field(tmp_path, text, field, words):
    path = write_yaml(tmp_path, text)
    with pytest.raises(ConfigError) as error:
        LoadSweepSpec(path)
    message = str(error.value)
    assert str(path) in message
    assert f"field '{field}'" in message
    assert words in message


def test_invalid_yaml_syntax_and_missing_file(tmp_path):
    with pytest.raises(ConfigError, match="not valid YAML"):
        LoadSweepSpec(write_yaml(tmp_path, "objects: [box\n"))
    with pytest.raises(ConfigError, match="cannot read"):
        LoadSweepSpec(tmp_path / "missing.yaml")


def test_a_registry_can_narrow_the_known_names():
    with pytest.raises(ConfigError, match="unknown controller 'heuristic'"):
        expand_trials(SweepSpec(), controllers=("memorized", "open_loop"))


def test_the_example_spec_file_loads_and_expands():
    path = Path(__file__).resolve().parents[2] / "analysis" / "example_sweep.yaml"
    spec = LoadSweepSpec(path)
    trials = expand_trials(spec)
    assert len(trials) == 3 * 4 * 15 * 3
    assert sum(t.well_placed for t in trials) == 3 * 4 * 3
    mug = ObjectConfig(name="mug", shape="cylinder", size=[0.04, 0.1], mass=0.3, friction=0.8)
    assert all(t.object_definition == mug for t in trials if t.object_name == "mug")


def test_the_randomised_cluster_spec_holds_1050_trials_of_distinct_seeds_and_yaws():
    path = Path(__file__).resolve().parents[2] / "analysis" / "randomised_sweep_1050.yaml"
    trials = expand_trials(LoadSweepSpec(path))
    assert len(trials) == 3 * 35 * 10
    assert len({t.seed for t in trials}) == len(trials)
    yaws = [abs(t.perturbation.yaw_rad) for t in trials]
    assert max(yaws) <= math.radians(10.0) and len(set(yaws)) == len(trials)


def test_scenario_overrides_reach_every_trial_and_survive_a_round_trip(tmp_path):
    """A spec's scenario_overrides (`--set` assignments) go with every trial, so a record
    says which settings made it."""
    path = write_yaml(tmp_path, "objects: [box]\ncontrollers: [memorized, heuristic]\n"
                      "attempts: 1\nscenario_overrides:\n"
                      "  - controller.memorized_corrective.events=[hold_avoid]\n")
    spec = LoadSweepSpec(path)
    assert spec.scenario_overrides == ("controller.memorized_corrective.events=[hold_avoid]",)
    trials = expand_trials(spec)
    assert len(trials) == 18
    for trial in trials:
        d = trial.to_dict()
        assert d["scenario_overrides"] == list(spec.scenario_overrides)
        assert TrialSpec.from_dict(d) == trial


def test_a_sweep_without_overrides_writes_the_trial_dicts_it_always_wrote():
    """No scenario_overrides: the trial dict has no such key, so a results folder made
    before the field existed still resumes (the runner compares trial dicts)."""
    trial = expand_trials(SweepSpec(objects=("box",), attempts=1))[0]
    d = trial.to_dict()
    assert "scenario_overrides" not in d
    assert TrialSpec.from_dict(d) == trial


def test_the_wide_grid_spec_covers_its_ranges_with_the_objects_its_events_are_recorded_for():
    """analysis/wide_grid.yaml: +-25 mm along the stroke, +-15 mm normal, yaw drawn within
    +-10 deg; its own objects' pad pairs, as drawn, span 0.30-0.80 and their masses stay at
    or below 0.30 kg; each own object is the one of the same name in
    analysis/wide_grid_objects.yaml, the scenario file its events are recorded from."""
    from tegrasp_drake.rig import materials
    from tegrasp_drake.rig.objects import BUILTIN_OBJECTS, object_description
    from tegrasp_drake.scenario.scenario import LoadScenario
    analysis = Path(__file__).resolve().parents[2] / "analysis"
    spec = LoadSweepSpec(analysis / "wide_grid.yaml")
    assert {dy for _, dy in spec.grid} >= {-0.025, 0.025}
    assert {dx for dx, _ in spec.grid} >= {-0.015, 0.015}
    assert spec.randomisation.placement_yaw_bound_deg == 10.0
    assert set(spec.objects) == set(BUILTIN_OBJECTS) | set(spec.user_objects)
    assert len(spec.user_objects) >= 4
    assert {o.shape for o in spec.user_objects.values()} == {"box", "cylinder"}
    b_mu, b_m = (spec.randomisation.friction_scale_bound,
                 spec.randomisation.mass_scale_bound)
    pairs = [materials.pair_friction(materials.PAD_COVER, o.friction * (1 + s * b_mu))
             for o in spec.user_objects.values() for s in (-1, 1)]
    assert 0.30 <= min(pairs) < 0.31 and 0.79 < max(pairs) <= 0.80
    assert 0.29 < max(o.mass * (1 + b_m) for o in spec.user_objects.values()) <= 0.30
    for name, config in spec.user_objects.items():
        recorded = LoadScenario(analysis / "wide_grid_objects.yaml", name).object
        assert recorded.name == name
        assert object_description(recorded) == object_description(config), name
    assert len(expand_trials(spec)) == 7 * 15 * 2 * 3
