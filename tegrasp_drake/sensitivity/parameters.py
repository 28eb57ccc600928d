"""What was guessed: the scenario settings nobody published, each with a plausible range and
the argument for it (docs/model.md, "What was guessed"). The one place the sensitivity sweep
and the docs table read; `python -m tegrasp_drake.sensitivity.parameters --check|--write
docs/model.md` compares or replaces the table between `<!-- uncertain parameters -->` and
`<!-- end of uncertain parameters -->`."""

import dataclasses
import sys
import typing

from tegrasp_drake.rig.generated_table import GeneratedTable


@dataclasses.dataclass(frozen=True)
class UncertainParameter:
    """One guessed scenario setting: `key` its dotted name (`--set key=value`), `default`
    the scenario's value, [low, high] its plausible range in `unit`; `choices` the values a
    discrete setting takes, `step` the grid a continuous one must sit on (else 4
    significant digits); `partners` gives the assignments that go with a value (the
    settings that must follow it); `kind` says what the range rests on (datasheet, paper,
    handbook, closed-form estimate) and `source` the argument."""
    key: str
    default: float
    low: float
    high: float
    unit: str
    kind: str
    source: str
    choices: tuple[float, ...] = ()
    step: float = 0.0
    partners: typing.Callable[[float], tuple[str, ...]] | None = None
    log_scale: bool = False  # sampled uniformly in log(value): a range over a factor of several

    @property
    def name(self) -> str:
        """The key as a word of a folder's name: `gripper.position_loop_hz` ->
        `gripper_position_loop_hz`."""
        return self.key.replace(".", "_")

    def snapped(self, value: float) -> float:
        """`value` on the setting's own values: the nearest choice, or the nearest step."""
        if self.choices:
            return min(self.choices, key=lambda c: abs(c - value))
        if self.step:
            return round(round(value / self.step) * self.step, 9)
        return float(f"{value:.4g}")

    def at_fraction(self, u: float) -> float:
        """The value a fraction u in [0, 1) of the range stands for: equal shares of the
        choices for a discrete setting, else low + u (high - low) (low (high / low)^u on a log
        scale), snapped."""
        if self.choices:
            inside = [c for c in self.choices if self.low <= c <= self.high]
            return inside[min(int(u * len(inside)), len(inside) - 1)]
        if self.log_scale:
            return self.snapped(self.low * (self.high / self.low) ** u)
        return self.snapped(self.low + u * (self.high - self.low))

    def assignments(self, value: float) -> tuple[str, ...]:
        """The `--set` assignments that put the setting at `value`, its partners' after it."""
        extra = self.partners(value) if self.partners else ()
        return (f"{self.key}={_yaml_number(value)}",) + tuple(extra)


def _yaml_number(value: float) -> str:
    """`value` as YAML reads it back as the same number (YAML 1.1 needs a point in a float
    with an exponent: 1.0e-06, not 1e-06)."""
    if float(value).is_integer() and abs(value) < 1e6:
        return str(int(value)) if isinstance(value, int) else f"{float(value):.1f}"
    return f"{float(value):.6e}" if abs(value) < 1e-3 else repr(float(value))


def _decimation_rate(decimation: float) -> tuple[str, ...]:
    """The AD7147's frame rate follows its decimation (simulation/capacitive_taxels.py): the
    capacitive transducer's sample rate, as the data sheet's rates are quoted, is set with it."""
    return ({64: "tactile.sample_rate_hz=108.0", 128: "tactile.sample_rate_hz=54.0"}[
        int(decimation)],)


