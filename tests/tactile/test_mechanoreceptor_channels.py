import numpy as np
import pytest

from tegrasp_drake.tactile.mechanoreceptor_channels import MakeMechanoreceptorChannels


def _evaluate(left_taxels, right_taxels, left_acceleration, right_acceleration):
    system = MakeMechanoreceptorChannels()
    context = system.CreateDefaultContext()
    system.GetInputPort("left_taxel_forces").FixValue(context, left_taxels)
    system.GetInputPort("right_taxel_forces").FixValue(context, right_taxels)
    system.GetInputPort("left_pad_acceleration").FixValue(context, left_acceleration)
    system.GetInputPort("right_pad_acceleration").FixValue(context, right_acceleration)
    return {name: system.GetOutputPort(name).Eval(context) for name in ("sa", "ra", "channels")}


def test_ports_have_stable_names_and_sizes():
    system = MakeMechanoreceptorChannels()
    assert [system.get_input_port(i).get_name() for i in range(4)] == [
        "left_taxel_forces", "right_taxel_forces", "left_pad_acceleration",
        "right_pad_acceleration"]
    assert system.GetOutputPort("channels").size() == 4


def test_eq1_sums_each_fingers_twelve_normal_forces():
    out = _evaluate(np.arange(12.0), np.full(12, 0.5), np.zeros(3), np.zeros(3))
    np.testing.assert_allclose(out["sa"], [66.0, 6.0])


def test_eq2_is_the_magnitude_of_the_vibration_vector():
    out = _evaluate(np.zeros(12), np.zeros(12), [3.0, 4.0, 0.0], [-1.0, 2.0, -2.0])
    np.testing.assert_allclose(out["ra"], [5.0, 3.0])


def test_channels_are_in_the_documented_order():
    out = _evaluate(np.ones(12), np.full(12, 2.0), [0.0, 0.0, 7.0], [0.0, 9.0, 0.0])
    np.testing.assert_allclose(out["channels"], [12.0, 24.0, 7.0, 9.0])


def test_the_channels_equal_numpys_sum_and_norm_bit_for_bit():
    # Eq. 1-2 are computed without np.sum's and np.linalg.norm's wrappers; same numbers.
    import numpy as np
    from tegrasp_drake.tactile.mechanoreceptor_channels import rapidly_adapting, slowly_adapting
    rng = np.random.default_rng(5)
    for _ in range(2000):
        forces = rng.normal(size=12) * 10.0 ** rng.uniform(-3, 2)
        vibration = rng.normal(size=3) * 10.0 ** rng.uniform(-3, 3)
        assert slowly_adapting(forces) == float(np.sum(forces))
        assert rapidly_adapting(vibration) == float(np.linalg.norm(vibration))


def test_channels_follow_the_taxels_and_the_vibration_when_either_changes_alone():
    # channels reads SA from the sa port's cache: a new taxel sample must reach it, and a
    # new vibration sample alone must not leave a stale SA or RA.
    system = MakeMechanoreceptorChannels()
    context = system.CreateDefaultContext()
    ports = {name: system.GetInputPort(name) for name in (
        "left_taxel_forces", "right_taxel_forces", "left_pad_acceleration",
        "right_pad_acceleration")}
    rng = np.random.default_rng(11)
    values = {name: rng.normal(size=port.size()) for name, port in ports.items()}
    for name, port in ports.items():
        port.FixValue(context, values[name])
    channels = system.GetOutputPort("channels")
    for step in range(40):
        name = list(ports)[step % 4]
        values[name] = rng.normal(size=ports[name].size())
        ports[name].FixValue(context, values[name])
        expected = [float(np.sum(values["left_taxel_forces"])),
                    float(np.sum(values["right_taxel_forces"])),
                    float(np.linalg.norm(values["left_pad_acceleration"])),
                    float(np.linalg.norm(values["right_pad_acceleration"]))]
        # The compiled RA sums x*x + y*y + z*z in order; numpy's norm may fuse or reorder
        # (its BLAS and the CPU decide): equal to a few units in the last place. A stale
        # channel would differ in the leading digits.
        assert channels.Eval(context).tolist() == pytest.approx(expected, rel=1e-14, abs=0.0)
