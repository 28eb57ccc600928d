"""The station's port contract: the names and sizes every station exports."""

import pytest

from tegrasp_drake.rig import station_interface as ports


def test_controller_ports_have_the_devices_sizes():
    """Six JACO2 joints (desired state: positions and velocities), the 2F-85's three command
    bytes and eight status bytes, twelve taxels and a three-axis film signal per pad."""
    assert ports.CONTROLLER_INPUTS == {"arm.desired_state": 12, "gripper.command": 3}
    assert ports.CONTROLLER_OUTPUTS == {
        "arm.position_measured": 6, "arm.velocity_measured": 6, "arm.torque_measured": 6,
        "gripper.status": 8,
        "tactile.left_taxel_forces": 12, "tactile.right_taxel_forces": 12,
        "tactile.left_pad_acceleration": 3, "tactile.right_pad_acceleration": 3}


def test_a_port_of_an_unknown_finger_is_refused_by_name():
    with pytest.raises(ValueError, match="finger must be one of .*'middle'"):
        ports.taxel_forces("middle")
