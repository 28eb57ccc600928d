"""Whether a block that runs every plant step gets cheaper as a compiled Drake system. From a
checkout:

    python -m benchmarks.per_step_python [--repeats 5] [--json]

Each variant is a small Diagram stepped at 1 kHz (the plant's step) for SIMULATED_S: a
compiled source of the gripper's generalized contact forces and state (a LinearSystem) read
every step by a ZeroOrderHold, through the block under test. Process CPU per step, variants
alternating within each repeat, medians, and each one's cost over the source and hold alone:

  - a bare Python output (one vector Eval, two floats written): what any Python callback
    costs per plant step, whatever it computes;
  - both linkage pads' normal forces (linkage_pad_statics.py, the films' per-step
    arithmetic with `joint_forces`) as a Python output;
  - the same formula as a SymbolicVectorSystem (stateless, evaluated on every read).

pydrake.symbolic evaluates an expression by walking its tree, so a compiled system is
cheaper than Python only for small expressions: compare the last two before compiling a block.
"""

import argparse
import json
import statistics
import time

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.symbolic import Variable
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.primitives import (ConstantVectorSource, LinearSystem,
                                        SymbolicVectorSystem, ZeroOrderHold)

from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig import paths
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.simulation.linkage_pad_statics import LinkagePadStatics

TIME_STEP_S = 1e-3  # the plant's step
SIMULATED_S = 3.0
VARIANTS = ("source and hold alone", "bare Python output", "pad statics, Python",
            "pad statics, SymbolicVectorSystem")


def linkage_pad_statics() -> LinkagePadStatics:
    """The statics of the linkage hand's model, welded to the world."""
    plant = MultibodyPlant(time_step=TIME_STEP_S)
    (gripper,) = paths.make_parser(plant).AddModels(url=gripper_hand("linkage").url)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", gripper))
    plant.Finalize()
    return LinkagePadStatics(plant, gripper)


class BarePythonOutput(LeafSystem):
    """Reads its input and writes two of its entries: a Python callback's floor.

    .. pydrake_system::

        name: BarePythonOutput
        input_ports:
        - u
        output_ports:
        - y

    Ports: u (size), any floats; y (2), u's first two entries.
    """

    def __init__(self, size: int):
        super().__init__()
        self._input = self.DeclareVectorInputPort("u", size)
        self.DeclareVectorOutputPort("y", 2, self._calc)

    def _calc(self, context, output):
        values = self._input.Eval(context).tolist()
        output.SetFromVector(values[:2])


class PythonPadStatics(LeafSystem):
    """Both pads' normal forces in Python.

    .. pydrake_system::

        name: PythonPadStatics
        input_ports:
        - u
        output_ports:
        - y

    Ports: u, the gripper instance's generalized contact forces [N m] then its state
    (positions first) [rad, rad/s]; y (2), the left and right pad normal forces [N].
    """

    def __init__(self, statics: LinkagePadStatics):
        super().__init__()
        self._statics = statics
        self._split = statics.velocities
        self._input = self.DeclareVectorInputPort("u", statics.velocities + statics.states)
        self.DeclareVectorOutputPort("y", 2, self._calc)

    def _calc(self, context, output):
        values = self._input.Eval(context).tolist()
        output.SetFromVector(self._statics.normal_forces(values[:self._split],
                                                         values[self._split:]))


def symbolic_pad_statics(statics: LinkagePadStatics) -> SymbolicVectorSystem:
    """The same forces as a SymbolicVectorSystem with the same input."""
    tau = [Variable(f"tau_{i}") for i in range(statics.velocities)]
    state = [Variable(f"x_{i}") for i in range(statics.states)]
    return SymbolicVectorSystem(input=tau + state,
                                output=list(statics.normal_force_expressions(tau, state)))


def block_under_test(variant: str, statics: LinkagePadStatics):
    """The system of `variant` (VARIANTS), or None for the source and hold alone."""
    size = statics.velocities + statics.states
    return {VARIANTS[0]: lambda: None,
            VARIANTS[1]: lambda: BarePythonOutput(size),
            VARIANTS[2]: lambda: PythonPadStatics(statics),
            VARIANTS[3]: lambda: symbolic_pad_statics(statics)}[variant]()


def per_step_diagram(block, size: int):
    """A Simulator of a decaying compiled signal of `size` entries through `block` into a
    ZeroOrderHold named "hold"."""
    builder = DiagramBuilder()
    source = builder.AddSystem(LinearSystem(
        A=0.999 * np.eye(size), B=np.zeros((size, 1)), C=np.eye(size), D=np.zeros((size, 1)),
        time_period=TIME_STEP_S))
    zero = builder.AddSystem(ConstantVectorSource([0.0]))
    builder.Connect(zero.get_output_port(), source.get_input_port())
    signal = source.get_output_port()
    if block is not None:
        builder.AddSystem(block)
        builder.Connect(signal, block.get_input_port())
        signal = block.get_output_port()
    hold = builder.AddNamedSystem("hold", ZeroOrderHold(TIME_STEP_S, signal.size()))
    builder.Connect(signal, hold.get_input_port())
    diagram = builder.Build()
    simulator = Simulator(diagram)
    # Joint angles of a half-closed finger (about 0.3 rad) and torques of a few N m, all
    # nonzero, so that nothing evaluates to a special case.
    diagram.GetMutableSubsystemContext(source, simulator.get_mutable_context()) \
        .SetDiscreteState(np.linspace(0.1, 0.5, size))
    return simulator


def step_cost_us(variant: str, statics: LinkagePadStatics, simulated_s: float) -> float:
    """Process CPU per plant step [us] of `variant`, simulated for simulated_s [s]."""
    simulator = per_step_diagram(block_under_test(variant, statics),
                                 statics.velocities + statics.states)
    simulator.Initialize()
    start = time.process_time()
    simulator.AdvanceTo(simulated_s)
    return (time.process_time() - start) / (simulated_s / TIME_STEP_S) * 1e6


def compare_per_step_blocks(*, repeats: int, simulated_s: float = SIMULATED_S) -> dict:
    """{variant: {"us_per_step", "over_alone_us"}}: medians over `repeats`, alternating."""
    statics = linkage_pad_statics()
    runs = {variant: [] for variant in VARIANTS}
    for _ in range(repeats):
        for variant in VARIANTS:
            runs[variant].append(step_cost_us(variant, statics, simulated_s))
    alone = statistics.median(runs[VARIANTS[0]])
    return {variant: {"us_per_step": statistics.median(values),
                      "over_alone_us": statistics.median(values) - alone}
            for variant, values in runs.items()}


def format_per_step_blocks(result: dict) -> str:
    lines = [f"{'variant':36s} {'us per step':>12s} {'over the source and hold':>25s}"]
    for variant, figures in result.items():
        lines.append(f"{variant:36s} {figures['us_per_step']:12.2f} "
                     f"{figures['over_alone_us']:25.2f}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=integer_option, default=5,
                        help="runs of each variant, alternating")
    parser.add_argument("--json", action="store_true",
                        help="print the figures as one JSON object")
    args = parser.parse_args(argv)
    if args.repeats < 1:
        parser.error(f"--repeats {args.repeats}: give at least 1 run per variant")
    result = compare_per_step_blocks(repeats=args.repeats)
    print(json.dumps(result) if args.json else format_per_step_blocks(result))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
