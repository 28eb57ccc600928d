"""The simulated 2F-85's drive, once a plant step, compiled (physics: sim_robotiq_driver.py):
a SymbolicVectorSystem evaluates drive_set_point or force_limited_set_point on (a, da/dt),
PLANNER and MEMORY; a ZeroOrderHold keeps MEMORY, sampled half a plant step after the
plant's; a second one gives the PD's set-point. Float order is Python's
(ordered_expressions.py), so the set-points match bit for bit."""

from pydrake.symbolic import Variable, logical_and, logical_or
from pydrake.systems.primitives import Multiplexer, SymbolicVectorSystem, ZeroOrderHold

from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.simulation.ordered_expressions import (SYMBOLIC, Ordered, expressions,
                                                         ordered_max, ordered_min, variable_of,
                                                         variables, where)

# phases: the loop drives; the screw holds a load over the torque; held at the limit
MOVING, STUCK, HELD = 0.0, 1.0, 2.0

# the planner's state: q [m], m/s, m/s^2, m, m/s, N, byte, gOBJ, s, +-1, counts
PLANNER = ("ref_q", "ref_v", "ref_a", "goal", "half_speed", "force", "position_byte",
           "object", "time", "direction", "restarts", "updates")
# the drive's memory: flag, rad, rad/s, phase, N m, rad, rad/s, count, gOBJ, 1 + updates
MEMORY = ("started", "set_a", "set_v", "phase", "motor", "anchor", "v_prev",
          "restarts_seen", "held_object", "held_object_since")
(REF_Q, REF_V, REF_A, GOAL, HALF_SPEED, FORCE, POSITION_BYTE, OBJECT, TIME, DIRECTION,
 RESTARTS, UPDATES) = range(len(PLANNER))
(STARTED, SET_A, SET_V, PHASE, MOTOR, ANCHOR, V_PREV, RESTARTS_SEEN, HELD_OBJECT,
 HELD_OBJECT_SINCE) = range(len(MEMORY))

_CLOSING = float(ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING)
_OPENING = float(ru.ObjectStatus.STOPPED_ON_CONTACT_OPENING)


def effective_phase(planner_state, memory) -> float:
    """The drive's phase: MOVING after a restart not yet stepped, else the memory's."""
    if planner_state[RESTARTS] != memory[RESTARTS_SEEN]:
        return MOVING
    return memory[PHASE]


def object_status_now(planner_state, memory) -> float:
    """gOBJ: the drive's if it held since the planner's last update, else the planner's."""
    if memory[HELD_OBJECT_SINCE] == planner_state[UPDATES] + 1.0:
        return memory[HELD_OBJECT]
    return planner_state[OBJECT]


def _linkage_drive(*, a, v, v_prev, set_a, set_v, phase, anchor, reference, v_ref, limit,
                   direction, gain, damping, inertia, time_step):
    """sim_robotiq_driver.drive_set_point on Ordered values, branches as nested `where`."""
    load = gain * (set_a - a) + damping * (set_v - v) - inertia * (v - v_prev) / time_step
    demand = gain * (reference - a) + damping * (v_ref - v)
    motor = ordered_min(ordered_max(demand, -limit), limit)
    locked = where(direction * motor >= limit, HELD, STUCK)
    held_stays = logical_and(phase.equals(HELD), direction * (a - anchor)
                             <= 0.5 * direction * (set_a - anchor))
    stuck_stays = logical_and(phase.equals(STUCK), direction * motor <= direction * load)
    locks = logical_and(phase.equals(MOVING), logical_and(
        direction * v <= 0.0, direction * load > ordered_max(direction * motor, 0.0)))
    within = abs(demand) <= limit
    v_next = 2.0 * v - v_prev
    stays = logical_or(held_stays, stuck_stays)
    new_a = where(stays, set_a, where(locks, a + load / gain, where(
        within, reference, a + time_step * v_next + motor / gain)))
    new_v = where(logical_or(stays, locks), 0.0, where(within, v_ref, v_next))
    new_phase = where(held_stays, HELD, where(logical_or(stuck_stays, locks), locked, MOVING))
    return (new_a, new_v, new_phase, where(held_stays, 0.0, motor),
            where(locks, a, anchor))


