"""The public API at the package's top: every name resolves, is documented, and importing
the package alone does not load pydrake."""

import subprocess
import sys

import tegrasp_drake


def test_every_public_name_resolves_to_a_documented_object():
    for name in tegrasp_drake.__all__:
        value = getattr(tegrasp_drake, name)
        if callable(value):
            assert value.__doc__ and value.__doc__.strip(), f"{name} has no docstring"


def test_builders_follow_drakes_camel_case():
    builders = [n for n in tegrasp_drake.__all__ if n.startswith(("Make", "Load", "Add"))]
    assert {"LoadScenario", "MakeGraspStation", "MakeHardwareStation",
            "MakeGraspDiagram"} <= set(builders)
    # Data loaders (memorized events, trial logs) stay snake_case; builders do not.
    assert not [n for n in tegrasp_drake.__all__ if n.startswith(("make_", "build_", "add_"))]


def test_an_unknown_name_is_an_attribute_error():
    try:
        tegrasp_drake.NoSuchThing  # noqa: B018
    except AttributeError as e:
        assert "NoSuchThing" in str(e)
    else:
        raise AssertionError("expected AttributeError")


def test_importing_the_package_does_not_load_pydrake():
    code = "import sys, tegrasp_drake; print('pydrake' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "False"
