"""The first-contact RA of the old accelerometer chain and of the PVDF film, side by side,
for the same pad strike at plant steps of 1, 0.5 and 0.25 ms; prints the contact peaks.

    python analysis/compare_ra_transients.py OUT.png [--speed 0.025]
"""

import sys

from tegrasp_drake.rig.number_text import number_option
from tegrasp_drake.commands.script_output import run_script, script_parser
from tegrasp_drake.figures.ra_transients import plot_ra_transients
from tegrasp_drake.rig.files import UserPathError
from tegrasp_drake.rig.ranges import Range
from tegrasp_drake.runs.pad_strike import PadStrikeConfig, run_pad_strike

TIME_STEPS = (1e-3, 5e-4, 2.5e-4)


def main(argv=None) -> int:
    parser = script_parser("compare_ra_transients", __doc__)
    parser.add_output("out", figure=True, help="the figure to write (.png, .pdf or .svg); an "
                      "existing figure only with --overwrite")
    parser.add_number("--speed", type=number_option, default=0.025, help="finger speed [m/s]",
                      allowed=Range(low=0.0, low_open=True, unit="m/s"))
    args = parser.parse_args(argv)
    strikes = {dt: run_pad_strike(PadStrikeConfig(time_step_s=dt, finger_speed_mps=args.speed))
               for dt in TIME_STEPS}
    for dt, strike in strikes.items():
        old = strike.accelerometer_ra(2.0)
        print(f"dt {1e3 * dt:g} ms: film peaks left {strike.contact_peak(0):.1f}, right "
              f"(own contact) {strike.contact_peak(1):.1f} m/s^2; accelerometer peak "
              f"{old[:, 0].max():.1f} m/s^2")
    try:
        print(f"wrote {plot_ra_transients(strikes, args.out)}")
    except UserPathError as error:
        raise SystemExit(f"compare_ra_transients: {error}") from None
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "compare_ra_transients"))
