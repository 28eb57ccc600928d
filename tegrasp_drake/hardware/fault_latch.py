"""FaultLatch: the faults of every source, kept once seen, and the arm's stop signal.

The watchdog latches silent devices itself; a Robotiq fault code can clear (e.g. after an
automatic release), but the run that saw it must not carry on as if nothing happened: the
state machine goes to Failed on any fault and the operator decides. So every fault seen
is kept, with its own `since`, in order of first sighting, and `stop` (holding the arm
still through JacoVelocityTracker) stays set.
"""

from pydrake.common.value import AbstractValue
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.hardware.device_fault import describe_faults


def latched_faults(latched: tuple, current) -> tuple:
    """`latched` plus the faults of `current` not yet in it (same device, kind, code)."""
    seen = {(f.device, f.kind, f.code) for f in latched}
    new = [f for f in current if (f.device, f.kind, f.code) not in seen]
    return latched + tuple(new) if new else latched


class FaultLatch(LeafSystem):
    """Keeps every fault of its sources (module docstring).

    One input per name in `sources`, in its order; with sources ["watchdog", "gripper"]
    (as MakeHardwareStation builds it):

    .. pydrake_system::

        name: FaultLatch
        input_ports:
        - watchdog_fault
        - gripper_fault
        output_ports:
        - fault
        - message
        - stop

    Ports:
        {source}_fault: (abstract tuple of DeviceFault) the source's current faults.
        fault: (abstract tuple of DeviceFault) every fault seen, in order of sighting.
        message: (abstract str) "" while there is none, else one line per fault (which
            device, what, since when), for the state machine's `device_fault` input.
        stop: (1) 1 once any fault was seen.

    A fault shows on the outputs one `period` [s] after its source reported it.
    """

    def __init__(self, sources, *, period: float = 1e-3):
        super().__init__()
        self._ports = [self.DeclareAbstractInputPort(f"{source}_fault", AbstractValue.Make(()))
                       for source in sources]
        self._state_index = self.DeclareAbstractState(AbstractValue.Make(()))
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._update)
        ticket = {self.abstract_state_ticket(self._state_index)}
        self.DeclareAbstractOutputPort(
            "fault", lambda: AbstractValue.Make(()),
            lambda context, out: out.set_value(self._faults(context)),
            prerequisites_of_calc=ticket)
        self.DeclareAbstractOutputPort(
            "message", lambda: AbstractValue.Make(""),
            lambda context, out: out.set_value(
                describe_faults(self._faults(context)) if self._faults(context) else ""),
            prerequisites_of_calc=ticket)
        self.DeclareVectorOutputPort(
            "stop", 1, lambda context, out: out.SetAtIndex(0, bool(self._faults(context))),
            prerequisites_of_calc=ticket)

    def _faults(self, context) -> tuple:
        return context.get_abstract_state(self._state_index).get_value()

    def _update(self, context, state):
        faults = self._faults(context)
        for port in self._ports:
            faults = latched_faults(faults, port.Eval(context))
        state.get_mutable_abstract_state(self._state_index).set_value(faults)
