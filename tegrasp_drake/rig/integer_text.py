"""Integers written as text, read with a bound: the one integer reader of every typed reader (YAML
and `--set` values via typed_yaml.parse_yaml, JSON via files.load_json, integer options).

Python refuses decimal text of more than 4300 digits (`sys.int_max_str_digits`, against
quadratic-time conversion), and no setting holds a number a float64 cannot (float fields take
integers too). So an integer is read only within a float64's range, |n| <= 1.8e308, decided from the
text's length before any conversion; past it, IntegerTextError says how many digits the text has.
Forms read: JSON's and YAML 1.2's decimal integers, and YAML 1.1's (PyYAML's): `_` separators, 0b,
0x and 0 (octal) prefixes and base-60 `1:30`."""

import math
import re
import sys

# The largest magnitude read: a float64's (every setting is checked as a number in its range).
LIMIT = sys.float_info.max
# Digits of LIMIT in a base, for the length check made before any conversion.
_MAX_BITS = sys.float_info.max_exp  # 1024: |n| < 2**1024 for every finite float
_BASE_PREFIXES = {"0b": 2, "0x": 16}
_YAML11_INT = re.compile(r"""^(?:[-+]?0b[0-1_]+
    |[-+]?0[0-7_]+
    |[-+]?(?:0|[1-9][0-9_]*)
    |[-+]?0x[0-9a-fA-F_]+
    |[-+]?[1-9][0-9_]*(?::[0-5]?[0-9])+)$""", re.X)


class IntegerTextError(ValueError):
    """Integer text beyond LIMIT (or not an integer); the message says why, without the text."""


def is_integer_text(text: str) -> bool:
    """True for text YAML 1.1 (PyYAML's resolver) reads as an integer."""
    return bool(_YAML11_INT.match(text))


_DECIMAL_INT = re.compile(r"^[-+]?[0-9]+$")


def read_integer(text: str, *, yaml11: bool = True) -> int:
    """The integer `text` writes (module docstring; `yaml11=False`: decimal digits alone, as
    JSON and the command line write them), IntegerTextError for text that is not one or whose
    value lies beyond LIMIT; the text's length is checked before it is converted."""
    grammar = _YAML11_INT if yaml11 else _DECIMAL_INT
    if not isinstance(text, str) or not grammar.match(text.strip()):
        raise IntegerTextError("is not an integer")
    body = text.strip().replace("_", "")
    sign = -1 if body.startswith("-") else 1
    body = body.lstrip("+-")
    if ":" in body:  # base 60, YAML 1.1: each part below 60
        parts = body.split(":")
        digits, base = len(parts), 60
    elif body[:2].lower() in _BASE_PREFIXES:
        base = _BASE_PREFIXES[body[:2].lower()]
        parts, digits = None, len(body) - 2
    elif yaml11 and len(body) > 1 and body.startswith("0"):
        base, parts, digits = 8, None, len(body) - 1
    else:
        base, parts, digits = 10, None, len(body)
    if (digits - 1) * math.log2(base) >= _MAX_BITS:
        raise IntegerTextError(_beyond(digits))
    if parts is not None:
        value = 0
        for part in parts:
            value = value * 60 + int(part)
    elif base == 10:
        value = int(body)
    else:
        value = int(body[2:] if base != 8 else body[1:], base)
    if value > LIMIT:
        raise IntegerTextError(_beyond(digits))
    return sign * value


def _beyond(digits: int) -> str:
    return (f"is an integer of {digits} digits, beyond the range of any setting (a float's, "
            "at most 1.8e308)")


def integer_option(text: str) -> int:
    """An argparse `type` for an integer option (decimal digits): read_integer, its error as
    argparse's, the text cut to a few dozen characters."""
    import argparse
    try:
        return read_integer(text, yaml11=False)
    except IntegerTextError as e:
        shown = text if len(text) <= 40 else f"{text[:20]}...({len(text)} characters)"
        raise argparse.ArgumentTypeError(f"{shown!r} {e}") from None
