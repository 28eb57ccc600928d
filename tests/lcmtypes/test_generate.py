"""The committed LCM types are what generate.sh makes from the .lcm files (lcm-gen, pinned)."""

import pathlib
import shutil
import subprocess
import sys

PACKAGE = pathlib.Path(__file__).resolve().parents[2] / "tegrasp_drake" / "lcmtypes"


def test_generate_reproduces_the_committed_types(tmp_path):
    copy = tmp_path / "lcmtypes"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
    bin_dir = pathlib.Path(sys.executable).parent
    env = {"PATH": f"{bin_dir}:/usr/bin:/bin"}
    subprocess.run(["sh", str(copy / "generate.sh")], check=True, env=env)
    committed = sorted(path.name for path in PACKAGE.glob("*.py"))
    assert sorted(path.name for path in copy.glob("*.py")) == committed
    for name in committed:
        assert (copy / name).read_text() == (PACKAGE / name).read_text(), name
