"""Draw one 2F-85 finger's linkage at open, mid and closed, with the pad centre's path.

    python analysis/linkage_figure.py docs/figures/finger_linkage.png

The closed form of robotiq/linkage.py: joints A-E, the driver (A-B), coupler (B-C),
follower (C-D, carrying the pad) and spring link (E-D), the pad face, its centre's path over
the stroke, and the flip height at 25 N (a contact below it lifts B off its pin).
"""

import math
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tegrasp_drake.commands.script_output import run_script, script_parser  # noqa: E402
from tegrasp_drake.figures.figure_files import save_figure  # noqa: E402
from tegrasp_drake.rig.files import UserPathError  # noqa: E402
from tegrasp_drake.robotiq import linkage  # noqa: E402
from tegrasp_drake.rig.tactile_fingertip import PAD_LENGTH  # noqa: E402


def draw(ax, theta: float, color: str, label: str) -> None:
    pose = linkage.finger_pose(theta)
    a, e = linkage.A, linkage.E
    for p, q, width in ((a, pose.b, 3), (pose.b, pose.c, 3), (pose.c, pose.d, 4),
                        (e, pose.d, 2)):
        ax.plot(*np.transpose([p, q]) * 1000, color=color, lw=width, solid_capstyle="round")
    pad = linkage.pad_center(theta)
    face = np.array([[pad[0], pad[1] - PAD_LENGTH / 2], [pad[0], pad[1] + PAD_LENGTH / 2]])
    ax.plot(*face.T * 1000, color=color, lw=6, alpha=0.5)
    # The follower's rigid part from D to the pad.
    ax.plot(*np.transpose([pose.d, pad + [0.004, -PAD_LENGTH / 2]]) * 1000, color=color, lw=1,
            ls=":")
    flip = pad[1] + linkage.flip_height(theta, 25.0)
    ax.plot([pad[0] * 1000 - 4, pad[0] * 1000 + 4], [flip * 1000] * 2, color=color, lw=1)
    ax.plot(*pad * 1000, "o", color=color, ms=4,
            label=f"{label}: opening {abs(2 * linkage.half_opening(theta)) * 1000:.0f} mm, "
                  f"pad +{linkage.pad_travel(theta) * 1000:.1f} mm")


def main(argv=None) -> int:
    parser = script_parser("linkage_figure", __doc__)
    parser.add_output("out", type=pathlib.Path, figure=True, help="the figure to write (.png, "
                      ".pdf or .svg); an existing figure only with --overwrite")
    out = parser.parse_args(argv).out
    fig, ax = plt.subplots(figsize=(6.4, 6.4))
    for theta, color, label in ((0.0, "tab:blue", "open"),
                                (linkage.driver_angle(0.0225), "tab:orange", "mid"),
                                (linkage.THETA_PADS_MEET, "tab:green", "closed")):
        draw(ax, theta, color, label)
    path = np.array([linkage.pad_center(t)
                     for t in np.linspace(0.0, linkage.THETA_PADS_MEET, 60)])
    ax.plot(*path.T * 1000, color="k", lw=1, ls="--", label="pad centre's path")
    for name in "ABCDE":
        p = getattr(linkage, name) * 1000
        ax.annotate(name, p, textcoords="offset points", xytext=(4, -10), fontsize=9)
    ax.plot(0, 0, alpha=0)
    ax.axvline(0, color="0.6", lw=0.8)
    ax.set_xlabel("y along the stroke [mm] (0: the grasp axis)")
    ax.set_ylabel("z along the approach axis [mm] (0: the mounting face)")
    ax.set_title("2F-85 finger, closed form. Short bars: the flip height at 25 N", fontsize=10, y=-0.16)
    ax.set_aspect("equal")
    ax.set_xlim(-5, 80)
    ax.set_ylim(45, 160)
    ax.legend(fontsize=8, loc="lower left", bbox_to_anchor=(0.0, 1.06), ncol=1)
    try:
        save_figure(fig, out, dpi=130, tight=True)
    except UserPathError as error:
        raise SystemExit(f"linkage_figure: {error}") from None
    print(f"wrote {out} ({math.degrees(linkage.THETA_PADS_MEET):.1f} deg to close)")
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "linkage_figure"))
