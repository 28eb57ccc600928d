"""`tegrasp plot`: every figure of the sweep (Table I against the paper, latency
distributions, success maps) from the committed results, Fig. 5c from the package's events,
in each format; and one-line errors for bad input."""

import pathlib

import numpy as np
import pytest
from matplotlib.image import imread

from tegrasp_drake.cli import main
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.runs.trial import run_trial

RESULTS = pathlib.Path(__file__).resolve().parents[2] / "analysis" / "results_seed0"


def _is_figure(path: pathlib.Path) -> bool:
    data = path.read_bytes()
    if path.suffix == ".png":
        image = imread(path)
        return min(image.shape[:2]) > 600 and np.ptp(image[..., :3]) > 0.5
    if path.suffix == ".pdf":
        return data.startswith(b"%PDF") and len(data) > 10_000
    return b"<svg" in data[:1000] and len(data) > 10_000


@pytest.mark.parametrize("what, source, name", [
    ("table1", RESULTS, "table1_vs_paper.png"),
    ("latency", RESULTS, "latency.pdf"),
    ("success-maps", RESULTS, "success_maps.svg"),
    ("events", None, "memorized_events.png"),
])
def test_plot_writes_the_figure(what, source, name, tmp_path, capsys):
    out = tmp_path / name
    assert main(["plot", what] + ([str(source)] if source else []) + ["--out", str(out)]) == 0
    assert capsys.readouterr().out.strip() == str(out)
    assert _is_figure(out)


def test_plot_format_names_the_default_file(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["plot", "table1", str(RESULTS), "--format", "svg"]) == 0
    assert _is_figure(tmp_path / "out" / "table1_vs_paper.svg")


@pytest.mark.parametrize("arguments, message", [
    (["table1", str(RESULTS), "--out", "figure.jpg"], "must end in one of .png, .pdf, .svg"),
    (["table1", str(RESULTS), "--out", "figure.png", "--format", "pdf"],
     "is a .png file but --format is pdf"),
    (["latency", "no/such/folder"], "no trial records under no/such/folder/trials"),
])
def test_bad_input_is_one_line(arguments, message, capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["plot"] + arguments)
    assert message in str(exit_info.value)
    assert "\n" not in str(exit_info.value)


@pytest.mark.parametrize("what, needed", [
    ("table1", "a sweep's results folder"), ("latency", "a sweep's results folder"),
    ("signals", "a trial log"), ("trial", "a trial log"), ("avoid", "a trial log"),
])
def test_a_missing_log_or_results_is_a_usage_error(what, needed, capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["plot", what])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith(f"tegrasp: error: `tegrasp plot {what}` needs LOG|RESULTS, {needed}")
    assert err.endswith("(see tegrasp plot --help)\n") and err.count("\n") == 1


def test_avoid_on_a_trial_without_a_hit_names_the_scenario_that_has_one(tmp_path):
    log = run_trial(LoadScenario(), max_time=1.0).log.save(tmp_path / "trial.npz")
    with pytest.raises(SystemExit) as exit_info:
        main(["plot", "avoid", str(log), "--out", str(tmp_path / "avoid.png")])
    assert "no Avoid transition" in str(exit_info.value)
    assert "box_hit_in_hold" in str(exit_info.value)
    assert not (tmp_path / "avoid.png").exists()


# Rule: `tegrasp plot events` draws one line per object in each panel, so a figure holds at
# most MAX_LINES_TOLD_APART objects: a folder with more is refused in one line listing them
# and saying to pick some with --object NAME, never drawn unreadable (with a matplotlib
# warning); --object picks the objects plotted.
def _many_objects_events(folder: pathlib.Path, count: int) -> None:
    import dataclasses

    from tegrasp_drake.events.events_folder import load_memorized_events, save_memorized_events
    from tegrasp_drake.rig.paths import package_events_dir
    box = load_memorized_events(package_events_dir(), "box")
    for k in range(count):
        save_memorized_events(folder, [dataclasses.replace(
            event, object_name=f"obj{k:02d}",
            scenario=event.scenario.replace("name: box", f"name: obj{k:02d}"))
            for event in box.values()])


def test_plot_events_of_more_objects_than_a_figure_tells_apart_is_refused(tmp_path, capfd):
    import warnings

    from tegrasp_drake.figures.figure_files import MAX_LINES_TOLD_APART
    from tests.bad_input.probes import assert_one_line_error, run_cli
    _many_objects_events(tmp_path / "events", MAX_LINES_TOLD_APART + 1)
    out = tmp_path / "events.png"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        code, text = run_cli(["plot", "events", "--events", str(tmp_path / "events"),
                              "--out", str(out)], capfd)
    assert_one_line_error(code, text, f"memorized events of {MAX_LINES_TOLD_APART + 1} objects",
                          "obj00", "--object NAME")
    assert not out.exists()
    assert main(["plot", "events", "--events", str(tmp_path / "events"), "--out", str(out),
                 "--object", "obj03", "--object", "obj07"]) == 0
    assert _is_figure(out)
