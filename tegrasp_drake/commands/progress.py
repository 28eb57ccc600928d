"""A progress bar in simulated seconds, on stderr, only when stderr is a terminal: the runs
call `progress(t, end)` [s]; lines printed meanwhile are written above the bar."""

import sys

BAR_FORMAT = ("{desc}: {percentage:3.0f}%|{bar}| {n:.1f}/{total:.1f} s simulated "
              "[{elapsed}<{remaining}]")


def progress_wanted(args, stream=None) -> bool:
    """A bar unless --quiet, and only on a terminal (never in a pipe, a file or CI)."""
    stream = stream if stream is not None else sys.stderr
    return not getattr(args, "quiet", False) and stream.isatty()


class SimulatedTimeBar:
    """`with SimulatedTimeBar("trial", enabled=...) as progress: run_trial(..., progress=progress)`.

    Disabled, it draws nothing and `write` is print."""

    def __init__(self, description: str, *, enabled: bool, stream=None):
        self._description = description
        self._enabled = enabled
        self._stream = stream if stream is not None else sys.stderr
        self._bar = None
        self._redirect = None

    def __enter__(self):
        if self._enabled:
            from tqdm.contrib.logging import logging_redirect_tqdm
            self._redirect = logging_redirect_tqdm()  # log records above the bar
            self._redirect.__enter__()
        return self

    def __call__(self, t: float, end: float) -> None:
        """Shows `t` of `end` simulated seconds (the bar appears with the first call)."""
        if not self._enabled:
            return
        if self._bar is None:
            from tqdm import tqdm
            # Redrawn on every call: the runs call at most 4 times per simulated second.
            self._bar = tqdm(total=max(end, t), desc=self._description, file=self._stream,
                             bar_format=BAR_FORMAT, dynamic_ncols=True, leave=False,
                             mininterval=0.0, miniters=1)
        self._bar.total = max(end, t)
        self._bar.update(t - self._bar.n)

    def write(self, line: str) -> None:
        """Prints `line` on stdout, above the bar."""
        if self._bar is None:
            print(line, flush=True)
        else:
            self._bar.write(line, file=sys.stdout)

    def __exit__(self, *exc_info):
        if self._redirect is not None:
            self._redirect.__exit__(*exc_info)
            self._redirect = None
        if self._bar is not None:
            self._bar.close()
            self._bar = None
        return False
