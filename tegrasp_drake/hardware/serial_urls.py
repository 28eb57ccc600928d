"""The pyserial URLs a device's port may be (`socket://HOST:PORT`, `rfc2217://HOST:PORT`,
`loop://`, `spy://DEVICE`), checked from their text as pyserial 3.5's handlers read them
(serial/urlhandler/protocol_*.py), before any port is opened: a scheme no handler of this
table takes, a host or port a socket cannot use, a query option the handler does not take,
takes once, or takes only with certain values. pyserial would raise a ValueError for an
unknown scheme, a TypeError inside its open for a socket:// URL without a port, a KeyError
for `?logging=loud`; it reads a flag given a value (`?color=no`) as set, an option given
twice as its first, a `timeout` with Python's float() (`nan`, `-1`); and spy://'s
`?file=PATH` opens PATH for writing when the port is named, before it is opened: a user's
file there would be emptied, so only a new file, an empty one, an earlier spy log or a
character device (a terminal, /dev/null) is taken."""

import math
import os
import re
import stat
import typing
import urllib.parse

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.rig.echo import shorten, shown


class SerialUrlScheme(typing.NamedTuple):
    """What one pyserial handler reads: `address` "host_port" (HOST:PORT, PORT from 1 to
    65535), "none" (nothing before the query) or "device" (a device path it wraps); its
    query `options`, each an option kind of _OPTION_WORDS; `example` a URL of it."""
    address: str
    options: dict
    example: str


_LOGGING = "logging"  # one of pyserial's LOGGER_LEVELS
_FLAG = "flag"  # present or not: pyserial reads any value, `color=no` too, as present
_SECONDS = "seconds"  # rfc2217's network timeout, float()
_SPY_FILE = "spy file"  # a file spy:// writes its log to (opened "w")
LOGGING_LEVELS = ("debug", "info", "warning", "error")
MAX_NETWORK_TIMEOUT_S = 60.0  # rfc2217's timeout: pyserial's default is 3 s

PYSERIAL_URL_SCHEMES = {
    "socket": SerialUrlScheme("host_port", {"logging": _LOGGING}, "socket://192.168.1.30:4001"),
    "rfc2217": SerialUrlScheme("host_port", {"logging": _LOGGING, "ign_set_control": _FLAG,
                                             "poll_modem": _FLAG, "timeout": _SECONDS},
                               "rfc2217://192.168.1.30:2217"),
    "loop": SerialUrlScheme("none", {"logging": _LOGGING}, "loop://"),
    "spy": SerialUrlScheme("device", {"file": _SPY_FILE, "color": _FLAG, "raw": _FLAG,
                                      "all": _FLAG}, "spy:///dev/ttyUSB0?file=spy.log"),
}

_OPTION_WORDS = {_LOGGING: f"one of {', '.join(LOGGING_LEVELS)}",
                 _FLAG: "no value (give it alone: any value, `no` too, turns it on)",
                 _SECONDS: f"a number of seconds above 0 and at most "
                           f"{MAX_NETWORK_TIMEOUT_S:g}",
                 _SPY_FILE: "the path of a new file, or of an earlier spy log"}

# The start of a line of spy://'s hexdump (FormatHexdump.write_line: '{:010.3f} {:4} ...'),
# after a colour's escape code.
_SPY_LOG_LINE = re.compile(rb"(?:\x1b\[[0-9;]*m)*\d{6}\.\d{3} \S")


def is_serial_url(port: str) -> bool:
    """Whether `port` is a URL (pyserial's serial_for_url takes it for one: it holds ://)."""
    return "://" in port


def wrapped_device(port: str) -> str:
    """The device a spy:// URL wraps (`spy:///dev/ttyUSB0?file=x` is /dev/ttyUSB0), else
    `port` itself: two ports on one line are found through it."""
    if port.split("://", 1)[0].lower() != "spy" or "://" not in port:
        return port
    try:
        parts = urllib.parse.urlsplit(port)
    except ValueError:
        return port
    return parts.netloc + parts.path or port


def device_file(port: str) -> str | None:
    """The path of the device file `port` opens: a plain path itself, the device spy://
    wraps; None for the other URLs (loop://, socket://, rfc2217://), which open no file:
    pyserial opens them, and says what is wrong, when the device starts."""
    if not is_serial_url(port):
        return port
    if port.split("://", 1)[0].lower() != "spy":
        return None
    device = wrapped_device(port)
    return None if device == port or is_serial_url(device) else device


def named_paths(port: str) -> dict[str, str]:
    """{path: what it is} of each device or file `port` opens: a device's path ("device");
    spy://'s wrapped device and its `?file=` log ("spy log file"); none for other URLs (they
    name no path). Two ports naming one path would share a line or write one log."""
    if not is_serial_url(port):
        return {port: "device"}
    if port.split("://", 1)[0].lower() != "spy":
        return {}
    paths = {wrapped_device(port): "device"}
    try:
        query = urllib.parse.urlsplit(port).query
    except ValueError:
        return paths
    for option in query.split("&") if query else ():
        key, _, value = option.partition("=")
        if urllib.parse.unquote_plus(key) == "file" and value:
            paths.setdefault(urllib.parse.unquote_plus(value), "spy log file")
    return paths


