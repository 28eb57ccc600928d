"""The JACO2 emulator (a Drake simulation on LCM) driven through the hardware-side Jaco
driver, both in one Simulator on memq:// LCM."""

import numpy as np
import pytest
from pydrake.lcm import DrakeLcm
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource

from tegrasp_drake.emulators.jaco_arm_emulator import MakeJacoArmEmulator
from tegrasp_drake.hardware.jaco.jaco_lcm_interface import AddJacoLcmDriver

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling

Q0 = np.array([3.3, 4.5, 1.1, 2.5, 2.3, 3.9])
GOAL = Q0 + np.array([0.1, -0.1, 0.05, 0.2, -0.2, 0.1])


def build(stop: float):
    lcm = DrakeLcm("memq://")
    builder = DiagramBuilder()
    arm = builder.AddSystem(MakeJacoArmEmulator(lcm=lcm, initial_positions=Q0))
    driver = AddJacoLcmDriver(builder, lcm=lcm)
    goal = builder.AddSystem(ConstantVectorSource(np.concatenate([GOAL, np.zeros(6)])))
    builder.Connect(goal.get_output_port(), driver.tracker.GetInputPort("desired_state"))
    stop_source = builder.AddSystem(ConstantVectorSource([stop]))
    builder.Connect(stop_source.get_output_port(), driver.tracker.GetInputPort("stop"))
    simulator = Simulator(builder.Build())
    return simulator, arm


def measured(simulator, arm, name):
    return arm.GetOutputPort(name).Eval(arm.GetMyContextFromRoot(simulator.get_context()))


def test_emulated_arm_follows_the_velocity_commands_to_the_goal():
    simulator, arm = build(stop=0.0)
    simulator.AdvanceTo(0.1)  # moving on every joint (tracker gain 5 1/s)
    assert np.all(np.abs(measured(simulator, arm, "velocity_measured")) > 0.1)
    simulator.AdvanceTo(3.0)
    np.testing.assert_allclose(measured(simulator, arm, "position_measured"), GOAL, atol=1e-3)


def test_emulated_arm_holds_still_when_stopped():
    simulator, arm = build(stop=1.0)
    simulator.AdvanceTo(1.0)
    np.testing.assert_allclose(measured(simulator, arm, "position_measured"), Q0, atol=1e-6)
