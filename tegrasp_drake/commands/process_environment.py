"""What the command line sets up in its own process before any command runs, so that the
user's environment does not surface as an internal error or as lines of another library:

- Python's UTF-8 mode under a locale whose encoding is not UTF-8 (`LC_ALL=C`, with
  `PYTHONUTF8=0` so Python does not turn it on itself): pydrake reads its own files with the
  locale's encoding and fails to import under ASCII. The process runs itself again with
  `-X utf8` (PEP 540) before pydrake is imported; if it cannot, one line says what to set.
- MPLBACKEND checked: matplotlib refuses to import under a backend name it does not know,
  although the figures are drawn into files (Agg) whatever it names; one line says so.
- A private matplotlib configuration folder when matplotlib's own (under $XDG_CONFIG_HOME or
  ~/.config, and its cache under $XDG_CACHE_HOME or ~/.cache) cannot be written, e.g. HOME=/proc:
  matplotlib would make a temporary one itself but says so in two lines of warnings first.
  An MPLCONFIGDIR that names no folder this user can write (a file) gets the same, with one
  `tegrasp: warning:` line. The folder is removed when the process ends. Nothing is made
  to find out: a home folder (or XDG folder) that does not exist counts as not writable and
  stays absent; under an existing one, matplotlib makes its own folders, as without tegrasp."""

import atexit
import codecs
import importlib
import locale
import os
import pathlib
import shutil
import sys
import tempfile

from tegrasp_drake.commands.error_boundary import ERROR_LEAD
from tegrasp_drake.rig.echo import shown


def locale_is_utf8() -> bool:
    """Whether text files are read as UTF-8: UTF-8 mode, or a locale whose encoding is UTF-8."""
    if sys.flags.utf8_mode:
        return True
    try:
        return codecs.lookup(locale.getpreferredencoding(False)).name == "utf-8"
    except LookupError:
        return False


def run_in_utf8_mode() -> None:
    """Replaces this process by itself in UTF-8 mode when the locale is not UTF-8 (module
    docstring); SystemExit with one line to set LANG=C.UTF-8 when that cannot be done. Call
    it before pydrake is imported, from the command line's entry point only."""
    if locale_is_utf8():
        return
    original = list(getattr(sys, "orig_argv", []))
    if original and sys.executable:
        try:
            os.execv(sys.executable, [sys.executable, "-X", "utf8", *original[1:]])
        except OSError:
            pass
    raise SystemExit(f"{ERROR_LEAD}the locale's text encoding is "
                     f"{locale.getpreferredencoding(False)}, and Drake needs UTF-8; set "
                     "LANG=C.UTF-8 (and unset LC_ALL, or set it to C.UTF-8) or PYTHONUTF8=1")


def _writable_folder(folder: pathlib.Path, base: pathlib.Path | None = None) -> bool:
    """Whether `folder` is a folder this user writes, or one matplotlib could make as one
    (its nearest existing ancestor a folder this user can make folders in), as matplotlib
    asks; nothing is left made here. With `base` (the home folder, or the XDG folder that holds `folder`), a `base`
    that does not exist counts as not writable: a missing home folder is never made, and
    matplotlib's folders then go to the temporary folder. Under an existing `base`,
    matplotlib makes its own folder (e.g. ~/.config/matplotlib) as it would without tegrasp."""
    if base is not None and not base.is_dir():
        return False
    path = folder
    while not os.path.lexists(path) and path != path.parent:
        path = path.parent
    if not (path.is_dir() and os.access(path, os.W_OK | os.X_OK)):
        return False
    if path == folder:
        return True
    try:  # access() says yes to root where no folder can be made (/proc): try, leave nothing
        os.rmdir(tempfile.mkdtemp(prefix=".tegrasp-probe-", dir=path))
    except OSError:
        return False
    return True


def _home_folder(variable: str, fallback: str) -> tuple[pathlib.Path, pathlib.Path]:
    """The folder an XDG `variable` names, or the home folder's `fallback` under it, with
    the folder that must already exist for it to be used (the named one, or the home)."""
    chosen = os.environ.get(variable, "").strip()
    if chosen:
        return pathlib.Path(chosen), pathlib.Path(chosen)
    home = pathlib.Path.home()
    return home / fallback, home


def _matplotlib_folders_usable() -> bool:
    """Whether matplotlib's own folders can be written, checked without making any:
    MPLCONFIGDIR when it is set (a warning in the package's one-line form when it cannot),
    else its configuration and cache folders under the home folder (or the XDG folders),
    which must exist."""
    chosen = os.environ.get("MPLCONFIGDIR")
    if chosen:
        if _writable_folder(pathlib.Path(chosen)):
            return True
        print(f"tegrasp: warning: MPLCONFIGDIR={shown(chosen)} is not a folder this user can "
              "write; matplotlib's settings and cache go to a temporary folder", file=sys.stderr)
        return False
    try:
        folders = [_home_folder(variable, fallback) for variable, fallback in
                   (("XDG_CONFIG_HOME", ".config"), ("XDG_CACHE_HOME", ".cache"))]
    except RuntimeError:  # no home folder at all
        return False
    return all(_writable_folder(folder / "matplotlib", base) for folder, base in folders)


def private_matplotlib_config() -> None:
    """Points MPLCONFIGDIR at a temporary folder (removed at exit) when matplotlib's folders
    cannot be written (module docstring): matplotlib would make one itself, with two lines
    of its own warnings."""
    if _matplotlib_folders_usable():
        return
    try:
        folder = tempfile.mkdtemp(prefix="tegrasp-matplotlib-")
    except OSError:
        return  # matplotlib says why, as it would have
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    os.environ["MPLCONFIGDIR"] = folder


def check_matplotlib_backend() -> None:
    """SystemExit with one line when MPLBACKEND names no backend matplotlib knows (module
    docstring); matplotlib is imported here only when the variable is set."""
    backend = os.environ.get("MPLBACKEND")
    if backend is None:
        return
    try:
        importlib.import_module("matplotlib")  # it reads MPLBACKEND as it is imported
    except ValueError:
        raise SystemExit(f"{ERROR_LEAD}MPLBACKEND={shown(backend)} is not a matplotlib "
                         "backend; unset it (tegrasp draws its figures into files, with Agg) "
                         "or give one, e.g. MPLBACKEND=agg") from None
