"""benchmarks.native_profile's sorting of py-spy's samples into the parts of a trial."""

import pytest

from benchmarks.native_profile import FRAMEWORK, main, parts_from_raw, sample_part

_ADVANCE = "drake::systems::Simulator<double>::AdvanceTo (libdrake.so)"
_TOP = "<module> (<string>:5);run_trial (tegrasp_drake/runs/trial.py:136)"


def _stack(*frames: str) -> list[str]:
    return [*_TOP.split(";"), _ADVANCE, *frames]


def test_a_python_systems_callback_owns_the_sample_whatever_it_evaluates():
    frames = _stack("drake::systems::LeafSystem<double>::DispatchDiscreteVariableUpdateHandler",
                    "TactilePads._sample (tegrasp_drake/simulation/tactile_pads.py:173)",
                    "pads_forces (tegrasp_drake/simulation/tactile_pads.py:112)",
                    "drake::multibody::MultibodyPlant<double>::CalcContactResults (libdrake.so)")
    assert sample_part(frames) == "Python: TactilePads"


def test_another_python_system_that_an_eval_runs_owns_its_own_samples():
    frames = _stack("PadFilms._update (tegrasp_drake/simulation/pad_vibration_sensor.py:262)",
                    "0x7f953f127206 (pydrake/systems/framework.so)",
                    "drake::systems::OutputPort<double>::Eval (libdrake.so)",
                    "PadNormalForces._calc (tegrasp_drake/simulation/pad_normal_forces.py:90)",
                    "normal_force (tegrasp_drake/simulation/pad_normal_forces.py:40)")
    assert sample_part(frames) == "Python: PadNormalForces"


def test_cpp_samples_go_to_the_first_matching_part():
    step = "drake::multibody::MultibodyPlant<double>::CalcStepUnrestricted (libdrake.so)"
    assert sample_part(_stack(step, "drake::geometry::internal::ComputeContactSurfaces<double>"
                              " (libdrake.so)")) == "plant step: contact surfaces"
    assert sample_part(_stack(step, "drake::multibody::contact_solvers::internal::"
                              "SapSolver<double>::SolveWithGuess (libdrake.so)")) \
        == "plant step: SAP solve"
    assert sample_part(_stack(step)) == "plant step: other"
    assert sample_part(_stack("drake::systems::VectorLogSink<double>::WriteToLog")) == "loggers"
    # Differential IK's own plant is multibody code too: the IK names the part.
    assert sample_part(_stack("drake::multibody::DifferentialInverseKinematicsIntegrator"
                              "::Integrate", "drake::multibody::MultibodyPlant<double>::"
                              "CalcJacobianSpatialVelocity")) == "differential IK"
    assert sample_part(_stack("drake::systems::DependencyTracker::NotifySubscribers")) \
        == FRAMEWORK


def test_the_innermost_compiled_drake_system_owns_a_sample_outside_python_and_the_step():
    update = "drake::systems::LeafSystem<double>::DispatchDiscreteVariableUpdateHandler"
    symbolic = "drake::systems::SymbolicVectorSystem<double>::EvaluateWithContext (libdrake.so)"
    gain = "drake::systems::AffineSystem<double>::CalcOutputY (libdrake.so)"
    accelerometer = "drake::systems::sensors::Accelerometer<double>::CalcOutput (libdrake.so)"
    outputs = "drake::multibody::MultibodyPlant<double>::CalcBodySpatialAccelerationsOutput"
    assert sample_part(_stack(update, symbolic, gain)) == \
        "Drake system: LinearSystem, MatrixGain"
    assert sample_part(_stack(update, symbolic)) == "Drake system: SymbolicVectorSystem"
    # The plant outputs an Eval computes count with the system that asked for them.
    assert sample_part(_stack(update, gain, accelerometer, outputs)) == \
        "Drake system: Accelerometer"
    assert sample_part(_stack(outputs)) == "plant outputs read by Drake systems"
    # Framework classes are not systems of a chain.
    assert sample_part(_stack("drake::systems::Diagram<double>::CalcOutput")) == FRAMEWORK


def test_samples_outside_advance_to_and_plain_functions_are_not_systems():
    assert sample_part(["<module> (<string>:4)", "build (tegrasp_drake/x.py:1)"]) == ""
    # A module-level function of the package is not a system's callback: the sample is
    # sorted by its C++ frames.
    assert sample_part(_stack("helper (tegrasp_drake/x.py:3)")) == FRAMEWORK


def test_raw_lines_are_summed_per_part_and_malformed_lines_skipped():
    python = ";".join(_stack("PadFilms._update (tegrasp_drake/simulation/pad_vibration_"
                             "sensor.py:272)"))
    text = "\n".join([f"{python} 3", f"{python} 4", ";".join(_stack()) + " 2",
                      "<module> (<string>:1) 9", "garbage", ""])
    assert parts_from_raw(text) == {"Python: PadFilms": 7, FRAMEWORK: 2}


def test_repeats_and_rate_are_checked_in_one_line_before_any_profiling(capsys):
    for argv, words in ((["--repeats", "3"], "profiles one trial a run"),
                        (["--rate", "0"], "at least 1 sample per second")):
        with pytest.raises(SystemExit):
            main(argv)
        assert words in capsys.readouterr().err