def serial_url_problem(url: str, device_problem) -> str | None:
    """Why pyserial would not open the URL `url` as the package's table takes it
    (PYSERIAL_URL_SCHEMES), in words that follow the URL and say what to do, or None.
    `device_problem(path)`: why a path spy:// wraps is no serial device (or None)."""
    scheme_text = url.split("://", 1)[0]
    scheme = PYSERIAL_URL_SCHEMES.get(scheme_text.lower())
    if scheme is None:
        return (f"is not a pyserial URL this package takes ({shown(scheme_text + '://')} is "
                f"not one; taken: {', '.join(s + '://' for s in PYSERIAL_URL_SCHEMES)}); "
                "give a device's path, e.g. /dev/ttyUSB0, or one of those")
    try:
        parts = urllib.parse.urlsplit(url)
    except ValueError as error:
        return f"does not parse as a URL ({error}); {_form(scheme)}"
    problem = (_address_problem(parts, scheme, device_problem)
               or _query_problem(parts.query, parts.scheme, scheme))
    return f"{problem}; {_form(scheme)}" if problem else None


def _form(scheme: SerialUrlScheme) -> str:
    return f"e.g. {scheme.example}"


def _address_problem(parts, scheme: SerialUrlScheme, device_problem) -> str | None:
    name = f"{parts.scheme}://"
    if parts.fragment:
        return f"has a fragment {shown('#' + parts.fragment)}, which {name} does not read"
    if scheme.address == "none":
        if parts.netloc or parts.path:
            return (f"has {shown(parts.netloc + parts.path)} before its options, which "
                    f"{name} ignores; give {name} alone")
        return None
    if scheme.address == "device":
        device = parts.netloc + parts.path
        if not device:
            return f"names no device for {name} to wrap"
        if is_serial_url(device):
            return f"wraps {shown(device)}: {name} wraps a device's path, not another URL"
        problem = device_problem(device)
        return f"wraps {shown(device)}, which {problem}" if problem else None
    if parts.path:
        return f"has a path {shown(parts.path)} after the port, which {name} ignores"
    if "@" in parts.netloc:
        return f"has a user name before '@', which {name} does not take"
    host, colon, port = parts.netloc.rpartition(":")
    if not colon or host.endswith("[") or (host.startswith("[") and not host.endswith("]")):
        host, port = parts.netloc, None  # an IPv6 address's colons: no port given
    if not host or host == "[]":
        return f"has no host ({name}HOST:PORT)"
    if port is None:
        return f"has no port ({name}HOST:PORT)"
    if not (port.isascii() and port.isdecimal()) or (len(port) > 1 and port[0] == "0") or (
            not 1 <= int(port[:6]) <= 65535):
        return f"has the port {shown(port)}, which is not a number from 1 to 65535"
    return None


def _query_problem(query: str, name: str, scheme: SerialUrlScheme) -> str | None:
    """The first query option pyserial's `name` handler would refuse, misread or read
    differently from what is written; spy://'s file must not be a user's file."""
    seen = set()
    takes = "; ".join(f"{key}: {_OPTION_WORDS[kind]}" for key, kind in scheme.options.items())
    for option in query.split("&") if query else ():
        key, equals, value = option.partition("=")
        key, value = urllib.parse.unquote_plus(key), urllib.parse.unquote_plus(value)
        if not key:
            return f"has an empty option (a '&' or '=' with nothing before it) ({takes})"
        if key not in scheme.options:
            return (f"has the option {shown(key)}, which pyserial's {name}:// does not take "
                    f"(it takes {takes})")
        if key in seen:
            return f"gives the option {key} twice (pyserial would read the first only)"
        seen.add(key)
        kind = scheme.options[key]
        problem = _option_value_problem(kind, value, bool(equals))
        if problem:
            return f"has {shorten(option)}: {key} {problem}"
    return None


def _option_value_problem(kind: str, value: str, given: bool) -> str | None:
    if kind == _FLAG:
        return None if not given else f"takes {_OPTION_WORDS[_FLAG]}"
    if kind == _LOGGING:
        return None if value in LOGGING_LEVELS else f"must be {_OPTION_WORDS[_LOGGING]}"
    if kind == _SECONDS:
        try:
            seconds = float(value)
        except ValueError:
            seconds = math.nan
        if not (math.isfinite(seconds) and 0 < seconds <= MAX_NETWORK_TIMEOUT_S):
            return f"must be {_OPTION_WORDS[_SECONDS]}"
        return None
    return spy_file_problem(value)


def spy_file_problem(path: str) -> str | None:
    """Why spy:// may not write its log to `path` (it opens it for writing, emptying it,
    as soon as the port is named), in words that follow "file", or None: a path to a new
    file in an existing folder, an empty file, an earlier spy log (its first line is one of
    spy's hexdump), or a character device (a terminal, /dev/null)."""
    if not path:
        return "is empty: give the path of the log file"
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        folder = os.path.dirname(path) or "."
        if not os.path.isdir(folder):
            return f"is in {shown(folder)}, which is not a folder"
        return None
    except OSError as error:
        return f"cannot be used ({os_error_text(error)})"
    if stat.S_ISCHR(mode):
        return None
    if stat.S_ISDIR(mode):
        return f"{shown(path)} is a folder: give a file's path"
    if not stat.S_ISREG(mode):
        return (f"{shown(path)} is not a file (a pipe would stall the port until read): give "
                "a file's path")
    try:
        with open(path, "rb") as file:
            start = file.read(64)
    except OSError as error:
        return f"{shown(path)} cannot be read ({os_error_text(error)})"
    if start and not _SPY_LOG_LINE.match(start):
        return (f"{shown(path)} is a file that is not an earlier spy log: pyserial would "
                "empty it; give a new file's path, or move that file away")
    return None
