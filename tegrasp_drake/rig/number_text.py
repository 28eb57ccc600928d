"""Numbers as a user reads them in a message: the one formatter of every number an error, a
warning or a printed result shows, so that none prints 3.997943786001997 where the others print
3.99794; and numbers as a user writes them on a command line: the one reader of every number
option (number_option; integer options: integer_text.integer_option), its text kept for the
option's messages."""

import math
import numbers
import re


def number_text(value) -> str:
    """`value` as text: an integer whole (4294967295, not 4.29497e+09), another real number to
    six significant digits (`{:g}`: 3.99794, 1e-06, nan, inf), a sequence of numbers as
    `(a, b)`, anything else as str()."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, list, tuple)):
        return str(value)
    if isinstance(value, (list, tuple)):
        return "(" + ", ".join(number_text(item) for item in value) + ")"
    if float(value).is_integer() and abs(value) < 1e15:
        return str(int(value))
    return f"{float(value):g}"


def count_text(count: int, noun: str) -> str:
    """`count` things as a message says it: "1 object", "0 objects", "4 objects" (`noun`
    singular; English adds "s" for every count but one)."""
    return f"{count} {noun}{'' if count == 1 else 's'}"


# A number as the command line writes one: ASCII decimal digits, a '-' sign, a fraction, an
# exponent (`2.5`, `-1`, `.5`, `5e-2`). Nothing else that Python's float() reads: no spaces
# around it, no '+' sign, no `1_0`, no other script's digits (`١٢`, `１２`), no inf or nan.
# re.ASCII: \d is 0-9 alone.
OPTION_NUMBER = re.compile(r"-?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?", re.ASCII)


class NumberTextError(ValueError):
    """Text that is not a number as OPTION_NUMBER writes one, or one no float holds; the
    message says why, following the text."""


class TypedNumber(float):
    """A number an option was given, holding the text the user typed (`typed`), which a
    message echoes (echo.shown): 600.0001 is not shown as 600, nor 1e-9 as 1e-09."""

    def __new__(cls, value: float, typed: str):
        number = super().__new__(cls, value)
        number.typed = typed
        return number

    def __reduce__(self):
        return TypedNumber, (float(self), self.typed)


def read_number(text: str) -> float:
    """The number `text` writes (OPTION_NUMBER) as a float; NumberTextError for other text,
    and for a number beyond a float's range: an integer beyond it is named by its digits
    (integer_text.read_integer), `1e400` and a nonzero number a float rounds to 0 (`1e-400`)
    are refused rather than read as inf or 0."""
    from tegrasp_drake.rig.integer_text import OPTION_INTEGER, IntegerTextError, read_integer
    if not isinstance(text, str) or not OPTION_NUMBER.fullmatch(text):
        raise NumberTextError("is not a number (write decimal digits, e.g. 3 or 2.5)")
    if OPTION_INTEGER.fullmatch(text):
        try:
            return float(read_integer(text, decimal_only=True))
        except IntegerTextError as e:
            raise NumberTextError(str(e)) from None
    if len(text) > 1000:  # float() of a long text is slow; no setting needs 1000 characters
        raise NumberTextError(f"is {len(text)} characters long; write the number in fewer")
    problem = float_beyond_problem(text)
    if problem is not None:
        raise NumberTextError(problem)
    return float(text)


def float_beyond_problem(text: str) -> str | None:
    """Why no float holds the number the decimal `text` writes, in words that follow the text
    or its field: float() would read one past a float's range as inf (`1e400`) and a nonzero
    one below it as 0 (`1e-400`); None when a float holds it (the number options and the YAML
    and `--set` readers refuse such text alike)."""
    value = float(text)
    if math.isinf(value) or (value == 0 and text.lower().split("e")[0].strip("+-.0")):
        return ("is beyond the range of any setting (a float's, a magnitude from 5e-324 to "
                "1.8e308, or 0)")
    return None


def number_option(text: str) -> TypedNumber:
    """An argparse `type` for a number option: read_number, the text kept (TypedNumber) for
    the option's range message; text that is not such a number does not parse (argparse's
    error, the text echoed by echo.shown)."""
    import argparse
    try:
        return TypedNumber(read_number(text), text)
    except NumberTextError as e:
        from tegrasp_drake.rig.echo import shown
        raise argparse.ArgumentTypeError(f"{shown(text)} {e}") from None



def distinct_number_texts(first, second) -> tuple[str, str]:
    """Two different numbers as text (number_text), each to its last digit (repr) when their
    six significant digits read the same, so a message never says "1.23457 != 1.23457"."""
    texts = number_text(first), number_text(second)
    return texts if texts[0] != texts[1] else (repr(float(first)), repr(float(second)))
