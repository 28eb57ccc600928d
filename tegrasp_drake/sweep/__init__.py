"""The grasping experiment as a sweep: specs, durable trial records, runner, Table I.

- spec.py: the sweep specification, its validation and the trial list (paired seeds).
- spec_file.py: LoadSweepSpec, a spec from a YAML file.
- trial_function.py: one sweep trial turned into a scenario and run.
- runner.py: runs the trials in parallel, records each durably, resumes after a kill.
- records.py: one checksummed JSON record per trial.
- table.py: Table I and the trials' statistics (paired McNemar tests).
- summary.py: the results table of docs/results.md.
- offset_table.py: success per placement offset.
- failure_classes.py: why each failed trial failed.
- detection_report.py: detection quality per trigger, paired comparisons.
- missed_event_report.py: the memorized events that did not come, replayed.
The figures and the whole results folder: tegrasp_drake/reports.py."""

from tegrasp_drake.sweep.offset_table import offset_rows, write_offset_table
from tegrasp_drake.sweep.records import (
    LoadedRecords,
    RecordError,
    check_record,
    load_records,
    make_record,
    read_record,
    record_path,
    write_record,
)
from tegrasp_drake.sweep.runner import (
    BenchmarkRun,
    SweepError,
    SweepSummary,
    check_result,
    run_benchmark,
    run_sweep,
)
from tegrasp_drake.sweep.spec import (
    BUILTIN_OBJECTS,
    CONTROLLER_NAMES,
    Perturbation,
    RandomisationConfig,
    SweepSpec,
    TrialSpec,
    expand_trials,
    product_grid,
    user_object,
    validate_spec,
)
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tegrasp_drake.sweep.summary import (
    readme_with_summaries,
    summary_markdown,
    write_summary,
)
from tegrasp_drake.sweep.table import (
    PAPER_TABLE1,
    controller_statistics,
    paired_comparisons,
    table1_rows,
    write_statistics,
    write_table1,
)
