"""The analysis scripts regenerate a results folder's reports from its records."""

import pytest

from tegrasp_drake.reports import write_reports
from tegrasp_drake.sweep import SweepSpec, run_sweep
from tests.fake_trials import fake_trial
from tests.analysis_script import load_analysis_script


def load_script(name):
    return load_analysis_script(name)


def test_scripts_regenerate_the_reports(tmp_path):
    run_sweep(SweepSpec(objects=("box", "thin_cylinder"), attempts=1), fake_trial, tmp_path,
              workers=2, progress=False)
    write_reports(tmp_path)
    names = ("table1.md", "table1.csv", "statistics.md", "statistics.json",
             "success_by_offset.md", "success_by_offset.csv")
    expected = {name: (tmp_path / name).read_bytes() for name in names}
    for name in names + ("success_maps.png",):
        (tmp_path / name).unlink()

    assert load_script("make_table1").main([str(tmp_path)]) == 0
    assert load_script("make_success_maps").main([str(tmp_path)]) == 0
    assert {name: (tmp_path / name).read_bytes() for name in names} == expected
    assert (tmp_path / "success_maps.png").stat().st_size > 10_000


def test_scripts_refuse_an_empty_folder(tmp_path):
    # main's refusal is the one line the error boundary (script_output.run_script) prints
    for script in ("make_table1", "make_success_maps"):
        with pytest.raises(SystemExit, match=f"{script}: error: no (finished )?trial records"):
            load_script(script).main([str(tmp_path)])
