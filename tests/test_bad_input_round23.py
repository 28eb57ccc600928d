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
