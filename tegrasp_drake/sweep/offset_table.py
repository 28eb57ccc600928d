"""Success per placement offset: Table I split by marker, so a reader sees where each
controller fails. One table per controller: a row per marker (nominal dx normal to the
palm, dy along the stroke, mm), a (~Hold, ~Unload) column pair per object."""

from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controller_title
from tegrasp_drake.sweep.records import record_result
from tegrasp_drake.sweep.spec import BUILTIN_OBJECTS
from tegrasp_drake.sweep.table import (markdown_and_csv_starts, ordered_names, succeeded,
                                       write_markdown_and_csv)

PHASES = ("hold", "unload")


@dataclass(frozen=True)
class OffsetRow:
    controller: str
    object_name: str
    marker_dx_mm: float
    marker_dy_mm: float
    trials: int
    hold_successes: int
    unload_successes: int
    errors: int


def offset_rows(records) -> list[OffsetRow]:
    """One row per (controller, object, marker), ordered by controller, object, dx, dy."""
    counts = defaultdict(lambda: {"trials": 0, "hold": 0, "unload": 0, "errors": 0})
    for record in records:
        trial = record["trial"]
        key = (trial["controller"], trial["object_name"],
               round(1000.0 * trial["marker_dx_m"], 3), round(1000.0 * trial["marker_dy_m"], 3))
        count = counts[key]
        if record["status"] != "ok":
            count["errors"] += 1
            continue
        count["trials"] += 1
        for phase in PHASES:
            count[phase] += succeeded(record_result(record), phase)
    controllers = ordered_names({k[0] for k in counts}, CONTROLLER_NAMES)
    objects = ordered_names({k[1] for k in counts}, BUILTIN_OBJECTS)
    rows = []
    for key in sorted(counts, key=lambda k: (controllers.index(k[0]), objects.index(k[1]),
                                             k[2], k[3])):
        c = counts[key]
        rows.append(OffsetRow(*key, trials=c["trials"], hold_successes=c["hold"],
                              unload_successes=c["unload"], errors=c["errors"]))
    return rows


def _cell(successes: int, trials: int) -> str:
    return f"{successes}/{trials}" if trials else "–"


OFFSET_TITLE = "# Success per placement offset"
OFFSET_HEADER = ["controller", "object", "marker_dx_mm", "marker_dy_mm", "trials",
                 "hold_successes", "unload_successes", "errors"]


def offset_table_starts() -> dict[str, str]:
    """success_by_offset.md and .csv, and how each starts (report_files)."""
    return markdown_and_csv_starts("success_by_offset", OFFSET_TITLE, OFFSET_HEADER)


def offset_markdown(rows: list[OffsetRow]) -> str:
    lines = [OFFSET_TITLE, "",
             "Each marker's nominal offset from the expected position (dx normal to the palm, "
             "dy along the stroke; every attempt adds jitter), and per object the trials that "
             "held the object 3 s (~Hold) and held then placed it upright (~Unload), as "
             "successes/trials of the finished trials. (0, 0) is the well-placed marker."]
    objects = ordered_names({row.object_name for row in rows}, BUILTIN_OBJECTS)
    for controller in ordered_names({row.controller for row in rows}, CONTROLLER_NAMES):
        mine = [row for row in rows if row.controller == controller]
        markers = sorted({(row.marker_dx_mm, row.marker_dy_mm) for row in mine})
        by_key = {(row.object_name, row.marker_dx_mm, row.marker_dy_mm): row for row in mine}
        header = ["dx [mm]", "dy [mm]"]
        for object_name in objects:
            header += [f"{object_name} ~Hold", f"{object_name} ~Unload"]
        header.append("errors")
        lines += ["", f"## {controller_title(controller)}", "",
                  "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        for dx, dy in markers:
            cells = [f"{dx:+g}" if dx else "0", f"{dy:+g}" if dy else "0"]
            errors = 0
            for object_name in objects:
                row = by_key.get((object_name, dx, dy))
                if row is None:
                    cells += ["–", "–"]
                    continue
                cells += [_cell(row.hold_successes, row.trials),
                          _cell(row.unload_successes, row.trials)]
                errors += row.errors
            cells.append(str(errors))
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def write_offset_table(records, out_dir) -> list[Path]:
    """Writes `success_by_offset.md` and `.csv` into `out_dir`; returns their paths."""
    rows = offset_rows(records)
    csv_rows = [[row.controller, row.object_name, f"{row.marker_dx_mm:g}",
                 f"{row.marker_dy_mm:g}", row.trials, row.hold_successes,
                 row.unload_successes, row.errors] for row in rows]
    return write_markdown_and_csv(out_dir, "success_by_offset", OFFSET_TITLE,
                                  offset_markdown(rows), OFFSET_HEADER, csv_rows)
