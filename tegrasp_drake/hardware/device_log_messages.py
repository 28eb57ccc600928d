"""The hardware station's device data as LCM messages (tegrasp_drake/lcmtypes), so a bus log
holds all the control loop saw: Sender systems (vectors -> message) and pure decoders back
to arrays. Channels: TEGRASP_TACTILE (1 kHz), TEGRASP_GRIPPER (100 Hz); the run adds
TEGRASP_TRANSITION, TEGRASP_FAULT and TEGRASP_RUN_INFO. `utime` is Context time [us]."""

import time

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.hardware.lcm_time import utime_from_time
from tegrasp_drake.robotiq import units
from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.lcmtypes import lcmt_tegrasp_gripper, lcmt_tegrasp_tactile

TACTILE_CHANNEL = "TEGRASP_TACTILE"
GRIPPER_CHANNEL = "TEGRASP_GRIPPER"
TRANSITION_CHANNEL = "TEGRASP_TRANSITION"
FAULT_CHANNEL = "TEGRASP_FAULT"
RUN_INFO_CHANNEL = "TEGRASP_RUN_INFO"
TACTILE_PUBLISH_PERIOD = 1e-3   # [s], the receiver's tick
GRIPPER_PUBLISH_PERIOD = 0.01   # [s]


class TactileStatusSender(LeafSystem):
    """TactileSerialReceiver's outputs of the same names [N, m/s^2, s] as an
    `lcmt_tegrasp_tactile`; it adds the host time it was built (tick_s), so a log gives each
    frame's latency from arrival_time.

    .. pydrake_system::

        name: TactileStatusSender
        input_ports:
        - left_taxel_forces
        - right_taxel_forces
        - left_pad_acceleration
        - right_pad_acceleration
        - time_measured
        - stale
        - zeroing
        - arrival_time
        output_ports:
        - lcmt_tegrasp_tactile
    """

    def __init__(self):
        super().__init__()
        self._forces = [self.DeclareVectorInputPort(f"{f}_taxel_forces", TAXELS_PER_PAD)
                        for f in FINGER_NAMES]
        self._accelerations = [self.DeclareVectorInputPort(f"{f}_pad_acceleration", 3)
                               for f in FINGER_NAMES]
        self._time_port = self.DeclareVectorInputPort("time_measured", 1)
        self._stale_port = self.DeclareVectorInputPort("stale", 1)
        self._zeroing_port = self.DeclareVectorInputPort("zeroing", 1)
        self._arrival_port = self.DeclareVectorInputPort("arrival_time", 1)
        self.DeclareAbstractOutputPort(
            "lcmt_tegrasp_tactile", lambda: AbstractValue.Make(lcmt_tegrasp_tactile()),
            self._calc_message)

    def _calc_message(self, context, output):
        message = lcmt_tegrasp_tactile()
        message.utime = utime_from_time(context.get_time())
        message.device_utime = utime_from_time(self._time_port.Eval(context)[0])
        message.stale = bool(self._stale_port.Eval(context)[0])
        message.zeroing = bool(self._zeroing_port.Eval(context)[0])
        message.arrival_s = float(self._arrival_port.Eval(context)[0])
        message.tick_s = time.monotonic()
        message.num_taxels = TAXELS_PER_PAD
        message.left_taxel_forces, message.right_taxel_forces = (
            port.Eval(context).tolist() for port in self._forces)
        message.left_pad_acceleration, message.right_pad_acceleration = (
            port.Eval(context).tolist() for port in self._accelerations)
        output.set_value(message)


class GripperStatusSender(LeafSystem):
    """The gripper's command (3 bytes [rPR, rSP, rFR]; zeros if unconnected), status (8 bytes,
    robotiq.units order) and time_measured (host monotonic [s]) as an `lcmt_tegrasp_gripper`.

    .. pydrake_system::

        name: GripperStatusSender
        input_ports:
        - command (optional)
        - status
        - time_measured
        output_ports:
        - lcmt_tegrasp_gripper
    """

    def __init__(self):
        super().__init__()
        self._command_port = self.DeclareVectorInputPort("command", units.COMMAND_SIZE)
        self._status_port = self.DeclareVectorInputPort("status", units.STATUS_SIZE)
        self._time_port = self.DeclareVectorInputPort("time_measured", 1)
        self.DeclareAbstractOutputPort(
            "lcmt_tegrasp_gripper", lambda: AbstractValue.Make(lcmt_tegrasp_gripper()),
            self._calc_message)

    def _calc_message(self, context, output):
        message = lcmt_tegrasp_gripper()
        message.utime = utime_from_time(context.get_time())
        message.status_arrival_s = float(self._time_port.Eval(context)[0])
        command = (self._command_port.Eval(context) if self._command_port.HasValue(context)
                   else np.zeros(units.COMMAND_SIZE))
        message.command = [int(round(x)) for x in command]
        message.status = [int(round(x)) for x in self._status_port.Eval(context)]
        output.set_value(message)


def tactile_arrays(messages) -> dict:
    """Arrays of lcmt_tegrasp_tactile messages: t, device_t [s]; taxels (n, 24) [N];
    pad_acceleration (n, 6); stale, zeroing; arrival_s, tick_s [s, host monotonic]."""
    messages = list(messages)
    n = len(messages)
    # Filled row by row into arrays made once: no list of rows beside them (a long log holds
    # hundreds of thousands of messages).
    taxels = np.empty((n, 2 * TAXELS_PER_PAD))
    pad_acceleration = np.empty((n, 6))
    for k, m in enumerate(messages):
        taxels[k, :TAXELS_PER_PAD] = m.left_taxel_forces
        taxels[k, TAXELS_PER_PAD:] = m.right_taxel_forces
        pad_acceleration[k, :3] = m.left_pad_acceleration
        pad_acceleration[k, 3:] = m.right_pad_acceleration
    return {
        "t": np.fromiter((m.utime * 1e-6 for m in messages), float, n),
        "device_t": np.fromiter((m.device_utime * 1e-6 for m in messages), float, n),
        "taxels": taxels,
        "pad_acceleration": pad_acceleration,
        "stale": np.fromiter((m.stale for m in messages), bool, n),
        "arrival_s": np.fromiter((m.arrival_s for m in messages), float, n),
        "tick_s": np.fromiter((m.tick_s for m in messages), float, n),
        "zeroing": np.fromiter((m.zeroing for m in messages), bool, n),
    }