def drive_step_system(hand, *, gain: float, damping: float, inertia: float,
                      time_step: float, initial_actuated: float) -> SymbolicVectorSystem:
    """The drive_step system of `hand`: input [a, da/dt, PLANNER, MEMORY], output MEMORY
    after the step; gains of the plant's PD, inertia [kg m^2], time_step [s]."""
    t = Variable("t")
    a, v = variables(["a", "v"])
    planner = variables([f"planner_{name}" for name in PLANNER])
    memory = variables([f"memory_{name}" for name in MEMORY])
    started = memory[STARTED].differs(0.0)
    set_a = where(started, memory[SET_A], initial_actuated)
    anchor = where(started, memory[ANCHOR], initial_actuated)
    phase = where(planner[RESTARTS].differs(memory[RESTARTS_SEEN]), MOVING, memory[PHASE])
    h = Ordered(t) + 0.5 * time_step - planner[TIME]
    q_ref = planner[REF_Q] + planner[REF_V] * h + 0.5 * planner[REF_A] * h * h
    reference = hand.actuated(q_ref, SYMBOLIC)
    rate = hand.half_opening_rate(reference, SYMBOLIC)
    v_ref = (planner[REF_V] + planner[REF_A] * h) / rate
    lever = abs(hand.half_opening_rate(a, SYMBOLIC))
    force = planner[FORCE]
    if hand.non_backdrivable:
        new_a, new_v, new_phase, motor, new_anchor = _linkage_drive(
            a=a, v=v, v_prev=memory[V_PREV], set_a=set_a, set_v=memory[SET_V], phase=phase,
            anchor=anchor, reference=reference, v_ref=v_ref, limit=2.0 * force * lever,
            direction=planner[DIRECTION], gain=gain, damping=damping, inertia=inertia,
            time_step=time_step)
    else:  # force_limited_set_point
        band = 2.0 * force * lever / gain
        new_a = a + ordered_min(ordered_max(reference - a, -band), band)
        new_v, new_phase, new_anchor = v_ref, phase, anchor
        motor = gain * (new_a - a)
    held = new_phase.equals(HELD)
    held_object = where(held, where(planner[GOAL] < hand.half_opening(a, SYMBOLIC), _CLOSING,
                                    _OPENING), memory[HELD_OBJECT])
    since = where(held, planner[UPDATES] + 1.0, memory[HELD_OBJECT_SINCE])
    outputs = [1.0, new_a, new_v, new_phase, motor, new_anchor, v, planner[RESTARTS],
               held_object, since]
    inputs = [variable_of(x) for x in [a, v, *planner, *memory]]
    return SymbolicVectorSystem(time=t, input=inputs, output=expressions(outputs))


def set_point_system(initial_actuated: float) -> SymbolicVectorSystem:
    """Input MEMORY, output the PD's set-point [a, da/dt]."""
    memory = variables([f"memory_{name}" for name in MEMORY])
    started = memory[STARTED].differs(0.0)
    return SymbolicVectorSystem(
        input=[variable_of(x) for x in memory],
        output=expressions([where(started, memory[SET_A], initial_actuated),
                            memory[SET_V]]))


def AddDriveStep(builder, *, hand, gain: float, damping: float, inertia: float,
                 time_step: float, initial_actuated: float, planner_state):
    """Adds the drive fed by `planner_state`; returns the (a, da/dt) input port to connect,
    the memory's and the set-point's output ports."""
    gather = builder.AddNamedSystem("drive_inputs", Multiplexer([2, len(PLANNER),
                                                                len(MEMORY)]))
    step = builder.AddNamedSystem("drive_step", drive_step_system(
        hand, gain=gain, damping=damping, inertia=inertia, time_step=time_step,
        initial_actuated=initial_actuated))
    memory = builder.AddNamedSystem("drive_memory", ZeroOrderHold(
        time_step, len(MEMORY), offset_sec=0.5 * time_step))
    set_point = builder.AddNamedSystem("drive_set_point", set_point_system(initial_actuated))
    builder.Connect(planner_state, gather.get_input_port(1))
    builder.Connect(memory.get_output_port(), gather.get_input_port(2))
    builder.Connect(gather.get_output_port(), step.get_input_port())
    builder.Connect(step.get_output_port(), memory.get_input_port())
    builder.Connect(memory.get_output_port(), set_point.get_input_port())
    return gather.get_input_port(0), memory.get_output_port(), set_point.get_output_port()
