"""A figure, its file and its format: every figure module makes its Figure with `new_figure`
and writes it with `save_figure` as PNG, PDF or SVG (by suffix), with matplotlib's object API
(no pyplot, no global backend state)."""

import contextlib
import os
import pathlib

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.rig.files import (UserPathError, existing_file_head, existing_output_head,
                                     temporary_sibling, write_error_remedy)

FIGURE_FORMATS = ("png", "pdf", "svg")
# How a figure file of each format starts, as matplotlib writes it: PNG's signature (PNG
# specification, 5.2), PDF's header (ISO 32000-1, 7.5.2), and the XML declaration and
# document type matplotlib's SVG backend writes first (tests/figures/test_figure_files.py:
# what a killed write of each format left is removed, so each is matplotlib's start).
FIGURE_STARTS = {"png": b"\x89PNG\r\n\x1a\n", "pdf": b"%PDF-",
                 "svg": b'<?xml version="1.0" encoding="utf-8" standalone="no"?>\n'
                        b"<!DOCTYPE svg"}
PNG_DPI = 150  # about 1800 px across a 12 in figure: sharp on screens and in a PDF viewer


# The most lines a panel tells apart: matplotlib's default colour cycle (tab10) has ten
# colours; more would repeat colours and crowd the legend (and, past a few dozen, collapse
# the panels of a figure sized for them).
MAX_LINES_TOLD_APART = 10


class FigureFormatError(ValueError):
    """A figure file name whose suffix is not one of FIGURE_FORMATS."""


def new_figure(width_in: float, height_in: float):
    """An empty matplotlib Figure of that size [in], laid out by constrained layout."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # only when drawing
    from matplotlib.figure import Figure
    figure = Figure(figsize=(width_in, height_in), layout="constrained")
    FigureCanvasAgg(figure)
    return figure


def figure_path(folder, stem: str, figure_format: str) -> pathlib.Path:
    """folder / stem.figure_format, after checking the format."""
    if figure_format not in FIGURE_FORMATS:
        raise FigureFormatError(f"figure format '{figure_format}' is not one of "
                                f"{', '.join(FIGURE_FORMATS)}")
    return pathlib.Path(folder) / f"{stem}.{figure_format}"


def check_figure_path(path) -> pathlib.Path:
    """`path` as a Path if its suffix names a figure format; FigureFormatError if not."""
    path = pathlib.Path(path)
    if path.suffix.lstrip(".").lower() not in FIGURE_FORMATS:
        raise FigureFormatError(f"figure file '{path}' must end in one of "
                                f"{', '.join('.' + f for f in FIGURE_FORMATS)}")
    return path


def starts_as_figure(path) -> bool:
    """Whether the file at `path` starts as a figure of the format its suffix names does
    (FIGURE_STARTS): a figure this tool wrote, not the user's notes under a figure's name. Only
    the head is read; False when it cannot be."""
    path = check_figure_path(path)
    try:
        head = existing_file_head(path, 1024)
    except OSError:
        return False
    return head is not None and head.startswith(FIGURE_STARTS[path.suffix.lstrip(".").lower()])


def figure_replace_problem(path, *, overwrite: bool = True) -> str | None:
    """Why a figure may not be written at `path`, in words that follow it, or None: an existing
    file is replaced only when it is a figure of the format `path`'s suffix names (its first
    bytes are FIGURE_STARTS' for it: the user's notes saved as notes.png are not), and, unless
    `overwrite`, not at all. A symbolic link, dangling or not, is the user's and never
    replaced (a rename would put the figure in its place). Only the head is read."""
    path = check_figure_path(path)
    if os.path.islink(path):
        return ("is a symbolic link (a figure is written as a file, never over a link); give "
                "another file name, or remove the link yourself")
    head, problem = existing_output_head(
        path, 1024, "a figure belongs; give another file name, or move it away")
    if problem:
        return problem
    if head is None:
        return None
    figure_format = path.suffix.lstrip(".").lower()
    if not head:
        return (f"exists and is empty (0 bytes), not a .{figure_format} figure: a file there "
                f"is replaced only when it holds one (starting as the {figure_format.upper()} "
                "format does); give another file name, or remove it yourself")
    if not head.startswith(FIGURE_STARTS[figure_format]):
        return (f"exists and is not a .{figure_format} figure (its first bytes are not those of "
                f"the {figure_format.upper()} format); give another file name, or remove it "
                "yourself")
    if not overwrite:
        return ("exists (an earlier figure); pass --overwrite to replace it, or give a new "
                "file name")
    return None


def save_figure(figure, path, *, dpi: float = PNG_DPI, tight: bool = False) -> pathlib.Path:
    """Writes `figure` in the format `path`'s suffix names, at `dpi` (a PNG's pixels per inch),
    cropped to what it draws when `tight` (matplotlib's bbox_inches="tight": a legend or title
    placed outside the axes); returns the path, or UserPathError. What a write of this figure
    killed by SIGKILL left beside it is removed first. An existing file that is not a figure
    of that format is never replaced (figure_replace_problem)."""
    path = check_figure_path(path)
    figure_format = path.suffix.lstrip(".").lower()
    problem = figure_replace_problem(path)  # checked before the work too; here for every writer
    if problem:
        raise UserPathError(f"cannot write the figure {path}: it {problem}")
    made = [folder for folder in (path.parent, *path.parent.parents) if not folder.exists()]
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        # A full disk leaves the old figure whole.
        with temporary_sibling(path, start=FIGURE_STARTS[figure_format]) as temporary:
            figure.savefig(temporary, format=figure_format, dpi=dpi, metadata=_metadata(path),
                           bbox_inches="tight" if tight else None)
    except OSError as error:
        for folder in made:  # the folders made for it, innermost first, if still empty
            with contextlib.suppress(OSError):
                folder.rmdir()
        raise UserPathError(f"cannot write the figure {path}: {os_error_text(error)}; "
                            f"{write_error_remedy(error)}", error) from None
    return path


def _metadata(path: pathlib.Path) -> dict:
    # Reproducible vector files: no creation date (PDF) and no date (SVG).
    suffix = path.suffix.lower()
    if suffix == ".pdf":
        return {"CreationDate": None}
    if suffix == ".svg":
        return {"Date": None}
    return {}
