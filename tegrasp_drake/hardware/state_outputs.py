"""Scalar output ports read straight from a driver system's abstract state.

The device receivers keep what they know in one immutable abstract state value and
compute every output from it (`time_measured`, `stale`, ...); each such port depends on
that state only.
"""


def declare_scalar_state_outputs(system, state_index, values: dict) -> None:
    """Declares on `system` one 1-element output port per entry of `values`, in order:
    {port name: function of the state's value (at `state_index`) -> number}."""
    ticket = {system.abstract_state_ticket(state_index)}
    for name, value_of in values.items():
        def calc(context, output, value_of=value_of):
            output.SetAtIndex(0, value_of(context.get_abstract_state(state_index).get_value()))
        system.DeclareVectorOutputPort(name, 1, calc, prerequisites_of_calc=ticket)
