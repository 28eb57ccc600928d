"""The package's layers (pyproject.toml [tool.importlinter]) hold: no module imports a higher
layer, and only tests, commands and benchmarks import the emulators."""

import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_imports_respect_the_layers_in_pyproject():
    lint_imports = pathlib.Path(sys.executable).parent / "lint-imports"
    result = subprocess.run([str(lint_imports), "--config", str(ROOT / "pyproject.toml"),
                             "--no-cache"], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-2000:]


def test_every_sub_package_is_installed():
    """pyproject.toml lists the packages a non-editable `pip install .` copies: a
    sub-package missing there imports from a source checkout and fails once installed."""
    import pathlib
    import tomllib
    root = pathlib.Path(__file__).resolve().parents[1]
    listed = set(tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]
                 ["packages"])
    found = {".".join(init.parent.relative_to(root).parts)
             for init in (root / "tegrasp_drake").rglob("__init__.py")}
    assert found <= listed, sorted(found - listed)
