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


def test_tests_mirror_the_package():
    """A module's tests live in tests/<package>/test_<module>.py; tests/ itself keeps the
    checks that span packages, none named after one package, and tests/bad_input/ the
    bad-input checks, which span packages too (a file for each kind of input)."""
    packages = {init.parent.name for init in (ROOT / "tegrasp_drake").glob("*/__init__.py")}
    packages |= {"benchmarks", "bad_input"}
    misplaced = [test.name for test in (ROOT / "tests").glob("test_*.py")
                 if any(test.stem.startswith(f"test_{package}_") for package in packages)]
    assert misplaced == []
    for folder in (ROOT / "tests").iterdir():
        if folder.is_dir() and (folder / "__init__.py").exists():
            assert folder.name in packages, folder.name


def test_every_named_test_file_exists():
    """A test file named in the CI script, the docs or the code exists: CI runs some by path,
    and a moved test must not leave a path that runs nothing."""
    import re
    tracked = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True,
                             text=True).stdout.split()
    if not tracked:  # not a git checkout: the files under the checkout's top folders
        tracked = [str(path.relative_to(ROOT)) for top in (".ci", "docs", "tegrasp_drake",
                   "analysis", "benchmarks", "tests") for path in (ROOT / top).rglob("*")
                   if path.is_file()] + ["README.md", "pyproject.toml"]
    named = set()
    for name in tracked:
        path = ROOT / name
        if path.suffix not in {"", ".py", ".md", ".toml", ".sh", ".yaml"} or not path.is_file():
            continue
        named |= {(name, found) for found in
                  re.findall(r"tests/[A-Za-z0-9_/]+\.py", path.read_text(errors="replace"))}
    missing = sorted(f"{name} names {found}" for name, found in named
                     if not (ROOT / found).exists())
    assert missing == []


def test_every_package_docstring_maps_its_modules():
    """Each package's __init__ docstring names every module and sub-package it holds (the
    reader's map of the package)."""
    import ast
    unmapped = []
    for init in sorted((ROOT / "tegrasp_drake").rglob("__init__.py")):
        folder = init.parent
        doc = ast.get_docstring(ast.parse(init.read_text())) or ""
        held = {path.stem for path in folder.glob("*.py") if not path.stem.startswith("_")}
        held |= {path.name for path in folder.iterdir() if (path / "__init__.py").exists()}
        unmapped += [f"{folder.relative_to(ROOT)}: {name}" for name in sorted(held)
                     if name not in doc]
    assert unmapped == []
