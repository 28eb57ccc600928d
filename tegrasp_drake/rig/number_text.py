"""Numbers as a user reads them in a message: the one formatter of every number an error, a
warning or a printed result shows, so that none prints 3.997943786001997 where the others print
3.99794."""

import numbers


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
