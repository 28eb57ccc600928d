"""`tegrasp demo`: the README's main job, a closed-loop tactile-event grasp on the default
scenario (memorized events), with its timeline, success and a Fig. 9-like figure.

`--controller open_loop` runs the ideal scripted grasp of Sec. III-A instead.
"""

from tegrasp_drake.commands import trial


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "demo", help="run the closed-loop tactile-event grasp on the default scenario")
    trial.add_trial_arguments(parser, default_out="out/demo")
    parser.set_defaults(func=trial.run)
