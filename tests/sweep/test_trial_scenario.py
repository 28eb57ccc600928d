"""The Scenario of a sweep trial (sweep/trial_function.py, scenario_from_trial_spec): what each
of the sweep's trials runs, built and validated without simulating."""

import dataclasses

import pytest

from tegrasp_drake.scenario.scenario import LoadScenario, validate
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
from tegrasp_drake.scenario.trial_result import TrialResult
from tegrasp_drake.sweep.trial_function import scenario_from_trial_spec
from tegrasp_drake.rig.typed_yaml import ConfigError


def _first_trial(**spec_fields) -> dict:
    return expand_trials(SweepSpec(**spec_fields))[0].to_dict()


@pytest.mark.parametrize("name", ["box", "thick_cylinder", "thin_cylinder"])
def test_a_built_in_objects_trial_is_that_object_with_its_perturbed_mass_and_friction(name):
    """Regression: the sweep built the built-in object with its shape filled in, which the
    validation then refused as "your own object ... needs its own name" in every trial."""
    trial = _first_trial(objects=(name,), controllers=("memorized",), grid=((0.0, 0.0),))
    scenario = scenario_from_trial_spec(trial)
    nominal = scenario_from_trial_spec(trial, nominal=True)
    p = trial["perturbation"]
    assert scenario.object.name == nominal.object.name == name
    assert scenario.object.shape == nominal.object.shape != ""
    assert scenario.object.size == nominal.object.size
    assert scenario.object.mass == pytest.approx(nominal.object.mass * p["mass_scale"])
    assert scenario.object.friction == pytest.approx(
        nominal.object.friction * p["friction_scale"])
    assert scenario.placement.offset == pytest.approx([trial["marker_dx_m"] + p["dx_m"],
                                                       trial["marker_dy_m"] + p["dy_m"]])
    assert scenario.controller.name == "memorized"
    assert scenario.random_seed == trial["seed"]


def test_a_sweeps_scenario_overrides_set_the_trials_controller_settings():
    """`--set` assignments of the sweep (scenario_overrides) apply to every trial's
    scenario, under the trial's own object, placement, seed and controller."""
    overrides = ("controller.memorized_corrective.events=[hold_avoid]",
                 "controller.taxel_aware.finger_strike.enabled=false")
    trial = _first_trial(objects=("box",), controllers=("taxel_aware",),
                         grid=((0.01, 0.0),), scenario_overrides=overrides)
    scenario = scenario_from_trial_spec(trial)
    assert scenario.controller.memorized_corrective.events == ["hold_avoid"]
    assert not scenario.controller.taxel_aware.finger_strike.enabled
    assert scenario.controller.name == "taxel_aware"
    assert scenario.random_seed == trial["seed"]
    assert scenario.placement.offset[0] == pytest.approx(0.01 + trial["perturbation"]["dx_m"])
    plain = scenario_from_trial_spec(_first_trial(objects=("box",),
                                                  controllers=("taxel_aware",),
                                                  grid=((0.01, 0.0),)))
    assert plain.controller.memorized_corrective.events == []
    assert plain.controller.taxel_aware.finger_strike.enabled


def test_validating_a_loaded_scenario_again_changes_nothing():
    """A script may change a loaded scenario and validate it again; the built-in object
    (now with its shape filled in) stays the built-in, and an own object must still be
    named."""
    scenario = LoadScenario()
    assert validate(scenario) == scenario
    heavier = dataclasses.replace(scenario, object=dataclasses.replace(scenario.object,
                                                                       mass=0.3))
    assert validate(heavier).object.mass == 0.3
    cylinder = dataclasses.replace(scenario, object=dataclasses.replace(
        scenario.object, shape="cylinder", size=[0.04, 0.1]))
    with pytest.raises(ConfigError, match="needs its own name"):
        validate(cylinder)


def test_a_sweep_trial_with_memorized_corrective_triggers_gets_their_events(monkeypatch):
    """run_trial_from_spec loads the corrective events the overrides name (the box's
    are in the package) and hands them to the trial; an object without recorded
    corrective events stops with the recording hint instead of running the heuristic."""
    from tegrasp_drake.events import MemorizedEventError
    from tegrasp_drake.sweep import trial_function as trial_module
    handed = {}

    def capture(scenario, *, events=None, corrective_events=None):
        handed.update(events=events, corrective_events=corrective_events)
        return TrialResult(hold_success=True)

    monkeypatch.setattr(trial_module, "run_trial", capture)
    overrides = ("controller.memorized_corrective.events=[hold_avoid]",)
    box = _first_trial(objects=("box",), controllers=("memorized",), grid=((0.0, 0.0),),
                       scenario_overrides=overrides)
    assert trial_module.run_trial_from_spec(box)["hold_success"] is True
    assert set(handed["corrective_events"]) >= {"hold_avoid"}
    assert handed["events"] is not None
    plain = _first_trial(objects=("box",), controllers=("open_loop",), grid=((0.0, 0.0),))
    trial_module.run_trial_from_spec(plain)
    assert handed == {"events": None, "corrective_events": None}
    thick = _first_trial(objects=("thick_cylinder",), controllers=("heuristic",),
                         grid=((0.0, 0.0),), scenario_overrides=overrides)
    with pytest.raises(MemorizedEventError, match="record_corrective_events"):
        trial_module.run_trial_from_spec(thick)
    # The open loop matches no corrective event: the sweep's setting is not its own.
    scripted = _first_trial(objects=("thick_cylinder",), controllers=("open_loop",),
                            grid=((0.0, 0.0),), scenario_overrides=overrides)
    trial_module.run_trial_from_spec(scripted)
    assert handed == {"events": None, "corrective_events": None}
