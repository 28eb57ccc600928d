"""The one bounded integer reader (rig/integer_text.py)."""

import argparse
import sys

import pytest

from tegrasp_drake.rig.integer_text import IntegerTextError, integer_option, read_integer


@pytest.mark.parametrize("text, value", [
    ("12", 12), ("-7", -7), ("+3", 3), ("0x1f", 31), ("0o17", 15), ("017", 17), ("0", 0)])
def test_the_yaml_12_core_integer_forms_are_read(text, value):
    assert read_integer(text) == value


@pytest.mark.parametrize("text", ["1:30", "0b101", "1_000", "+0x1f", "3.0", ""])
def test_yaml_11_only_integer_forms_are_not_integers(text):
    with pytest.raises(IntegerTextError, match="is not an integer"):
        read_integer(text)


def test_decimal_only_refuses_the_prefixed_forms():
    assert read_integer("017", decimal_only=True) == 17
    for text in ("0x1f", "0o17"):
        with pytest.raises(IntegerTextError, match="is not an integer"):
            read_integer(text, decimal_only=True)


@pytest.mark.parametrize("text", ["9" * 5000, "-" + "9" * 400, "0x" + "f" * 300,
                                  "0o" + "7" * 400, "9" * 309])
def test_an_integer_beyond_a_floats_range_is_refused_with_its_length(text):
    with pytest.raises(IntegerTextError, match=r"is an integer of \d+ digits, beyond the range"):
        read_integer(text)


def test_the_largest_integer_a_float_holds_is_read():
    largest = int(sys.float_info.max)
    assert read_integer(str(largest)) == largest


def test_the_length_is_checked_before_python_converts_the_text():
    # Past Python's 4300-digit limit int() raises its own ValueError; the reader never calls it.
    assert sys.get_int_max_str_digits() < 5000
    with pytest.raises(IntegerTextError):
        read_integer("7" * 5000)


def test_an_integer_option_refuses_a_long_value_without_echoing_it():
    with pytest.raises(argparse.ArgumentTypeError) as refused:
        integer_option("9" * 5000)
    assert "5000 digits" in str(refused.value) and len(str(refused.value)) < 200
    assert integer_option("4") == 4
