"""The per-step block benchmark's variants run and report (their values are machine dependent)."""

import math

import numpy as np

from benchmarks.per_step_python import (VARIANTS, block_under_test, compare_per_step_blocks,
                                        format_per_step_blocks, linkage_pad_statics,
                                        per_step_diagram)


def test_every_variant_is_measured_against_the_source_and_hold_alone():
    result = compare_per_step_blocks(repeats=1, simulated_s=0.05)
    assert list(result) == list(VARIANTS)
    assert all(math.isfinite(figures["us_per_step"]) and figures["us_per_step"] > 0.0
               for figures in result.values())
    assert result[VARIANTS[0]]["over_alone_us"] == 0.0
    assert all(variant in format_per_step_blocks(result) for variant in VARIANTS)


def test_both_statics_variants_hold_the_same_forces():
    # The two measured blocks compute the same thing, so their costs compare.
    statics = linkage_pad_statics()
    held = []
    for variant in VARIANTS[2:]:
        simulator = per_step_diagram(block_under_test(variant, statics),
                                     statics.velocities + statics.states)
        simulator.AdvanceTo(0.01)
        hold = simulator.get_system().GetSubsystemByName("hold")
        held.append(hold.get_output_port().Eval(
            hold.GetMyContextFromRoot(simulator.get_context())))
    assert np.all(np.abs(held[0]) > 0.0)
    np.testing.assert_allclose(held[1], held[0], rtol=1e-12)
