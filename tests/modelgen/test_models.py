import re

import numpy as np
from pydrake.multibody.plant import MultibodyPlant

from tegrasp_drake.rig import paths
from tegrasp_drake.rig.arm_kinematics import make_arm_control_plant
from tegrasp_drake.modelgen import jaco2_dh
from tegrasp_drake.modelgen.__main__ import GENERATED


NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def _text_and_numbers(sdf: str) -> tuple[list[str], np.ndarray]:
    """The SDF text with its numbers cut out, and the numbers."""
    return NUMBER.split(sdf), np.array([float(x) for x in NUMBER.findall(sdf)])


def test_committed_models_equal_their_generators():
    # Numbers are compared to 1e-9 relative (1e-12 absolute): the generators' floating-point
    # results may differ in the last digits between CPUs and libm versions.
    for relative, make in GENERATED.items():
        committed_text, committed = _text_and_numbers((paths.models_dir() / relative).read_text())
        generated_text, generated = _text_and_numbers(make())
        assert committed_text == generated_text, relative
        np.testing.assert_allclose(committed, generated, rtol=1e-9, atol=1e-12, err_msg=relative)


def test_arm_model_matches_kinovas_dh_forward_kinematics():
    plant = make_arm_control_plant()
    context = plant.CreateDefaultContext()
    rng = np.random.default_rng(3)
    for _ in range(5):
        q = rng.uniform(1.0, 5.0, 6)
        plant.SetPositions(context, q)
        X = plant.GetFrameByName("flange").CalcPoseInWorld(context).GetAsMatrix4()
        np.testing.assert_allclose(X, jaco2_dh.forward_kinematics(q), atol=1e-6)


def test_gripper_fingers_are_coupled_and_singly_actuated():
    plant = MultibodyPlant(1e-3)
    paths.make_parser(plant).AddModels(url="package://tegrasp/robotiq_2f85/robotiq_2f85_tactile.sdf")
    plant.Finalize()
    assert plant.num_actuators() == 1 and plant.num_constraints() == 1
