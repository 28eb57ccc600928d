"""`tegrasp plot events`: a figure like the paper's Fig. 5c of every memorized event."""

from tegrasp_drake import paths


def register(subparsers) -> None:
    parser = subparsers.add_parser("plot", help="figures: `tegrasp plot events`")
    parser.add_argument("what", choices=("events",))
    parser.add_argument("--events", default=None, help="events folder (default: the package's)")
    parser.add_argument("--out", default="out/memorized_events.png")
    parser.set_defaults(func=run)


def run(args) -> int:
    import pathlib

    from tegrasp_drake.events import MemorizedEventError, load_all_memorized_events
    from tegrasp_drake.events.plot import plot_memorized_events
    try:
        events = load_all_memorized_events(args.events or paths.events_dir())
    except MemorizedEventError as e:
        raise SystemExit(f"tegrasp: error: {e}") from None
    pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    print(plot_memorized_events(events, args.out))
    return 0
