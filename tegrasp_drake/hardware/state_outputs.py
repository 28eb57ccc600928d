"""Scalar output ports read straight from a device receiver's immutable abstract state."""


def declare_scalar_state_outputs(system, state_index, values: dict) -> None:
    """One 1-element output per {port name: state value -> number}, depending on that state."""
    ticket = {system.abstract_state_ticket(state_index)}
    for name, value_of in values.items():
        def calc(context, output, value_of=value_of):
            output.SetAtIndex(0, value_of(context.get_abstract_state(state_index).get_value()))
        system.DeclareVectorOutputPort(name, 1, calc, prerequisites_of_calc=ticket)
