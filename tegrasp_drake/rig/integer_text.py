"""Integers written as text, read with a bound: the one integer reader of every typed reader (YAML
and `--set` values via typed_yaml.parse_yaml, JSON via files.load_json, integer options).

Python refuses decimal text of more than 4300 digits (`sys.int_max_str_digits`, against
quadratic-time conversion), and no setting holds a number a float64 cannot (float fields take
integers too). So an integer is read only within a float64's range, |n| <= 1.8e308, decided from the
text's length before any conversion; past it, IntegerTextError says how many digits the text has.
Forms read: YAML 1.2's core schema's integers (decimal, `0o17` octal, `0x1f` hexadecimal; `017` is
decimal 17), or with `decimal_only` decimal digits alone, as JSON and the command line write them."""

import math
import re
import sys

# The largest magnitude read: a float64's (every setting is checked as a number in its range).
LIMIT = sys.float_info.max
# Digits of LIMIT in a base, for the length check made before any conversion.
_MAX_BITS = sys.float_info.max_exp  # 1024: |n| < 2**1024 for every finite float
_BASE_PREFIXES = {"0o": 8, "0x": 16}
# YAML 1.2 core schema's integer forms (core_schema_yaml.py resolves plain scalars with it).
CORE_INT = re.compile(r"^(?:[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+)$")
_DECIMAL_INT = re.compile(r"^[-+]?[0-9]+$")
# An integer option's text: as number_text.OPTION_NUMBER writes an integer (no spaces, no '+');
# number_option reads such text as an integer too.
OPTION_INTEGER = re.compile(r"-?[0-9]+")


class IntegerTextError(ValueError):
    """Integer text beyond LIMIT (or not an integer); the message says why, without the text."""


def read_integer(text: str, *, decimal_only: bool = False) -> int:
    """The integer `text` writes (module docstring), IntegerTextError for text that is not one
    or whose value lies beyond LIMIT; the text's length is checked before it is converted."""
    grammar = _DECIMAL_INT if decimal_only else CORE_INT
    if not isinstance(text, str) or not grammar.match(text.strip()):
        raise IntegerTextError("is not an integer")
    body = text.strip()
    sign = -1 if body.startswith("-") else 1
    body = body.lstrip("+-")
    base = _BASE_PREFIXES.get(body[:2], 10)
    if base != 10:
        body = body[2:]
    digits = len(body)
    if (digits - 1) * math.log2(base) >= _MAX_BITS:
        raise IntegerTextError(_beyond(digits))
    value = int(body, base)
    if value > LIMIT:
        raise IntegerTextError(_beyond(digits))
    return sign * value


def integer_digits(value: int) -> int:
    """How many decimal digits |value| has, found from its bit length: Python refuses to write
    an integer of more than 4300 digits as text, so a huge one is never converted."""
    magnitude = abs(value)
    digits = int((max(magnitude.bit_length(), 1) - 1) * math.log10(2)) + 1  # low by at most 1
    return digits + 1 if magnitude >= 10 ** digits else digits


def integer_beyond_problem(value) -> str | None:
    """For a Python int beyond LIMIT (one given to the Python API, which no reader bounded),
    the words read_integer's error gives for its text, following "field 'x'"; else None."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) > LIMIT:
        return _beyond(integer_digits(value))
    return None


def _beyond(digits: int) -> str:
    return (f"is an integer of {digits} digits, beyond the range of any setting (a float's, "
            "at most 1.8e308)")


def integer_option(text: str) -> int:
    """An argparse `type` for an integer option (decimal digits, a '-' sign: as every number
    option writes one, number_text.OPTION_NUMBER): read_integer, its error as argparse's, the
    text echoed by echo.shown."""
    import argparse
    try:
        if not OPTION_INTEGER.fullmatch(text):
            raise IntegerTextError("is not an integer")
        return read_integer(text, decimal_only=True)
    except IntegerTextError as e:
        from tegrasp_drake.rig.echo import shown
        raise argparse.ArgumentTypeError(f"{shown(text)} {e}") from None
