"""The simulated 2F-85's compiled drive step (robotiq_drive_step.py) against the Python
drive step it replaces (the SimRobotiqDriver's `_drive_step` up to this change, written
out below on the module's pure functions), bit for bit, on random states that reach every
branch."""

import math

import numpy as np
import pytest

from tegrasp_drake.robotiq import linkage
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.simulation.robotiq_drive_step import (
    ANCHOR, DIRECTION, FORCE, GOAL, HELD, HELD_OBJECT, HELD_OBJECT_SINCE, MEMORY, MOTOR,
    MOVING, PHASE, PLANNER, REF_A, REF_Q, REF_V, RESTARTS, RESTARTS_SEEN, SET_A, SET_V,
    STARTED, STUCK, TIME, UPDATES, V_PREV, drive_step_system, set_point_system)
from tegrasp_drake.simulation.sim_robotiq_driver import (GripperDriverConfig, drive_set_point,
                                                         force_limited_set_point,
                                                         held_object_status)

TIME_STEP = 1e-3


def python_drive_step(hand, config, planner, memory, a, v, t, initial_actuated):
    """The drive step as SimRobotiqDriver ran it in Python: the memory after the step at
    time t (the state it kept, in robotiq_drive_step.MEMORY's layout)."""
    gain, damping = hand.pd_gains(config)
    started = memory[STARTED] != 0.0
    set_point = ([memory[SET_A], memory[SET_V]] if started else [initial_actuated, 0.0])
    phase = MOVING if planner[RESTARTS] != memory[RESTARTS_SEEN] else memory[PHASE]
    anchor = memory[ANCHOR] if started else initial_actuated
    motor = memory[MOTOR]
    h = t + 0.5 * TIME_STEP - planner[TIME]
    q_ref = planner[REF_Q] + planner[REF_V] * h + 0.5 * planner[REF_A] * h * h
    reference = hand.actuated(q_ref)
    rate = hand.half_opening_rate(reference)
    v_ref = (planner[REF_V] + planner[REF_A] * h) / rate
    lever = abs(hand.half_opening_rate(a))
    if hand.non_backdrivable:
        set_a, set_v, phase, motor, anchor = drive_set_point(
            a=a, v=v, v_prev=memory[V_PREV], set_point=set_point, phase=phase,
            anchor=anchor, reference=(reference, v_ref), limit=2.0 * planner[FORCE] * lever,
            direction=planner[DIRECTION], gain=gain, damping=damping,
            inertia=hand.drive_inertia(config), time_step=TIME_STEP)
    else:
        set_a = force_limited_set_point(a, reference, planner[FORCE], gain, lever)
        set_v = v_ref
        motor = gain * (set_a - a)
    held_object, since = memory[HELD_OBJECT], memory[HELD_OBJECT_SINCE]
    if phase == HELD:
        held_object = float(held_object_status(hand.half_opening(a), planner[GOAL]))
        since = planner[UPDATES] + 1.0
    return [1.0, set_a, set_v, phase, motor, anchor, v, planner[RESTARTS], held_object, since]


def random_case(rng, hand, config):
    """(planner state, memory, a, v, t) around a blocked or moving finger."""
    gain, _ = hand.pd_gains(config)
    a = hand.actuated(rng.uniform(0.0, 0.0425))
    lever = abs(hand.half_opening_rate(a))
    force = rng.uniform(ru.FORCE_MIN_N, ru.FORCE_MAX_N)
    limit = 2.0 * force * lever
    k = int(rng.integers(0, 20000))
    t = (k + 0.5) * TIME_STEP
    planner = np.zeros(len(PLANNER))
    planner[REF_Q] = rng.choice([rng.uniform(0.0, 0.0425), hand.half_opening(a) +
                                 rng.normal(scale=1e-3)])
    planner[REF_V] = rng.choice([0.0, rng.normal(scale=0.05)])
    planner[REF_A] = rng.choice([0.0, 0.5, -0.5])
    planner[GOAL] = rng.choice([0.0, 0.0425, rng.uniform(0.0, 0.0425)])
    planner[FORCE] = force
    planner[TIME] = 0.005 * math.floor(t / 0.005)
    planner[DIRECTION] = rng.choice([1.0, -1.0])
    planner[RESTARTS] = float(rng.integers(0, 3))
    planner[UPDATES] = float(rng.integers(0, 5))
    memory = np.zeros(len(MEMORY))
    memory[STARTED] = rng.choice([0.0, 1.0], p=[0.1, 0.9])
    memory[SET_A] = a + rng.choice([1.0, -1.0]) * rng.uniform(0.0, 2.5) * limit / gain
    memory[SET_V] = rng.choice([0.0, rng.normal(scale=0.05)])
    memory[PHASE] = rng.choice([MOVING, STUCK, HELD])
    memory[MOTOR] = rng.uniform(-limit, limit)
    memory[ANCHOR] = a + rng.normal(scale=1e-3)
    memory[V_PREV] = rng.choice([0.0, rng.normal(scale=0.05)])
    memory[RESTARTS_SEEN] = planner[RESTARTS] - rng.choice([0.0, 1.0], p=[0.8, 0.2])
    memory[HELD_OBJECT] = rng.choice([0.0, 2.0, 1.0])
    memory[HELD_OBJECT_SINCE] = float(rng.integers(0, 5))
    if not memory[STARTED]:  # before the first step the memory is all zero
        memory[:] = 0.0
    v = rng.choice([0.0, rng.normal(scale=0.05), -abs(rng.normal(scale=1e-3))])
    return planner, memory, float(a), float(v), t


@pytest.mark.parametrize("model", ["linkage", "prismatic"])
def test_the_compiled_drive_step_equals_the_python_one_bit_for_bit(model):
    config = GripperDriverConfig(model=model)
    hand = gripper_hand(model)
    gain, damping = hand.pd_gains(config)
    initial = hand.actuated(ru.STROKE_M / 2)
    system = drive_step_system(hand, gain=gain, damping=damping,
                               inertia=hand.drive_inertia(config), time_step=TIME_STEP,
                               initial_actuated=initial)
    context = system.CreateDefaultContext()
    rng = np.random.default_rng(38)
    phases = set()
    for _ in range(3000):
        planner, memory, a, v, t = random_case(rng, hand, config)
        context.SetTime(t)
        system.get_input_port().FixValue(context, np.concatenate([[a, v], planner, memory]))
        compiled = system.get_output_port().Eval(context).tolist()
        expected = python_drive_step(hand, config, planner.tolist(), memory.tolist(), a, v, t,
                                     initial)
        assert compiled == expected, (planner, memory, a, v, t)
        phases.add((memory[PHASE], expected[PHASE]))
    if model == "linkage":  # every phase was entered from every phase
        assert phases == {(p, q) for p in (MOVING, STUCK, HELD) for q in (MOVING, STUCK, HELD)}


def test_before_its_first_step_the_drive_sets_the_hands_initial_set_point():
    initial = linkage.driver_angle(ru.STROKE_M / 2)
    system = set_point_system(initial)
    context = system.CreateDefaultContext()
    system.get_input_port().FixValue(context, np.zeros(len(MEMORY)))
    assert system.get_output_port().Eval(context).tolist() == [initial, 0.0]
    memory = np.zeros(len(MEMORY))
    memory[[STARTED, SET_A, SET_V]] = 1.0, 0.3, -0.2
    system.get_input_port().FixValue(context, memory)
    assert system.get_output_port().Eval(context).tolist() == [0.3, -0.2]