UNCERTAIN_PARAMETERS = (
    UncertainParameter(
        "gripper.pad_friction", 4.42, 0.91, 50.0, "", "handbook",
        "the pads' geometry coefficient, which Drake combines with an object's as "
        "2 mu_pad mu / (mu_pad + mu); the default gives the pad-object pairs 0.81 (cardboard) "
        "and 0.69 (plastic), the handbook's 0.80 and 0.70 for a fabric over a compliant "
        "backing on paper or polymer, 0.5-0.9 (\"Friction by material pair\"). "
        "At 0.91 the pairs are 0.60 and 0.53, a quarter lower; at 50 they are 0.89 and 0.74, "
        "the most the objects' own coefficients allow (twice theirs)", log_scale=True),
    UncertainParameter(
        "gripper.position_loop_hz", 60.0, 40.0, 100.0, "Hz", "closed-form estimate",
        "Robotiq publishes no loop gain. The 2F-85 takes commands at up to 200 Hz, and a "
        "position loop faster than half that follows no command faster (100 Hz); below "
        "40 Hz the locked drive, at the loop's stiffness J (2 pi f)^2, yields more than "
        "0.5 mm to a 50 N push (\"The drive\")"),
    UncertainParameter(
        "gripper.screw_efficiency", 0.35, 0.26, 0.47, "", "handbook",
        "a self-locking lead screw's forward efficiency tan(lead) / tan(lead + atan(mu)): "
        "0.26-0.47 for leads of 3-8 deg, steel on bronze (mu 0.15; Shigley's Mechanical "
        "Engineering Design, power screws)"),
    UncertainParameter(
        "arm.command_latency_s", 0.010, 0.005, 0.030, "s", "closed-form estimate",
        "Kinova publishes no figure: the JACO2's 10 ms DSP cycle of buffering (Kinova's "
        "kinova-ros README, 100 Hz velocity commands) plus about 1 ms of USB, at least half "
        "a cycle; 30 ms is a host that queues a command or two. On the plant's 1 ms steps",
        step=0.001),
    UncertainParameter(
        "tactile.capacitive.decimation", 64, 64, 128, "", "datasheet",
        "the AD7147's decimation, 64, 128 or 256 (Analog Devices AD7147 data sheet): 12 "
        "stages of 0.768 ms at 64, a frame of 9.2 or 18.4 ms (108 or 54 Hz), the noise "
        "falling as sqrt(64 / decimation); the paper does not give it. Not 256: its 27.1 Hz "
        "frames do not fill the paper's 0.5 s event window (Sec. III-A) a whole number of "
        "times (13.6). The sample rate is set with it", choices=(64, 128),
        partners=_decimation_rate),
    UncertainParameter(
        "vibration.film.film_charge_gain_c_per_m", 2.5e-5, 1e-6, 2.5e-5, "C/m", "datasheet",
        "G_Q = d31 E_f kappa A_f with d31 23 pC/N and E_f 2.5 GPa (TE Connectivity PVDF "
        "film data) and the bending strain of a free 6 x 45 mm cantilever's root, the "
        "upper bound (a free film; TE's LDT0-028K reads about 50 mV/g); a film bonded "
        "behind the fingertip's board strains 3-30 times less, about 1e-6 C/m "
        "(closed-form beam estimate; \"The film's sensitivity S and its range\")",
        log_scale=True),
    UncertainParameter(
        "tactile.pad_modulus_pa", 2.0e6, 5.0e5, 4.0e6, "Pa", "handbook",
        "the paper names no elastomer. Shore 13A-63A by Gent's relation E = 0.0981 (56 + "
        "7.62 S) / (0.1375 (254 - 2.54 S)) MPa (Gent 1958; 45A gives the default), the "
        "silicones and urethanes tactile pads are cast from (Dow's Sylgard 184 data sheet "
        "gives 43A, 1.9 MPa). "
        "Below 0.5 MPa a taxel's 10 N (the most one carries in the 25-100 N grasps) on its "
        "40 mm^2, 250 kPa, would compress the 4 mm pad by more than half; at 4 MPa the "
        "capacitive taxel's 4 counts of noise are 0.6 N, twice the 0.3 N contact threshold. "
        "The pads' contact, the taxels' compression and the film's impact stiffness E A / "
        "(t / 2) follow it", log_scale=True),
    UncertainParameter(
        "arm.start_position_bound_m", 0.0, 0.0, 0.005, "m", "closed-form estimate",
        "Kinova publishes no repeatability for the JACO2. The hand starts up to this far off "
        "its start pose along each axis (uniform, drawn from the trial's seed) while the "
        "controller plans from the nominal one: 5 mm is 0.4 deg of one joint over the "
        "0.7 m from the shoulder to the start pose, an arm that repeats a taught pose to a "
        "few millimetres. At 0 it starts there exactly", step=0.0005),
)


def parameter(key: str) -> UncertainParameter:
    """The table's parameter of `key`; KeyError naming the known keys."""
    for entry in UNCERTAIN_PARAMETERS:
        if entry.key == key or entry.name == key:
            return entry
    raise KeyError(f"'{key}' is not an uncertain parameter (known: "
                   f"{', '.join(p.key for p in UNCERTAIN_PARAMETERS)})")


def scenario_setting(scenario, key: str):
    """(value, declared Range or None) of the dotted setting `key` of `scenario`; KeyError
    when no field of that name exists."""
    from tegrasp_drake.rig.ranges import range_of
    node, field = scenario, None
    for part in key.split("."):
        if not dataclasses.is_dataclass(node):
            raise KeyError(f"'{key}': '{part}' is not a field of a section")
        field = next((f for f in dataclasses.fields(node) if f.name == part), None)
        if field is None:
            raise KeyError(f"'{key}': no field '{part}'")
        node = getattr(node, part)
    return node, range_of(field)


def _number(value: float, unit: str) -> str:
    """`value` as the table writes it: whole numbers below 1e5 whole, others in 4 significant
    digits with a short exponent (2e6, 2.5e-5)."""
    text = f"{value:.4g}" if not float(value).is_integer() or abs(value) >= 1e5 \
        else str(int(value))
    mantissa, exponent, power = text.partition("e")
    if exponent:
        text = f"{mantissa}e{int(power)}"
    return f"{text} {unit}".strip()


def parameters_markdown(parameters=UNCERTAIN_PARAMETERS) -> str:
    """The docs' table: setting, default, low, high, what the range rests on, the argument."""
    lines = ["| setting | default | low | high | rests on | argument for the range |",
             "|---|---|---|---|---|---|"]
    for p in parameters:
        lines.append(f"| `{p.key}` | {_number(p.default, p.unit)} | {_number(p.low, p.unit)} "
                     f"| {_number(p.high, p.unit)} | {p.kind} | {p.source} |")
    return "\n".join(lines) + "\n"


PARAMETERS_TABLE = GeneratedTable(name="the uncertain parameters table",
                                  marker="uncertain parameters",
                                  markdown=lambda: parameters_markdown())
documented_table = PARAMETERS_TABLE.documented


def main(argv=None) -> int:
    """`--check PAGE` or `--write PAGE` (GeneratedTable.main)."""
    return PARAMETERS_TABLE.main(argv, description=__doc__.split("\n\n")[0])


if __name__ == "__main__":
    sys.exit(main())
