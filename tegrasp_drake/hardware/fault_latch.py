"""FaultLatch: the faults of every source, kept once seen, and the arm's stop signal. A
Robotiq fault code can clear, but the run that saw it must not carry on: every fault stays,
with its own `since`, and `stop` stays set."""

from pydrake.common.value import AbstractValue
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.hardware.device_fault import describe_faults


def latched_faults(latched: tuple, current) -> tuple:
    """`latched` plus the faults of `current` not yet in it (same device, kind, code)."""
    seen = {(f.device, f.kind, f.code) for f in latched}
    new = [f for f in current if (f.device, f.kind, f.code) not in seen]
    return latched + tuple(new) if new else latched


class FaultLatch(LeafSystem):
    """Keeps every fault of its sources, shown one `period` [s] after reported: one
    `{source}_fault` input per name in `sources`. fault: every fault seen; message: "" or one
    line per fault; stop: 1 once any was seen.

    .. pydrake_system::

        name: FaultLatch
        input_ports:
        - watchdog_fault
        - gripper_fault
        - tactile_fault
        output_ports:
        - fault
        - message
        - stop
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
