"""The committed events/ are record-events' output; recorded events go to the user's folder
and carry their object."""

import hashlib

import numpy as np
import pytest

from tegrasp_drake import cli
from tegrasp_drake.scenario.scenario_events import load_controller_events
from tegrasp_drake.events.events_folder import events_folder_of
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.rig import paths
from tegrasp_drake.recording.paper_events import events_of_ideal_grasp
from tegrasp_drake.events import load_memorized_events
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS, object_description
from tests.cheap_contact import cheap_contact_arguments

pytestmark = pytest.mark.slow


@pytest.mark.parametrize("object_name", sorted(BUILTIN_OBJECTS))
def test_rerunning_record_events_reproduces_the_committed_files(object_name, ideal_grasp_log):
    """record_events is the ideal grasp (the session's shared run of it) and the cut."""
    committed = load_memorized_events(paths.package_events_dir(), object_name)
    recorded = events_of_ideal_grasp(ideal_grasp_log(object_name),
                                     LoadScenario(name=object_name), object_name)
    assert set(recorded) == set(committed)
    for transition, event in recorded.items():
        np.testing.assert_allclose(event.sa, committed[transition].sa, rtol=0, atol=1e-12)
        np.testing.assert_allclose(event.ra, committed[transition].ra, rtol=0, atol=1e-12)
        assert event.object_description == committed[transition].object_description
        assert event.object_description == object_description(
            LoadScenario(name=object_name).object)


def _folder_digest(folder) -> str:
    digest = hashlib.sha256()
    for path in sorted(folder.rglob("*.json")):
        digest.update(str(path.relative_to(folder)).encode() + path.read_bytes())
    return digest.hexdigest()


def test_record_events_writes_the_users_folder_and_the_controller_reads_it_first(
        empty_user_events_folder, capsys):
    package = paths.package_events_dir()
    before = _folder_digest(package)
    # The cheap contact: the claim is where the recorded files go and which folder the
    # controller reads, not what they hold.
    assert cli.main(["record-events", "--object", "thin_cylinder",
                     *cheap_contact_arguments()]) == 0
    assert str(empty_user_events_folder) in capsys.readouterr().out
    assert _folder_digest(package) == before  # the package's events are read-only
    assert (empty_user_events_folder / "thin_cylinder" / "reach_load.json").is_file()
    scenario = LoadScenario(name="thin_cylinder")
    assert events_folder_of(paths.events_search_path(), "thin_cylinder") == (
        empty_user_events_folder)
    assert events_folder_of(paths.events_search_path(), "box") == package
    assert set(load_controller_events(scenario)) == {"reach_load", "load_lift",
                                                      "place_unload"}


def test_an_object_whose_taxels_never_see_the_commanded_grip_records_at_its_plateau(
        tmp_path, capsys):
    """A 22 mm cylinder of 0.25 kg reads 21.4 N of 22.5 N (90 % of the
    command) on the taxels (the pad does not cover all of its contact) although the grasp
    lifts it. Its grip is judged against its plateau, so the script's lift starts with the
    grip settled and record-events records it, Load-Lift at the start of the lift."""
    # The cheap contact: the claim is the recording's grip-settled rule against the taxels'
    # plateau (the pad's coverage of a thin rod), not how the held rod creeps.
    assert cli.main(["record-events", "--events", str(tmp_path),
                     "--set", "object.name=rod", "--set", "object.shape=cylinder",
                     "--set", "object.size=[0.022,0.12]", "--set", "object.mass=0.25",
                     "--set", "object.friction=0.5", *cheap_contact_arguments()]) == 0
    events = load_memorized_events(tmp_path, "rod")
    assert set(events) == {"reach_load", "load_lift", "place_unload"}
    contact = events["reach_load"].transition_time_s
    lift = events["load_lift"].transition_time_s
    assert contact < lift < contact + 1.0  # the Load phase's dwell after contact
