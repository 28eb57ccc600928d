import argparse

import pytest

from tegrasp_drake.rig.number_text import (NumberTextError, count_text, number_option,
                                           read_number)


def test_count_text_says_one_thing_in_the_singular_and_others_in_the_plural():
    assert count_text(1, "marker") == "1 marker"
    assert count_text(0, "marker") == "0 markers"
    assert count_text(4, "marker") == "4 markers"


@pytest.mark.parametrize("text, value", [("3", 3.0), ("-2.5", -2.5), (".5", 0.5), ("5.", 5.0),
                                         ("5e-2", 0.05), ("1E+3", 1000.0), ("007", 7.0)])
def test_a_number_option_reads_decimal_text(text, value):
    assert read_number(text) == value


@pytest.mark.parametrize("text", ["1_0", "\u0661\u0662", "\uff11\uff12", " 3", "3 ", "+3", "inf",
                                  "-inf", "nan", "0x10", "", "3\n", "1e", "--3"])
def test_a_number_option_refuses_what_only_python_reads_as_a_number(text):
    with pytest.raises(NumberTextError, match="is not a number"):
        read_number(text)


def test_a_number_option_keeps_the_text_typed_for_its_messages():
    assert number_option("600.0001").typed == "600.0001"
    with pytest.raises(argparse.ArgumentTypeError, match="'1_0' is not a number"):
        number_option("1_0")
