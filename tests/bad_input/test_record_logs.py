"""A trial log read for a sweep record (analysis/rejudge_from_logs.py, hold_creep.py, the
missed-event report) is found by its name (trial_log_name of the record's trial), so a log
copied or renamed onto another record's name would be judged as that record's trial. Each
is checked to be the record's trial: its controller, object, seed and placement offset (what
its metadata and the record both hold); another trial's is refused naming the log, the
record and the field."""

import numpy as np
import pytest

from tegrasp_drake.scenario.scenario import scenario_to_yaml
from tegrasp_drake.scenario.trial_log_file import TrialLog, TrialLogError, logger_periods
from tegrasp_drake.sweep.records import load_records
from tegrasp_drake.sweep.runner import run_sweep
from tegrasp_drake.sweep.spec import SweepSpec
from tegrasp_drake.sweep.trial_function import (load_record_log, scenario_from_trial_spec,
                                                trial_log_name)
from tests.analysis_script import load_analysis_script
from tests.fake_trials import fake_trial


def _log_of(trial: dict, **meta) -> TrialLog:
    """A quiet one-second log of `trial` (its scenario and controller in its metadata)."""
    scenario = scenario_from_trial_spec(trial)
    bases = {name: np.arange(0.0, 1.0, period)
             for name, period in logger_periods(scenario).items()}

    def zeros(name, width):
        return np.zeros((len(bases[name]), width))
    arm_q = zeros("t_slow", 6)
    arm_q[:, 1:3] = [3.0, 1.0]  # joints 2 and 3 within the JACO2's limits
    object_state = zeros("t_slow", 13)
    object_state[:, 0] = 1.0  # the identity orientation
    return TrialLog(t_sa=bases["t_sa"], taxels=zeros("t_sa", 24), true_taxels=zeros("t_sa", 24),
                    t_ra=bases["t_ra"], channels=zeros("t_ra", 4),
                    pad_acceleration=zeros("t_ra", 6), t_slow=bases["t_slow"], arm_q=arm_q,
                    arm_q_desired=arm_q, gripper_command=zeros("t_slow", 3),
                    gripper_status=zeros("t_slow", 8), phase=np.zeros(len(bases["t_slow"])),
                    object_state=object_state,
                    meta={"controller": trial["controller"],
                          "scenario": scenario_to_yaml(scenario), **meta})


@pytest.fixture(scope="module")
def sweep_with_logs(tmp_path_factory):
    """A sweep's records (two controllers, two markers) and each trial's log, by its name."""
    folder = tmp_path_factory.mktemp("sweep")
    spec = SweepSpec(objects=("box",), controllers=("open_loop", "heuristic"), attempts=1,
                     base_seed=652, grid=((0.0, 0.0), (0.0, 0.015)))
    run_sweep(spec, fake_trial, folder / "results", workers=1, progress=False)
    records = load_records(folder / "results").records
    for record in records.values():
        _log_of(record["trial"]).save(folder / "logs" / trial_log_name(record["trial"]))
    return folder, records


def _swapped(folder, records, first: str, second: str):
    """The logs folder with the logs of records `first` and `second` swapped."""
    logs = folder / "logs"
    paths = [logs / trial_log_name(records[i]["trial"]) for i in (first, second)]
    texts = [path.read_bytes() for path in paths]
    paths[0].write_bytes(texts[1])
    paths[1].write_bytes(texts[0])
    return paths


@pytest.mark.parametrize("other, words", [
    ("heuristic/box/m00/a0", ["its meta 'controller' is '", "but the record's trial's "
                                                            "controller is '"]),
    ("open_loop/box/m01/a0", ["its meta 'scenario' random_seed is",
                              "but the record's trial's seed is"]),
])
def test_rejudging_with_a_log_of_another_trial_is_refused(sweep_with_logs, tmp_path, capfd,
                                                          other, words):
    from tegrasp_drake.commands.script_output import run_script
    folder, records = sweep_with_logs
    paths = _swapped(folder, records, "open_loop/box/m00/a0", other)
    try:
        out = tmp_path / "rejudged"
        code = run_script(load_analysis_script("rejudge_from_logs").main, "rejudge_from_logs",
                          [str(folder / "results"), str(folder / "logs"), str(out)])
        captured = capfd.readouterr()
        message = captured.err
        assert code == 1 and message.count("\n") == 1, (code, captured)
        assert message.startswith("rejudge_from_logs: error: trial log '"), message
        named = [(path, trial_id) for path, trial_id in zip(paths, ("open_loop/box/m00/a0", other))
                 if f"trial log '{path}' is not the log of record trials/"
                    f"{trial_id.replace('/', '.')}.json" in message]
        assert named, message
        for expected in (*words, "give the --logs folder of the sweep that wrote the records"):
            assert expected in message, message
        assert "Traceback" not in message and not out.exists()
    finally:
        _swapped(folder, records, "open_loop/box/m00/a0", other)


@pytest.mark.parametrize("meta, words", [
    ({"controller": "heuristic"}, "meta 'controller' is 'heuristic'"),
])
def test_a_log_is_read_for_its_record_only(sweep_with_logs, meta, words):
    folder, records = sweep_with_logs
    record = records["open_loop/box/m01/a0"]
    path = folder / "logs" / trial_log_name(record["trial"])
    assert load_record_log(path, record).meta["controller"] == "open_loop"
    other = dict(record["trial"], seed=record["trial"]["seed"] + 1)
    bad = folder / "other.npz"
    _log_of(other).save(bad)
    with pytest.raises(TrialLogError, match="its meta 'scenario' random_seed is"):
        load_record_log(bad, record)
    _log_of(record["trial"], **meta).save(bad)
    with pytest.raises(TrialLogError, match=words):
        load_record_log(bad, record)
    moved = dict(record["trial"], marker_dy_m=0.0)
    _log_of(moved).save(bad)
    with pytest.raises(TrialLogError, match="placement.offset"):
        load_record_log(bad, record)
