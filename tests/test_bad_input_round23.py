"""Bad inputs the fourteenth review found, one test per rule."""

import tracemalloc

import pytest

from tegrasp_drake.commands import emulate


# Rule: a file is read with a bound before its end: --write-config looks at the first line
# of the file it would replace, and reads no more of it (a sparse 200 MB file here).
def test_write_config_reads_only_the_first_line_of_the_file_it_would_replace(tmp_path):
    big = tmp_path / "big.yaml"
    with open(big, "wb") as f:
        f.truncate(200_000_000)
    tracemalloc.start()
    try:
        with pytest.raises(SystemExit, match="was not written by `tegrasp emulate`"):
            emulate._check_config_target(big)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 10_000_000, f"{peak} bytes allocated to check a 200 MB file's first line"


# Rule: an events folder missing a file a trial needs is bad input (exit 1, one line naming
# the file), as a missing --events folder is; exit 2 is kept for a refused sweep spec.
def test_a_sweep_events_folder_missing_a_file_exits_1(tmp_path, capfd):
    import shutil
    from tegrasp_drake.rig import paths
    from tests.test_bad_input import run_cli
    events = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), events)
    (events / "box" / "load_lift.json").unlink()
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", "memorized",
                          "--base-seed", "640", "--attempts", "1", "--workers", "1",
                          "--out", str(tmp_path / "sw"), "--events", str(events)], capfd)
    assert code == 1, text
    assert "load_lift.json" in text and len(text.strip().splitlines()) == 1, text
    assert "Traceback" not in text and not (tmp_path / "sw").exists(), text
