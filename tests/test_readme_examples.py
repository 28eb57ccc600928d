"""The "From Python" examples of the README and of docs/ run as written: each Python block
of such a section is saved as a script and run in a fresh interpreter, in an empty folder
(TMPDIR inside it). No page holds a Python block elsewhere, so every one is run."""

import os
import pathlib
import re
import subprocess
import sys

import pytest

import tegrasp_drake

ROOT = pathlib.Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
SWEEPS = ROOT / "docs" / "sweeps.md"
SECTION = "## From Python"
PYTHON_BLOCK = re.compile(r"```python\n(.*?)```", re.DOTALL)


def pages() -> list[pathlib.Path]:
    return [README, *sorted((ROOT / "docs").glob("*.md"))]


def python_blocks(page: pathlib.Path = README) -> list[str]:
    """The Python blocks of `page`'s "From Python" section (none without one)."""
    text = page.read_text(encoding="utf-8")
    if SECTION not in text:
        return []
    start = text.index(SECTION)
    end = text.find("\n## ", start + len(SECTION))
    return PYTHON_BLOCK.findall(text[start:end if end >= 0 else len(text)])


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


def test_the_readme_and_the_sweeps_page_have_their_examples():
    (diagram,) = python_blocks(README)
    (sweep,) = python_blocks(SWEEPS)
    assert "DiagramBuilder" in diagram and "run_sweep" in sweep


def test_every_python_block_of_the_pages_is_one_that_runs():
    for page in pages():
        every = PYTHON_BLOCK.findall(page.read_text(encoding="utf-8"))
        assert every == python_blocks(page), f"{page.name}: a Python block outside {SECTION}"
    assert sum(len(python_blocks(page)) for page in pages()) == 2  # the two run below


@pytest.mark.slow
def test_the_diagram_builder_example_runs(tmp_path):
    out = run_script(python_blocks(README)[0], tmp_path)
    for step in ("Reach -> Load", "Load -> Lift", "Place -> Unload", "Unload -> Done"):
        assert step in out, out
    assert "samples of SA and RA" in out


@pytest.mark.slow
def test_the_sweep_example_runs(tmp_path):
    out = run_script(python_blocks(SWEEPS)[0], tmp_path)
    assert "2 trials ran, 0 raised" in out, out
    assert "| controller |" in out and "memorized triggers" in out
    assert len(re.findall(r"^memorized/box/m00/a\d hold (True|False)", out, re.MULTILINE)) == 2
    # The sweep's folder: under TMPDIR, with both trials' records and the reports.
    (sweep,) = (tmp_path / "tmp").glob("sweep-*")
    assert len(list((sweep / "trials").glob("*.json"))) == 2
    assert (sweep / "summary.md").is_file() and (sweep / "table1.md").is_file()
