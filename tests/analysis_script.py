"""The scripts of analysis/ as modules, for the tests that call their functions (they are
scripts, not a package: loaded from their files)."""

import importlib.util
import pathlib

ANALYSIS = pathlib.Path(__file__).resolve().parents[1] / "analysis"


def load_analysis_script(name: str):
    """analysis/`name`.py, executed as a module named `name`."""
    spec = importlib.util.spec_from_file_location(name, ANALYSIS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
