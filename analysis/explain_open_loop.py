"""Why the open-loop grasp succeeds at the paper's misplacements in this simulation: runs the
ideal scripted grasp of each built-in object at the four corner markers (+-1 cm normal to
the palm, +-1.5 cm along the stroke), plots where the object goes and how it tilts, and
prints the margins.

    python analysis/explain_open_loop.py OUT.png [--workers 2]
"""

import concurrent.futures
import sys

import numpy as np

CORNERS_M = [(dx, dy) for dx in (-0.010, 0.010) for dy in (-0.015, 0.015)]
OBJECTS = ("box", "thick_cylinder", "thin_cylinder")


def run_corner(job):
    """(object, (dx, dy)) -> (times, object xyz [m], tilt [deg], result)."""
    from tegrasp_drake.scenario.grasp_outcome import tilt_deg
    from tegrasp_drake.scenario.scenario import LoadScenario
    from tegrasp_drake.runs.trial import run_trial
    name, (dx, dy) = job
    scenario = LoadScenario(name=name, overrides=[f"placement.offset=[{dx},{dy}]",
                                                  "controller.name=open_loop"])
    trial = run_trial(scenario)
    log = trial.log
    tilt = np.array([tilt_deg(row) for row in log.object_state])
    return name, (dx, dy), log.t_slow, log.object_state[:, 4:7], tilt, trial.result, \
        list(scenario.placement.expected_xy)


def main(argv=None) -> int:
    from tegrasp_drake.commands.script_output import script_parser
    parser = script_parser("explain_open_loop", __doc__)
    parser.add_output("out", figure=True, help="the figure to write (.png, .pdf or .svg); an "
                      "existing figure only with --overwrite")
    parser.add_workers()
    args = parser.parse_args(argv)
    from tegrasp_drake.figures.figure_files import save_figure
    from tegrasp_drake.rig.files import UserPathError
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    jobs = [(name, corner) for name in OBJECTS for corner in CORNERS_M]
    with concurrent.futures.ProcessPoolExecutor(args.workers) as pool:
        runs = list(pool.map(run_corner, jobs))
    figure, axes = plt.subplots(3, len(OBJECTS), figsize=(15, 10), sharex=True)
    for column, name in enumerate(OBJECTS):
        for run_name, (dx, dy), t, xyz, tilt, result, expected in runs:
            if run_name != name:
                continue
            label = f"dx {1e3 * dx:+.0f} mm, dy {1e3 * dy:+.0f} mm"
            lift = next(e["t"] for e in result["transitions"] if e["to"] == "Lift")
            at_lift = np.searchsorted(t, lift)
            axes[0, column].plot(t, 1e3 * (xyz[:, 1] - expected[1]), label=label)
            axes[1, column].plot(t, 1e3 * (xyz[:, 0] - expected[0]), label=label)
            axes[2, column].plot(t, tilt, label=label)
            print(f"{name:15s} {label}: at Lift y {1e3 * (xyz[at_lift, 1] - expected[1]):+6.1f} "
                  f"mm, x {1e3 * (xyz[at_lift, 0] - expected[0]):+6.1f} mm, tilt "
                  f"{tilt[at_lift]:5.2f} deg; max tilt before Unload "
                  f"{tilt[:np.searchsorted(t, lift + 6.0)].max():5.2f} deg; final tilt "
                  f"{result['final_tilt_deg']:5.2f} deg; hold {result['hold_success']}, "
                  f"unload {result['unload_success']}")
        axes[0, column].set_title(f"{name}: open loop at the corner markers")
        axes[0, column].set_ylabel("object y - expected (along the stroke) [mm]")
        axes[1, column].set_ylabel("object x - expected (normal to the palm) [mm]")
        axes[2, column].set_ylabel("tilt from upright [deg]")
        axes[2, column].set_xlabel("time [s]")
        for row in axes[:, column]:
            row.grid(alpha=0.3)
        axes[0, column].legend(fontsize=8)
    figure.tight_layout()
    try:
        save_figure(figure, args.out, dpi=110)
    except UserPathError as error:
        raise SystemExit(f"explain_open_loop: {error}") from None
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    from tegrasp_drake.commands.script_output import run_script
    sys.exit(run_script(main, "explain_open_loop"))
