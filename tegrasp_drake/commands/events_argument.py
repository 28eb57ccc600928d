"""The --events DIR option of the commands that read memorized events (trial, sweep,
hardware, plot, replay): one argparse type checks the folder before anything runs."""


def events_folder_option(text: str) -> str:
    """An argparse `type` for an --events folder to read: it must exist (the API's
    INPUT_FOLDER rule), checked before anything runs whatever the controller."""
    import argparse
    from tegrasp_drake.rig.api_boundary import INPUT_FOLDER
    from tegrasp_drake.rig.ranges import shorten
    problem = INPUT_FOLDER.problem(text)
    if problem:
        raise argparse.ArgumentTypeError(f"{shorten(repr(text))} {problem}")
    return text


def add_events_argument(parser, *, default: str = "$TEGRASP_EVENTS_DIR or "
                        "~/.local/share/tegrasp/events, then the package's") -> None:
    """--events DIR, a memorized events folder to read (events_folder_option)."""
    parser.add_argument("--events", metavar="DIR", default=None, type=events_folder_option,
                        help=f"memorized events folder to read (default: {default})")
