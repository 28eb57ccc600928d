"""The README's "From Python" examples run as written: each Python block of that section is
saved as a script and run in a fresh interpreter, in an empty folder (TMPDIR inside it)."""

import os
import pathlib
import re
import subprocess
import sys

import pytest

import tegrasp_drake

README = pathlib.Path(__file__).resolve().parent.parent / "README.md"
SECTION = "## From Python"


def python_blocks() -> list[str]:
    text = README.read_text(encoding="utf-8")
    start = text.index(SECTION)
    end = text.index("\n## ", start + len(SECTION))
    return re.findall(r"```python\n(.*?)```", text[start:end], re.DOTALL)


def run_script(code: str, folder: pathlib.Path) -> str:
    script = folder / "example.py"
    script.write_text(code, encoding="utf-8")
    temporary = folder / "tmp"
    temporary.mkdir()
    # The child imports this same tegrasp_drake, from whatever folder it runs in.
    package_parent = str(pathlib.Path(tegrasp_drake.__file__).resolve().parent.parent)
    python_path = os.pathsep.join(filter(None, [package_parent, os.environ.get("PYTHONPATH")]))
    done = subprocess.run([sys.executable, str(script)], cwd=folder, capture_output=True,
                          text=True, timeout=900,
                          env=dict(os.environ, TMPDIR=str(temporary), PYTHONPATH=python_path))
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def test_the_section_has_the_two_examples():
    blocks = python_blocks()
    assert len(blocks) == 2
    assert "DiagramBuilder" in blocks[0] and "run_sweep" in blocks[1]


@pytest.mark.slow
def test_the_diagram_builder_example_runs(tmp_path):
    out = run_script(python_blocks()[0], tmp_path)
    for step in ("Reach -> Load", "Load -> Lift", "Place -> Unload", "Unload -> Done"):
        assert step in out, out
    assert "samples of SA and RA" in out


@pytest.mark.slow
def test_the_sweep_example_runs(tmp_path):
    out = run_script(python_blocks()[1], tmp_path)
    assert "2 trials ran, 0 raised" in out, out
    assert "| controller |" in out and "memorized triggers" in out
    assert len(re.findall(r"^memorized/box/m00/a\d hold (True|False)", out, re.MULTILINE)) == 2
    # The sweep's folder: under TMPDIR, with both trials' records and the reports.
    (sweep,) = (tmp_path / "tmp").glob("sweep-*")
    assert len(list((sweep / "trials").glob("*.json"))) == 2
    assert (sweep / "summary.md").is_file() and (sweep / "table1.md").is_file()
