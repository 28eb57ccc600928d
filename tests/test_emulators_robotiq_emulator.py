"""The emulated Robotiq 2F-85's behaviour (RobotiqGripperModel; no serial line)."""

import pytest

from tegrasp_drake.rig import robotiq_units as units
from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulatorConfig, RobotiqGripperModel
from tegrasp_drake.hardware.robotiq.registers import command_registers

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling


def _model(**config):
    return RobotiqGripperModel(RobotiqEmulatorConfig(**config), now=0.0)


def _activate(model, now):
    model.write(1000, command_registers(0, 0, 0, activate=False, go_to=False), now)
    model.write(1000, command_registers(0, 0, 0, go_to=False), now)


def test_model_activation_takes_its_duration():
    model = _model(activation_duration=0.5)
    _activate(model, 0.0)
    assert model.status(0.4)[units.STATUS_STA] == units.ActivationStatus.ACTIVATING
    status = model.status(0.6)
    assert status[units.STATUS_STA] == units.ActivationStatus.ACTIVE
    assert status[units.STATUS_PO] == units.POSITION_OPEN_BYTE


def test_model_go_to_without_activation_is_fault_7():
    model = _model()
    model.write(1000, command_registers(100, 255, 10, activate=False), 0.0)
    assert model.status(0.1)[units.STATUS_FLT] == 0x07


def test_model_fingers_move_at_the_commanded_speed():
    model = _model(activation_duration=0.0)
    _activate(model, 0.0)
    model.status(0.0)
    model.write(1000, command_registers(230, 255, 10), 1.0)
    full_stroke_time = units.STROKE_M / units.SPEED_MAX_MPS
    halfway = model.status(1.0 + full_stroke_time / 2)
    assert halfway[units.STATUS_OBJ] == units.ObjectStatus.MOVING
    assert halfway[units.STATUS_PO] == pytest.approx((3 + 230) / 2, abs=1)
    done = model.status(1.0 + full_stroke_time + 0.01)
    assert done[units.STATUS_OBJ] == units.ObjectStatus.AT_REQUESTED_POSITION
    assert done[units.STATUS_PO] == 230


def test_model_stops_on_an_object_while_closing():
    model = _model(activation_duration=0.0, object_opening=0.04)
    _activate(model, 0.0)
    model.write(1000, command_registers(255, 255, 255), 0.0)
    status = model.status(2.0)
    assert status[units.STATUS_OBJ] == units.ObjectStatus.STOPPED_ON_CONTACT_CLOSING
    assert status[units.STATUS_PO] == round(units.position_from_opening(0.04))
    assert status[units.STATUS_CU] > 0
    model.set_object_opening(None, 2.0)  # the object slips out: the fingers close on
    assert model.status(3.0)[units.STATUS_OBJ] == units.ObjectStatus.AT_REQUESTED_POSITION


def test_model_major_fault_stops_the_fingers_until_reactivation():
    model = _model(activation_duration=0.0)
    _activate(model, 0.0)
    model.write(1000, command_registers(230, 0, 10), 0.0)
    moved = model.status(0.1)[units.STATUS_PO]
    model.inject_fault(0x0E, 0.1)
    assert model.status(0.5)[units.STATUS_PO] == moved
    assert model.status(0.5)[units.STATUS_FLT] == 0x0E
    _activate(model, 0.5)
    assert model.status(0.6)[units.STATUS_FLT] == 0
