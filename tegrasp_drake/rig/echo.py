"""Values as a message echoes them: the one echo of every value a user gave that an error, a
warning or a usage message repeats. A value pasted by mistake is cut to ECHO_CHARS, so that no
message runs pages long, and the echo never raises, so that no message can fail to be made.
A byte a path or an environment value could not decode is shown as that byte (`'/tmp/x\\xff'`),
not as the surrogate Python holds it by (`\\udcff`)."""

import os
import re
import sys

# How many characters of a value a message repeats.
ECHO_CHARS = 80


def shorten(text: str, limit: int = ECHO_CHARS) -> str:
    """`text` cut to about `limit` characters, its start and its end kept (a path's folder
    and file name), saying how long it was."""
    if len(text) <= limit:
        return text
    tail = limit * 3 // 8
    return f"{text[:limit - tail]}...{text[len(text) - tail:]} ({len(text)} characters)"


# A byte os.fsdecode could not decode, held as a surrogate (\udc80-\udcff): raw, and as repr
# writes it (not after an escaped backslash: `\\udcff` is the text a user typed).
_UNDECODED = re.compile("[\udc80-\udcff]")
_UNDECODED_REPR = re.compile(r"(?<!\\)((?:\\\\)*)\\udc([89a-f][0-9a-f])")


def undecoded_as_bytes(text: str) -> str:
    """`text` with each byte a path or an environment value could not decode written as a
    bytes repr writes it (os.fsencode: `/tmp/x\\xff`); every error line the user reads."""
    return _UNDECODED.sub(lambda m: repr(os.fsencode(m.group()))[2:-1], text)


def undecoded_byte(text: str) -> tuple[int, int] | None:
    """(position, byte) of the first byte in `text` that a command-line argument, a path or
    an environment value held and could not decode as UTF-8 (a surrogate), or None."""
    found = _UNDECODED.search(text)
    return None if found is None else (found.start(), os.fsencode(found.group())[0])


def _repr_bytes(text: str) -> str:
    """A repr's `\\udcff` (an undecoded byte) as the byte's `\\xff`."""
    return _UNDECODED_REPR.sub(r"\1\\x\2", text)


def shown(value) -> str:
    """`value` as a message echoes it, cut to ECHO_CHARS: a number an option was given as the
    user typed it (number_text.TypedNumber: `600.0001`, not 600), a text quoted, an integer
    Python will not write as text (over 4300 digits) by its count of digits, anything else by
    its repr, or by its type where its repr fails."""
    from tegrasp_drake.rig.integer_text import integer_digits
    typed = getattr(value, "typed", None) if isinstance(value, float) else None
    if isinstance(typed, str):
        return shorten(typed)
    if isinstance(value, str):
        return _repr_bytes(repr(shorten(value)))
    if isinstance(value, int) and abs(value) > sys.float_info.max:
        return f"<an integer of {integer_digits(value)} digits>"
    try:
        return _repr_bytes(shorten(repr(value)))
    except Exception:  # any repr may fail (a huge int inside a list); the message must not
        return f"<a {type(value).__name__} that cannot be written as text>"


# The types whose values a message echoes after their type's name (`str 'box'`, `int 5`,
# `list [1]`): what was given is then both its kind and its text.
_ECHOED_TYPES = (str, bytes, bytearray, bool, int, float, complex, list, tuple, dict, set,
                 frozenset)


def given(value) -> str:
    """What a user gave, in the words that follow "got" in an error: `None`; a text, number or
    plain collection by its type and its echo (`str 'box'`, `int -3`, `list [1]`); an enum's
    member by its name (`Mode.HOLD`); a path by its type and text; any other object (a config
    of the wrong class, a Drake system) by its class alone (`a HardwareStationConfig`), whose
    repr would run for lines."""
    import enum
    if value is None:
        return "None"
    if isinstance(value, enum.Enum):
        return f"{type(value).__name__}.{value.name}"
    if isinstance(value, _ECHOED_TYPES):
        return f"{type(value).__name__} {shown(value)}"
    if isinstance(value, os.PathLike):
        try:
            return f"{type(value).__name__} {shown(os.fspath(value))}"
        except Exception:  # noqa: BLE001: a __fspath__ of its own that raises
            pass
    if type(value).__module__ == "numpy":  # an array or a NumPy scalar: its values say it
        return f"{type(value).__name__} {shown(value)}"
    name = type(value).__name__
    return f"{'an' if name[:1] in 'AEIOUaeiou' else 'a'} {name}"
