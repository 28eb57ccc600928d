"""The grasping experiment as a sweep: specs, durable trial records, runner, Table I.

`tegrasp sweep` runs every object at every marker of a grid, a few attempts each, once
per controller, with paired seeds; records each trial durably; resumes after a kill; and
writes Table I, statistics and success per offset (the figures and the whole results
folder: tegrasp_drake/reports.py).
"""

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
