"""`tegrasp demo`: the README's main job, a closed-loop tactile-event grasp on the default
scenario, with its timeline, success and a Fig. 9-like figure (`--controller open_loop`: the
ideal scripted grasp of Sec. III-A). It replaces the last demo in out/demo."""

import argparse

from tegrasp_drake.commands import trial

DESCRIPTION = """\
The README's demonstration: the paper's memorized-trigger grasp of the box on the default
scenario (the box on its marker), closed loop. Prints the state timeline (each transition's
trigger and its four correlation scores), hold and unload success and the real-time factor;
writes out/demo/states.png (like the paper's Fig. 9), signals.png (Fig. 5a-b), the log
trial.npz and result.json, replacing the last demo's. It takes the options of
`tegrasp trial`, which runs any scenario and keeps every run."""

EPILOG = """\
examples:
  tegrasp demo                             # the closed-loop grasp; figures in out/demo
  tegrasp demo --controller open_loop      # the ideal scripted grasp of Sec. III-A
  tegrasp demo --meshcat                   # watch it in Meshcat; Enter to quit"""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "demo", help="run the closed-loop tactile-event grasp on the default scenario",
        description=DESCRIPTION, epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    trial.add_trial_arguments(parser, out_help="folder for the demo (default: out/demo, "
                              "replaced by each demo); a DIR that holds a run is refused "
                              "unless --overwrite")
    parser.set_defaults(func=trial.run, default_out="out/demo", replace_default_out=True)
