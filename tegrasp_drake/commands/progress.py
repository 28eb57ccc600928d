"""A progress bar in simulated seconds, on stderr, only when stderr is a terminal: the runs
call `progress(t, end)` [s]; lines printed meanwhile are written above the bar."""

import sys

from tegrasp_drake.commands import output_streams

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
        """Shows `t` of `end` simulated seconds (the bar appears with the first call). Called
        from inside a simulation (Drake's monitor): a stream that refuses the bar stops the
        bar, never the run (`_stop_drawing`)."""
        if not self._enabled:
            return
        try:
            if self._bar is None:
                from tqdm import tqdm
                # Redrawn on every call: the runs call at most 4 times per simulated second.
                self._bar = tqdm(total=max(end, t), desc=self._description, file=self._stream,
                                 bar_format=BAR_FORMAT, dynamic_ncols=True, leave=False,
                                 mininterval=0.0, miniters=1)
            self._bar.total = max(end, t)
            self._bar.update(t - self._bar.n)
        except (OSError, ValueError) as error:  # ValueError: the stream was closed
            self._stop_drawing(error)

    def _stop_drawing(self, error: Exception) -> None:
        """No more bar after `error`: a refused write (a full disk, a hung-up terminal) is
        remembered for the command's end (output_streams) unless the guarded stream did; a
        closed pipe or stream is left for the end's flush to find."""
        self._enabled = False
        bar, self._bar = self._bar, None
        if bar is not None:
            bar.disable = True  # closing it draws nothing more
        if isinstance(error, OSError) and not isinstance(
                error, (BrokenPipeError, output_streams.OutputStreamError)):
            output_streams.note_failed_write(
                output_streams.OutputStreamError(output_streams.STANDARD_ERROR, error))

    def write(self, line: str) -> None:
        """Prints `line` on stdout, above the bar. Called from inside a run (a hardware run's
        monitor): a stream that refuses the bar's redraw stops the bar, as in `__call__`,
        and the line is printed alone (once: the bar's clear and redraw are on its stream, the
        line on stdout, the command's own output)."""
        self._on_bar_stream(lambda bar: bar.clear())
        print(line, flush=True)
        self._on_bar_stream(lambda bar: bar.refresh())

    def _on_bar_stream(self, draw) -> None:
        """`draw(bar)` if a bar is shown; a stream that refuses it stops the bar."""
        if self._bar is None:
            return
        try:
            draw(self._bar)
        except (OSError, ValueError) as error:  # ValueError: the stream was closed
            self._stop_drawing(error)

    def __exit__(self, *exc_info):
        if self._redirect is not None:
            self._redirect.__exit__(*exc_info)
            self._redirect = None
        if self._bar is not None:
            try:
                self._bar.close()  # clears the bar's line
            except (OSError, ValueError) as error:
                self._stop_drawing(error)
            self._bar = None
        return False
