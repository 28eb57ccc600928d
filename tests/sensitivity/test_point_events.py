"""A sensitivity point records the events each of its controllers reads in its own world:
the taxel_aware controller's ensemble included, not the package's default-world ensemble.
The recordings are stand-ins (the package's events relabelled with the scenario they were
asked to record in), so nothing is simulated."""

import dataclasses
import json
import textwrap

from tegrasp_drake.events import load_memorized_events
from tegrasp_drake.recording import ensemble_events, paper_events
from tegrasp_drake.recording.ensemble_events import ENSEMBLE_FOLDER
from tegrasp_drake.rig import paths
from tegrasp_drake.scenario.scenario import scenario_to_yaml
from tegrasp_drake.sensitivity.study import LoadSensitivitySpec, one_at_a_time, run_sensitivity
from tegrasp_drake.transfer.matrix import cell_name
from tests.fake_trials import fake_trial_reading_events

SPEC = """\
    parameters: [tactile.pad_modulus_pa]
    events: each_point
    sweep:
      objects: [box]
      controllers: [memorized, taxel_aware]
      grid: [[0.0, 0.0]]
      attempts: 1
      base_seed: 600
    """


def _relabelled(folder, object_name, scenario) -> dict:
    """The package's events of `object_name` in `folder`, as if recorded in `scenario`."""
    return {transition: dataclasses.replace(event, scenario=scenario_to_yaml(scenario))
            for transition, event in load_memorized_events(folder, object_name).items()}


def test_a_point_with_taxel_aware_reads_the_ensemble_recorded_in_its_own_world(
        tmp_path, monkeypatch):
    recorded = []

    def record_events(object_name, scenario, **_):
        recorded.append(("paper", scenario.tactile.pad_modulus_pa))
        return _relabelled(paths.package_events_dir(), object_name, scenario)

    def record_object_ensemble(object_name, scenario, runs, **_):
        recorded.append(("ensemble", scenario.tactile.pad_modulus_pa))
        return _relabelled(paths.package_events_dir() / ENSEMBLE_FOLDER, object_name,
                           scenario)

    monkeypatch.setattr(paper_events, "record_events", record_events)
    monkeypatch.setattr(ensemble_events, "record_object_ensemble", record_object_ensemble)
    spec_file = tmp_path / "sensitivity.yaml"
    spec_file.write_text(textwrap.dedent(SPEC))
    spec = LoadSensitivitySpec(spec_file)
    points = one_at_a_time(spec)
    moduli = {point.name: dict(point.values).get("tactile.pad_modulus_pa", 2.0e6)
              for point in points}
    assert sorted(moduli.values()) == [5.0e5, 2.0e6, 4.0e6]
    out = tmp_path / "out"
    run_sensitivity(spec, points, fake_trial_reading_events, out, workers=1, progress=False)
    assert sorted(recorded) == sorted((kind, m) for kind in ("paper", "ensemble")
                                      for m in moduli.values())
    results = {}
    for path in (out / "cells").glob("*/trials/*.json"):
        record = json.loads(path.read_text())
        results[(path.parts[-3], record["trial"]["controller"])] = \
            record["result"]["events_pad_modulus_pa"]
    assert len(results) == 2 * len(points)
    for point, modulus in moduli.items():
        for controller in ("memorized", "taxel_aware"):
            assert results[(cell_name(point, point), controller)] == [modulus], \
                (point, controller)
