"""The emulated 2F-85's go-to request gPR [byte], shared with the emulated myRIO, whose
replay holds at each recorded grip or release until the gripper is commanded likewise.
In one process the myRIO reads gPR from the gripper model; across processes it follows the
latest message on GRIPPER_STATE_CHANNEL, so a lost message only delays it by a period."""

import threading
import time

from tegrasp_drake.hardware.lcm_boundary import decode_lcm
from tegrasp_drake.hardware.message_boundary import MessageBoundary, RejectedMessage
from tegrasp_drake.robotiq import units

GRIPPER_STATE_CHANNEL = "EMULATED_ROBOTIQ"
# [s] the status rate the driver polls (100 Hz); a request reaches the myRIO within it.
GRIPPER_STATE_PERIOD_S = 0.01


def request_of_model(model):
    """A callable: the gripper model's gPR now [byte]."""
    return lambda: int(model.status(time.monotonic())[units.STATUS_PR])


def publish_gripper_state(lcm_url: str, model, stop: threading.Event):
    """A thread publishing the model's command (rPR, rSP, rFR) and status on
    GRIPPER_STATE_CHANNEL of `lcm_url` every GRIPPER_STATE_PERIOD_S until `stop`."""
    import lcm

    from tegrasp_drake.lcmtypes import lcmt_tegrasp_gripper

    bus = lcm.LCM(lcm_url)

    def run():
        while not stop.wait(GRIPPER_STATE_PERIOD_S):
            now = time.monotonic()
            message = lcmt_tegrasp_gripper()
            message.utime = int(now * 1e6)
            message.status_arrival_s = now
            message.command = model.command()
            message.status = [int(round(v)) for v in model.status(now)]
            bus.publish(GRIPPER_STATE_CHANNEL, message.encode())
    thread = threading.Thread(target=run, name="gripper state", daemon=True)
    thread.start()
    return thread


def check_gripper_request(data: bytes) -> int:
    """The gPR [byte] of a GRIPPER_STATE_CHANNEL message's bytes, or RejectedMessage."""
    from tegrasp_drake.lcmtypes import lcmt_tegrasp_gripper
    message = decode_lcm(lcmt_tegrasp_gripper, data)
    request = message.status[units.STATUS_PR]
    if not 0 <= request <= 255:
        raise RejectedMessage("out of range", f"gPR = {request}, not a byte")
    return int(request)


class GripperRequestFollower:
    """The newest gPR [byte] on GRIPPER_STATE_CHANNEL (None before the first), when called;
    thread-safe. A malformed message is counted in `boundary` and the last good request kept."""

    def __init__(self):
        self._lock = threading.Lock()
        self._request = None
        self.boundary = MessageBoundary(f"myrio: {GRIPPER_STATE_CHANNEL}",
                                        check_gripper_request)

    def on_message(self, data: bytes):
        request = self.boundary.accept(data)
        if request is None:
            return
        with self._lock:
            self._request = request

    def __call__(self) -> int | None:
        with self._lock:
            return self._request


def follow_gripper_state(lcm_url: str, stop: threading.Event) -> GripperRequestFollower:
    """A GripperRequestFollower fed from `lcm_url` by a thread until `stop`."""
    import lcm

    follower = GripperRequestFollower()
    bus = lcm.LCM(lcm_url)
    bus.subscribe(GRIPPER_STATE_CHANNEL, lambda channel, data: follower.on_message(data))

    def run():
        while not stop.is_set():
            bus.handle_timeout(20)
    threading.Thread(target=run, name="gripper follower", daemon=True).start()
    return follower
