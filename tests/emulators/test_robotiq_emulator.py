"""The emulated Robotiq 2F-85's behaviour (RobotiqGripperModel; no serial line)."""

import pytest

from tegrasp_drake.robotiq import units
from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulatorConfig, RobotiqGripperModel
from tegrasp_drake.robotiq.registers import command_registers

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
    assert status[units.STATUS_CU] == 0  # the screw holds (the manual's finished grasp)
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


def test_model_go_to_written_with_the_activation_is_carried_out_after_it():
    # One register, rACT | rGTO (0x0900), as pyrobotiqgripper's activate() writes it.
    model = _model(activation_duration=0.5)
    model.write(1000, command_registers(0, 0, 0, activate=False, go_to=False), 0.0)
    model.write(1000, [0x0900], 0.0)
    activating = model.status(0.4)
    assert activating[units.STATUS_STA] == units.ActivationStatus.ACTIVATING
    assert activating[units.STATUS_GTO] == 0
    assert activating[units.STATUS_FLT] == units.FAULT_ACTION_DELAYED
    active = model.status(0.6)
    assert active[units.STATUS_STA] == units.ActivationStatus.ACTIVE
    assert active[units.STATUS_GTO] == 1  # the echo of rGTO
    assert active[units.STATUS_FLT] == 0
    model.write(1001, [60, 0xFFFF], 0.6)  # rPR, then rSP | rFR, rGTO still 1
    assert model.status(2.0)[units.STATUS_PO] == 60


def test_model_go_to_stays_delayed_if_rgto_is_cleared_during_activation():
    model = _model(activation_duration=0.5)
    model.write(1000, [0x0900, 60, 0xFFFF], 0.0)
    model.write(1000, [0x0100], 0.1)
    status = model.status(1.0)
    assert status[units.STATUS_GTO] == 0 and status[units.STATUS_FLT] == 0
    assert status[units.STATUS_PO] == units.POSITION_OPEN_BYTE


def test_model_fingers_stop_at_the_ends_of_the_stroke():
    model = _model(activation_duration=0.0)
    _activate(model, 0.0)
    model.write(1000, command_registers(255, 255, 10), 0.0)
    closed = model.status(2.0)
    assert closed[units.STATUS_PO] == units.POSITION_CLOSED_BYTE
    assert closed[units.STATUS_OBJ] == units.ObjectStatus.AT_REQUESTED_POSITION
    assert closed[units.STATUS_PR] == 255
    model.write(1000, command_registers(0, 255, 10), 2.0)
    opened = model.status(4.0)
    assert opened[units.STATUS_PO] == units.POSITION_OPEN_BYTE
    assert opened[units.STATUS_OBJ] == units.ObjectStatus.AT_REQUESTED_POSITION


def test_model_rejects_a_write_outside_the_command_registers():
    with pytest.raises(ValueError, match="registers 1000-1002"):
        _model().write(1002, [0, 0], 0.0)
