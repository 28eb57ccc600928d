import argparse

import pytest

from tegrasp_drake.rig.echo import ECHO_CHARS, shorten, shown
from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig.number_text import number_option


def test_integer_and_number_options_echo_a_long_text_alike():
    text = "9" * (2 * ECHO_CHARS) + "x"
    echoes = []
    for option in (integer_option, number_option):
        with pytest.raises(argparse.ArgumentTypeError) as error:
            option(text)
        echoes.append(str(error.value).split(" is not")[0])
    assert echoes == [shown(text), shown(text)]
    assert f"({len(text)} characters)" in shown(text)


def test_a_text_is_echoed_quoted_and_cut():
    assert shown("abc") == "'abc'"
    text = "a" * 500 + "b" * 500
    assert shown(text) == repr("a" * 50 + "..." + "b" * 30 + " (1000 characters)")


def test_a_long_path_keeps_its_start_and_its_end():
    path = "/home/me/" + "x" * 300 + "/trial.npz"
    cut = shorten(path)
    assert cut.startswith("/home/me/x") and cut.endswith("x/trial.npz (319 characters)"), cut
    assert len(cut) < ECHO_CHARS + 30


def test_a_number_typed_is_echoed_as_typed():
    assert shown(number_option("600.0001")) == "600.0001"
    assert shown(number_option("1e-9")) == "1e-9"


class _Unwritable:
    def __repr__(self):
        raise RuntimeError("no repr")


@pytest.mark.parametrize("value, expected", [
    (10 ** 5000, "<an integer of 5001 digits>"),
    ([10 ** 5000], "<a list that cannot be written as text>"),
    (_Unwritable(), "<a _Unwritable that cannot be written as text>"),
    (b"\xff" * 200, repr(b"\xff" * 200)[:50] + "..." + repr(b"\xff" * 200)[-30:]
     + " (803 characters)"),
], ids=["huge integer", "list of a huge integer", "repr raises", "bytes"])
def test_an_echo_never_raises(value, expected):
    assert shown(value) == expected


def test_a_byte_a_path_could_not_decode_is_echoed_as_the_byte():
    import os
    import pathlib
    path = os.fsdecode(b"/tmp/x\xff")  # as Python holds an argument or a variable's value
    assert shown(path) == "'/tmp/x\\xff'"
    assert shown(pathlib.PurePosixPath(path)) == "PurePosixPath('/tmp/x\\xff')"
    assert shown("typed \\udcff") == "'typed \\\\udcff'"  # the text a user typed, kept
