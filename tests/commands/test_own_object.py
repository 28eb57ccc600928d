"""A user's own object with every controller: the documented
`tegrasp record-events --scenario FILE --scenario-name NAME` records what each controller
needs, then `tegrasp trial --controller taxel_aware` runs on that object."""

import json

import pytest

from tegrasp_drake import cli
from tests.cheap_contact import CHEAP_CONTACT_SECTIONS

# The cheap contact: the claim is the documented commands' plumbing on an own object (its
# events recorded, then read by taxel_aware), the same whichever contact both run in.
MY_SCENARIOS = """\
my_box:
  object: {name: my_box, shape: box, size: [0.050, 0.045, 0.100], mass: 0.14, friction: 0.45}
""" + "".join(f"  {section}: {json.dumps(fields)}\n"
              for section, fields in CHEAP_CONTACT_SECTIONS.items())


@pytest.mark.slow
def test_taxel_aware_runs_on_an_own_object_after_the_documented_record_events(
        tmp_path, monkeypatch, capsys, empty_user_events_folder):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "my.yaml").write_text(MY_SCENARIOS)
    assert cli.main(["record-events", "--scenario", "my.yaml",
                     "--scenario-name", "my_box"]) == 0
    assert "ensemble of 5 runs" in capsys.readouterr().out
    assert (empty_user_events_folder / "ensemble" / "my_box" / "reach_load.json").is_file()
    assert cli.main(["trial", "--scenario", "my.yaml", "--scenario-name", "my_box",
                     "--controller", "taxel_aware", "--json", "--out", "run"]) == 0
    result = json.loads((tmp_path / "run" / "result.json").read_text())
    assert result["transitions"], result
