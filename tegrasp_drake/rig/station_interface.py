"""The station's ports: the one contract between a station and the controller. The simulated and
real stations export these names, so the controller connects to either; name a port by its
constant. CONTROLLER_INPUTS and CONTROLLER_OUTPUTS are the ports every station has."""

from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.robotiq import units

ARM_JOINTS = 6  # the JACO2 j2n6s300: six joints
PAD_ACCELERATION_AXES = 3  # each pad's vibration signal, x y z of the pad frame [m/s^2]

# Inputs: what the controller commands.
ARM_DESIRED_STATE = "arm.desired_state"  # (12) joint positions [rad], velocities [rad/s]
GRIPPER_COMMAND = "gripper.command"  # (3) rPR, rSP, rFR bytes (robotiq.units)

# Outputs every station has: what the controller reads.
ARM_POSITION_MEASURED = "arm.position_measured"  # (6) [rad]
ARM_VELOCITY_MEASURED = "arm.velocity_measured"  # (6) [rad/s]
ARM_TORQUE_MEASURED = "arm.torque_measured"  # (6) [N m], gravity-free
GRIPPER_STATUS = "gripper.status"  # (8) status bytes (robotiq.units order)


def taxel_forces(finger: str) -> str:
    """The port of one pad's 12 taxel normal forces [N] (finger: "left" or "right")."""
    return f"tactile.{_finger(finger)}_taxel_forces"


def pad_acceleration(finger: str) -> str:
    """The port of one pad's vibration film, in acceleration-equivalent units [m/s^2] (3)."""
    return f"tactile.{_finger(finger)}_pad_acceleration"


def _finger(finger: str) -> str:
    if finger not in FINGER_NAMES:
        raise ValueError(f"finger must be one of {FINGER_NAMES}, got {finger!r}")
    return finger


CONTROLLER_INPUTS = {ARM_DESIRED_STATE: 2 * ARM_JOINTS, GRIPPER_COMMAND: units.COMMAND_SIZE}
CONTROLLER_OUTPUTS = {
    ARM_POSITION_MEASURED: ARM_JOINTS,
    ARM_VELOCITY_MEASURED: ARM_JOINTS,
    ARM_TORQUE_MEASURED: ARM_JOINTS,
    GRIPPER_STATUS: units.STATUS_SIZE,
    **{taxel_forces(finger): TAXELS_PER_PAD for finger in FINGER_NAMES},
    **{pad_acceleration(finger): PAD_ACCELERATION_AXES for finger in FINGER_NAMES},
}

# Both stations, for logs (no controller reads it).
ARM_COMMANDED_STATE = "arm.commanded_state"  # (12) positions and velocities sent to the arm

# Simulation only: ground truth for evaluation and the plant's internals.
OBJECT_STATE = "object.state"  # (13) quaternion wxyz, p_WO [m], w_WO [rad/s], v_WO [m/s]
TRUE_TAXEL_FORCES = "tactile.true_taxel_forces"  # (24) both pads before noise [N]
CONTACT_RESULTS = "contact_results"  # the plant's ContactResults (abstract)
BODY_POSES = "body_poses"  # the plant's body poses X_WB (abstract)
QUERY_OBJECT = "query_object"  # the scene graph's QueryObject (abstract)
GRIPPER_STATE = "gripper.state"  # the gripper model instance's joint positions, velocities
GRIPPER_PLANT_DESIRED_STATE = "gripper.plant_desired_state"  # (2) actuated joint's set-point
ARM_SERVO_SET_POINT = "arm.servo_set_point"  # (12) the arm joints' PD set-point
CARRIAGE_DESIRED_STATE = "carriage.desired_state"  # (12) the carriage PD's set-point (carriage.py)
GRIPPER_WRIST_WRENCH = "gripper.wrist_wrench"  # (6) the carriage-gripper weld's wrench

# Hardware only: faults and each device's clock.
FAULT = "fault"  # every fault seen, a tuple of DeviceFault (abstract); () while all is well
DEVICE_FAULT = "device_fault"  # the same as text (abstract str); "" while all is well
STOP = "stop"  # (1) 1 once there is any fault
ARM_TIME_MEASURED = "arm.time_measured"  # (1) [s], each device's last message
GRIPPER_TIME_MEASURED = "gripper.time_measured"
TACTILE_TIME_MEASURED = "tactile.time_measured"
TACTILE_STALE = "tactile.stale"  # (1) 1 while the tactile stream is late
TACTILE_ZEROING = "tactile.zeroing"  # (1) 1 while the taxel offsets are being measured
# (abstract (n, 6) array [m/s^2]) every film sample of the tick, in device order
TACTILE_PAD_ACCELERATION_SAMPLES = "tactile.pad_acceleration_samples"


# The rates [Hz] a station's taxel_forces and pad_acceleration outputs are sampled at, (SA, RA),
# kept on the station Diagram as this attribute by the station that knows them (the simulated
# one, from its scenario); a real station's device sets its own, so none is declared.
_SAMPLE_RATES_ATTRIBUTE = "tactile_sample_rates_hz"


def declare_sample_rates(station, rates_hz: tuple[float, float]) -> None:
    """Records on `station` the (SA, RA) rates [Hz] its tactile outputs are sampled at."""
    setattr(station, _SAMPLE_RATES_ATTRIBUTE, (float(rates_hz[0]), float(rates_hz[1])))


def declared_sample_rates(station) -> tuple[float, float] | None:
    """The (SA, RA) rates [Hz] `station` declared (declare_sample_rates), or None."""
    return getattr(station, _SAMPLE_RATES_ATTRIBUTE, None)
