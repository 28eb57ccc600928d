"""Which station a scenario runs on (typed config), as in Drake's hardware_sim:
`station: !SimulatedStationConfig {}` (the default) or the real devices:

    station: !HardwareStationConfig              # MakeHardwareStation
      arm: {lcm_url: "udpm://239.255.76.67:7667?ttl=0"}
      gripper: {port: /dev/ttyUSB0, device_id: 9}
      tactile: {port: /dev/ttyACM0, calibration_file: pads.yaml}"""

import dataclasses
import ipaddress
import math
import os
import stat
import sys
import tempfile
import typing

from pydrake.common.yaml import yaml_dump_typed

from tegrasp_drake.rig.files import os_error_text
from tegrasp_drake.hardware.realtime import SCHEDULING_POLICIES
from tegrasp_drake.hardware.serial_urls import (is_serial_url, named_paths,
                                                 serial_url_problem, wrapped_device)
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.ranges import bounded, check_ranges, chosen
from tegrasp_drake.modelgen.jaco2_dh import continuous_joints_problem
from tegrasp_drake.hardware.jaco.jaco_lcm import (JACO_COMMAND_CHANNEL, JACO_LCM_PERIOD,
                                                  JACO_STATUS_CHANNEL)
from tegrasp_drake.hardware.myrio.tactile_frame import (COUNTS_SIZE, CRC_SIZE, FRAME_PERIOD_US,
                                                        HEADER_SIZE)
from tegrasp_drake.rig.jaco_velocity_tracker import JacoVelocityTrackerConfig
from tegrasp_drake.robotiq import registers
from tegrasp_drake.hardware.robotiq.modbus_client import (ACTIVATION_MIN_S, MIN_PERIOD,
                                                          RobotiqModbusConfig)
from tegrasp_drake.hardware.watchdog import DEFAULT_TIMEOUTS
from tegrasp_drake.rig.typed_yaml import (ConfigError, ForeignTagError, apply_override,
                                          check_instance, load_typed, loaded_with_overrides,
                                          read_yaml_file, refuse_a_key_set_twice,
                                          require_fields, require_mapping)
from tegrasp_drake.rig.api_boundary import PathLike, public_api, public_dataclass
from tegrasp_drake.rig.echo import shorten, shown

LCM_URL_VARIABLE = "LCM_DEFAULT_URL"
LCM_OWN_DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"


def default_lcm_url() -> str:
    """LCM's own default bus, or the one LCM_DEFAULT_URL names now: read when a default is
    needed, as lcm.LCM() reads it when a bus is made (a script that sets the variable after
    importing this package gets its bus)."""
    return os.environ.get(LCM_URL_VARIABLE, "").strip() or LCM_OWN_DEFAULT_URL


def lcm_url_origin(url: str, field: str) -> str:
    """Where a message says `url` came from: the LCM_DEFAULT_URL environment variable when it
    set the default and `url` is that default (the user wrote no `field`, and fixes the
    variable), else `field` ("field 'arm.lcm_url'", "--lcm-url")."""
    if os.environ.get(LCM_URL_VARIABLE, "").strip() and url == default_lcm_url():
        return f"the environment variable {LCM_URL_VARIABLE} (the default of {field})"
    return field


def lcm_url_text_problem(url, field: str) -> str | None:
    """Why `url`, the default LCM_DEFAULT_URL set, cannot be text at all (a control
    character: typed_yaml.text_problem), naming the variable as lcm_url_origin does, or None
    (also for a URL that `field` gave: the field's own check names it)."""
    from tegrasp_drake.rig.typed_yaml import text_problem
    if not isinstance(url, str) or lcm_url_origin(url, field) == field:
        return None
    problem = text_problem(url)
    return f"{lcm_url_origin(url, field)} {problem}, got {shown(url)}" if problem else None


@public_dataclass
@dataclasses.dataclass
class JacoLcmDriver:
    """The JACO2 through the Kinova LCM driver (joint-velocity mode, 100 Hz) on `lcm_url`
    (`?ttl=0` keeps multicast on this host), Drake's KINOVA_JACO_{COMMAND,STATUS} channels."""
    lcm_url: str = dataclasses.field(default_factory=default_lcm_url)
    tracker: JacoVelocityTrackerConfig = dataclasses.field(
        default_factory=JacoVelocityTrackerConfig)

    def __post_init__(self):
        # A control character from LCM_DEFAULT_URL is the variable's to fix: said naming it
        # (lcm_url_origin), before the field check names a field the user did not write.
        problem = lcm_url_text_problem(self.lcm_url, "field 'arm.lcm_url'")
        if problem:
            from tegrasp_drake.rig.typed_yaml import ConfigTypeError
            raise ConfigTypeError(problem)

    @property
    def channels(self) -> tuple[str, str]:
        return JACO_COMMAND_CHANNEL, JACO_STATUS_CHANNEL


# A silence the watchdog may call a device's fault: more than this many of its update periods,
# so that one late sample never trips it (the defaults, DEFAULT_TIMEOUTS, allow 5-20).
WATCHDOG_MIN_PERIODS = 2

# [s] the myRIO's frame period: one frame a millisecond (TACTILE_FRAME.md).
TACTILE_FRAME_PERIOD_S = FRAME_PERIOD_US * 1e-6
# [baud] what the myRIO's stream needs on a serial line, 8N1 (10 bits a byte): a frame
# without counts every millisecond, and each finger's counts once per AD7147 sequence,
# ~9.2 ms (TACTILE_FRAME.md: about 23 kB/s). A slower line falls ever further behind.
TACTILE_STREAM_BAUD = math.ceil(10 * ((HEADER_SIZE + CRC_SIZE) / TACTILE_FRAME_PERIOD_S
                                      + 2 * COUNTS_SIZE / 9.2e-3))
# [frames] the most frames a burst may leave waiting: each is a millisecond of latency, and
# one 0.5 s event window (Sec. III-A) late, a sample no longer meets the window it belongs to.
TACTILE_MAX_BACKLOG = 500


@public_dataclass
@dataclasses.dataclass
class SerialTactileDriver:
    """The myRIO tactile stream (hardware/myrio/TACTILE_FRAME.md) on a serial port, with an
    optional TactileCalibration YAML ("" for the defaults)."""
    port: str = "/dev/ttyACM0"
    # 23 kB/s of frames is 25 % of 921600 baud (TACTILE_FRAME.md). Low end: what the stream
    # needs (TACTILE_STREAM_BAUD); on the USB port (CDC-ACM) the rate is nominal: leave the
    # default. High: the fastest UART rates, 12 Mbaud.
    baudrate: int = bounded(921600, low=TACTILE_STREAM_BAUD, high=12_000_000, unit="baud",
                            why="at least the myRIO stream's ~23 kB/s, 8N1; at most 12 Mbaud")
    calibration_file: str = ""
    # the receiver's `stale` flag: 50 frame periods (the watchdog has its own timeout). Low
    # end: WATCHDOG_MIN_PERIODS frame periods (one late frame must not mark the stream stale);
    # high: 10 s of silence is a stream gone.
    stale_timeout: float = bounded(
        0.05, low=WATCHDOG_MIN_PERIODS * TACTILE_FRAME_PERIOD_S, high=10.0, unit="s",
        why=f"at least {WATCHDOG_MIN_PERIODS} of the myRIO's "
            f"{number_text(TACTILE_FRAME_PERIOD_S)} s frame periods")
    # frames left waiting in a burst, so the latency is at most 8 ms with no sample lost
    max_backlog: int = bounded(8, low=0, high=TACTILE_MAX_BACKLOG, unit="frames",
                               why="a frame a millisecond, at most one 0.5 s event window late",
                               below="must be zero or a positive number of frames")


def _watchdog_timeout(default: float, updates: str, period: float):
    """A device's watchdog timeout field [s]: longer than WATCHDOG_MIN_PERIODS of the
    device's `updates` (in words), one each `period` [s], so one late update never trips it
    (watchdog_timeouts_problem checks the gripper's against its configured timing too); at
    most 10 s, a silence that long is a device gone."""
    least = WATCHDOG_MIN_PERIODS * period
    return bounded(default, low=least, low_open=True, high=10.0, unit="s",
                   why=f"longer than {WATCHDOG_MIN_PERIODS} of {updates}, "
                       f"{number_text(period)} s each")


@public_dataclass
@dataclasses.dataclass
class DeviceWatchdogConfig:
    """Silence [s] after which a device trips the watchdog (hardware/watchdog.py), and the
    extra time a device may take to say anything after the start."""
    # the JACO2 driver's statuses at 100 Hz (JACO_LCM_PERIOD)
    arm_timeout: float = _watchdog_timeout(DEFAULT_TIMEOUTS["arm"], "the JACO2's statuses",
                                           JACO_LCM_PERIOD)
    # the 2F-85's status reads at up to 200 Hz (MIN_PERIOD)
    gripper_timeout: float = _watchdog_timeout(DEFAULT_TIMEOUTS["gripper"],
                                               "the 2F-85's status reads", MIN_PERIOD)
    # the myRIO's frames, one a millisecond
    tactile_timeout: float = _watchdog_timeout(DEFAULT_TIMEOUTS["tactile"],
                                               "the myRIO's frames", TACTILE_FRAME_PERIOD_S)
    # [s] extra time a device may take to be first heard from after the start: none needed
    # (the station waits for each before the loop starts), at most a minute
    startup_grace: float = bounded(1.0, low=0.0, high=60.0, unit="s",
                                   below="must be zero or positive [s]")

    def timeouts(self) -> dict[str, float]:
        """{device: timeout} in the watchdog's device order."""
        return {"arm": self.arm_timeout, "gripper": self.gripper_timeout,
                "tactile": self.tactile_timeout}


@public_dataclass
@dataclasses.dataclass
class HardwareStationConfig:
    """The real devices (or their emulators): MakeHardwareStation."""
    arm: JacoLcmDriver = dataclasses.field(default_factory=JacoLcmDriver)
    gripper: RobotiqModbusConfig = dataclasses.field(default_factory=RobotiqModbusConfig)
    tactile: SerialTactileDriver = dataclasses.field(default_factory=SerialTactileDriver)
    watchdog: DeviceWatchdogConfig = dataclasses.field(default_factory=DeviceWatchdogConfig)
    # [s] before the loop starts, for the arm's status, gripper activation and pad zeroing.
    # Low end: the 2F-85's fastest activation (ACTIVATION_MIN_S), which the wait holds; high:
    # ten minutes, more than any device's start-up (a longer wait is a device not coming up).
    ready_timeout: float = bounded(
        10.0, low=ACTIVATION_MIN_S, high=600.0, unit="s",
        why=f"at least the 2F-85's fastest activation, {number_text(ACTIVATION_MIN_S)} s")
    # "fifo", "nice" or "normal", each falling back to the next (hardware/realtime.py)
    scheduling: str = chosen("fifo", names=SCHEDULING_POLICIES)
    realtime_priority: int = bounded(10, low=1, high=99, why="SCHED_FIFO priorities, sched(7)")

    def check_relations(self, source: str) -> None:
        """ConfigError naming the field unless the fields are in their ranges and relate as
        a loaded config's timings must (request and watchdog timeouts against the baud rate
        and the device periods): public functions (MakeHardwareStation) call it on a config
        changed since it was loaded. The LCM URL and the ports are checked when opened."""
        check_ranges(self, source)
        problem = (gripper_request_timeout_problem(self) or watchdog_timeouts_problem(self))
        if problem:
            raise ConfigError(f"{source}: {problem}")


# The LCM providers (lcm_create's URL schemes) a URL may name, by its text, before LCM is
# given it: the buses other processes share (udpm:// multicast, tcpq:// through an
# lcm-tcpq server) and memq://, a bus inside the one process that opens it (library code and
# tests run both ends in one process on it). Anything else is refused unopened: LCM's
# file:// provider is an event-log file, which opening (even to check it) creates, or with
# ?mode=w truncates, and which no other process hears.
SHARED_LCM_PROVIDERS = ("udpm", "tcpq")
IN_PROCESS_LCM_PROVIDERS = ("memq",)


class LcmUrlOption(typing.NamedTuple):
    """An option a provider takes in a URL's query: a decimal integer from `low` to `high`,
    `what` it sets in words ("a multicast TTL")."""
    low: int
    high: int
    what: str


# The options each provider takes in a URL's query and the integers each allows (LCM's
# lcm_udpm.c, lcm_tcpq.c and lcm_memq.c). LCM warns of another option on stderr and runs
# without it, and reads a value with C's strtol(base 0): `010` as octal 8, `1e6` as 1, and a
# number past its C type wrapped; so the text is checked here. ttl: IP_MULTICAST_TTL, ip(7),
# an 8-bit field; recv_buf_size: SO_RCVBUF, socket(7), a C int (LCM reads 0 as the kernel's
# default: leave the option out for it).
LCM_URL_OPTIONS = {
    "udpm": {"ttl": LcmUrlOption(0, 255, "a multicast TTL"),
             "recv_buf_size": LcmUrlOption(1, 2**31 - 1,
                                           "a socket receive buffer's size in bytes")},
    "tcpq": {}, "memq": {}}


class LcmUrlAddress(typing.NamedTuple):
    """The ADDRESS a provider's URL gives (PROVIDER://HOST[:PORT]): HOST an IPv4 literal of
    `kind` ("multicast": a udpm:// group; "unicast": the tcpq:// server, never 0.0.0.0, a
    multicast or broadcast address), PORT optional, a decimal integer from 1 to 65535
    without a leading zero; `form` is how to write it, `example` one."""
    kind: str
    form: str
    example: str


# The address each provider's URL gives (LCM's lcm_udpm.c and lcm_tcpq.c). LCM 1.5.3's tcpq
# provider never resolves a host name (it calls gethostbyname only if inet_aton returns a
# negative number, which it never does): a name, or no host, connects to 0.0.0.0, which is
# this host's 127.0.0.1, so only an IPv4 literal is taken. Both read the port with C's
# strtol(base 0): `07700` as octal, `0x1e14` as hex, `7700x` as 7700.
LCM_URL_ADDRESSES = {
    "udpm": LcmUrlAddress("multicast", "give udpm://GROUP:PORT, e.g. "
                          "udpm://239.255.76.67:7667?ttl=0", "udpm://239.255.76.67:7667?ttl=0"),
    "tcpq": LcmUrlAddress("unicast", "give tcpq://HOST:PORT with HOST the lcm-tcpq server's "
                          "IPv4 address, e.g. tcpq://127.0.0.1:7700", "tcpq://127.0.0.1:7700"),
}


_UDPM = LCM_URL_ADDRESSES["udpm"]


def lcm_provider(url: str) -> str:
    """The provider `url` names (the text before "://"), or "" when it names none."""
    return url.split("://", 1)[0] if "://" in url else ""


def _providers_text(providers) -> str:
    return " or ".join(f"{provider}://" for provider in providers)


LCM_URL_EXAMPLE = "udpm://239.255.76.67:7667?ttl=0"


def lcm_url_form_problem(url: str) -> str | None:
    """Why `url` does not parse as an LCM URL, PROVIDER://ADDRESS[?OPTION=VALUE&...] (for
    udpm:// and tcpq://, ADDRESS an IPv4 HOST[:PORT] (LCM_URL_ADDRESSES) and the value of
    each option of LCM_URL_OPTIONS a decimal integer LCM reads as written:
    _integer_text_problem), in words that follow "'URL': ", or None: a command line's
    --lcm-url that does not parse (exit 2). What a URL that parses names (a provider, an
    address, a port or option value out of range, an option) is lcm_url_problem's."""
    provider = lcm_provider(url)
    if not provider:
        return f"it names no provider (PROVIDER://ADDRESS); give e.g. {LCM_URL_EXAMPLE}"
    if provider not in LCM_URL_ADDRESSES:
        return None
    address, _, query = url.split("://", 1)[1].partition("?")
    form = LCM_URL_ADDRESSES[provider].form
    options = LCM_URL_OPTIONS[provider]
    for option in query.split("&") if query else ():
        key, _, value = option.partition("=")
        if key in options:
            problem = _integer_text_problem(value)
            if problem:
                return (f"{key} {shown(value)} {problem} ({key} is "
                        f"{_option_words(options[key])}); {form}")
    host, colon, port = address.partition(":")
    try:
        ipaddress.IPv4Address(host)
    except ValueError:
        if host:  # none: refused as no address, by lcm_url_problem
            resolved = (" (LCM's tcpq:// never resolves a host name: any name would connect "
                        "to 127.0.0.1)" if provider == "tcpq" else "")
            return f"address {shown(host)} is not an IPv4 address{resolved}; {form}"
    problem = _integer_text_problem(port) if colon else None
    if problem:
        return f"port {shown(port)} {problem}; {form}"
    return None


def _integer_text_problem(text: str) -> str | None:
    """Why `text` is not a decimal integer as LCM's strtol(base 0) reads it, in words that
    follow it, or None: digits after an optional '-' (no '+', `0x`, exponent or space) and
    no leading zero (strtol would read it as octal). A negative one is out of every range:
    the caller's range check names it."""
    digits = text.removeprefix("-")
    if not (digits.isascii() and digits.isdecimal()):
        return "is not a decimal integer"
    if len(digits) > 1 and digits.startswith("0"):
        return "has a leading zero (LCM would read it as octal)"
    return None


def _option_words(option: LcmUrlOption) -> str:
    """"WHAT, an integer from LOW to HIGH" for an option of LCM_URL_OPTIONS."""
    return f"{option.what}, an integer from {option.low} to {option.high}"


def lcm_url_option(text: str) -> str:
    """argparse's type of --lcm-url: the URL as given, or a usage error (exit 2) when it does
    not parse (lcm_url_form_problem). The default LCM_DEFAULT_URL set is the environment's,
    not the command line's: checked later, naming the variable (lcm_url_origin); a control
    character is refused before (usage_parser: exit 2 on the command line, 1 in a default)."""
    import argparse
    from tegrasp_drake.rig.typed_yaml import text_problem
    given = lcm_url_origin(text, "--lcm-url") == "--lcm-url" and not text_problem(text)
    problem = lcm_url_form_problem(text) if given else None
    if problem:  # argparse puts "argument --lcm-url: " before it
        raise argparse.ArgumentTypeError(f"{shown(text)}: {problem}")
    return text


def lcm_url_problem(url: str) -> str | None:
    """Why LCM cannot open `url` as a bus, or None (check_ranges refuses an empty one, which
    LCM would take for its default bus). A provider other than SHARED_LCM_PROVIDERS and
    IN_PROCESS_LCM_PROVIDERS is refused from the text, before LCM opens anything. The
    library's reason, printed on file descriptor 2, is captured so a bad URL is one line.
    A URL that does not parse is said so first (lcm_url_form_problem)."""
    form = lcm_url_form_problem(url)
    if form:
        return f"does not parse as an LCM URL: {form}"
    provider = lcm_provider(url)
    if provider not in SHARED_LCM_PROVIDERS + IN_PROCESS_LCM_PROVIDERS:
        return (f"is not an LCM bus URL: {_provider_named(provider)}; accepted: "
                f"{_providers_text(SHARED_LCM_PROVIDERS)} (and "
                f"{_providers_text(IN_PROCESS_LCM_PROVIDERS)} inside one process), e.g. "
                "udpm://239.255.76.67:7667?ttl=0")
    problem = _lcm_url_text_problem(url, provider)
    if problem:
        return f"{problem}; expected e.g. {LCM_URL_ADDRESSES.get(provider, _UDPM).example}"
    import lcm
    with tempfile.TemporaryFile() as captured:
        sys.stderr.flush()
        saved = os.dup(2)
        os.dup2(captured.fileno(), 2)
        try:
            lcm.LCM(url)
            failed = False
        except (RuntimeError, OSError):
            failed = True
        finally:
            os.dup2(saved, 2)
            os.close(saved)
        captured.seek(0)
        said = captured.read().decode(errors="replace").strip()
    invalid = [line for line in said.splitlines() if "invalid value" in line.lower()]
    if not failed and invalid:  # LCM warns of an option it did not take, runs with its default
        reason = invalid[0].removeprefix("Warning:").strip()
        return (f"has a value LCM does not take ({reason}; LCM would use its default); "
                "expected e.g. udpm://239.255.76.67:7667?ttl=0")
    if not failed:
        if said:
            print(said, file=sys.stderr)  # not ours to hide
        return None
    reason = said.splitlines()[-1].split(" -- ", 1)[-1].strip() if said else ""
    return (f"cannot be opened by LCM ({reason + '; ' if reason else ''}expected e.g. "
            "udpm://239.255.76.67:7667?ttl=0)")


def _lcm_url_text_problem(url: str, provider: str) -> str | None:
    """What LCM would ignore or misread in `url`, a URL of `provider`, from its text: a query
    option the provider does not take (LCM_URL_OPTIONS) or given twice, a value outside its
    option's range, and for udpm:// and tcpq:// an address not of the provider's kind
    (LCM_URL_ADDRESSES) or a port not from 1 to 65535. A value that is no decimal integer is
    lcm_url_form_problem's."""
    address, _, query = url.split("://", 1)[1].partition("?")
    accepted, seen = LCM_URL_OPTIONS[provider], set()
    takes = ("it takes " + "; ".join(f"{key}, {_option_words(option)}"
                                     for key, option in accepted.items())
             if accepted else "it takes none")
    for option in query.split("&") if query else ():
        key, _, value = option.partition("=")
        if not option:
            return (f"has an empty option (a '&' with nothing before or after it), which "
                    f"LCM's {provider}:// does not take ({takes})")
        if key not in accepted:
            return (f"has the option {shown(key)}, which LCM's {provider}:// does not "
                    f"take ({takes})")
        if key in seen:
            return f"gives the option {key} twice"
        seen.add(key)
        bounds = accepted[key]
        if not _decimal(value, (bounds.low, bounds.high)):
            return f"has {key}={shorten(value)}; {key} is {_option_words(bounds)}"
    if provider not in LCM_URL_ADDRESSES:
        return None
    host, colon, port = address.partition(":")
    problem = _lcm_host_problem(host, LCM_URL_ADDRESSES[provider].kind)
    if problem:
        return f"has {problem}"
    if colon and not _decimal(port, (1, 65535)):
        return f"has the port {shown(port)}, which is not a number from 1 to 65535"
    return None


def _lcm_host_problem(host: str, kind: str) -> str | None:
    """Why `host` is no IPv4 address of `kind` (LcmUrlAddress), in words that follow "has",
    or None."""
    try:
        address = ipaddress.IPv4Address(host)
    except ValueError:
        address = None
    if kind == "multicast":
        if address is None or not address.is_multicast:
            return (f"the address {shown(host)}, which is not a multicast IPv4 address "
                    "(224.0.0.0 to 239.255.255.255)")
        return None
    if address is None:
        return ("no host (LCM would connect to 127.0.0.1): give the lcm-tcpq server's IPv4 "
                "address") if not host else (
                f"the address {shown(host)}, which is not an IPv4 address")
    for test, words in ((address.is_unspecified, "the unspecified address (LCM would connect "
                         "to this host)"),
                        (address.is_multicast, "a multicast address"),
                        (address == ipaddress.IPv4Address("255.255.255.255"),
                         "the broadcast address"),
                        (address.is_reserved, "a reserved address (240.0.0.0/4)")):
        if test:
            return (f"the address {shown(host)}, which is {words}, not a server's: give the "
                    "lcm-tcpq server's IPv4 address")
    return None


def _decimal(text: str, bounds: tuple[int, int] | None = None) -> bool:
    """Whether `text` is ASCII digits (of a number within `bounds`, when given)."""
    if not (text.isascii() and text.isdecimal()):
        return False
    return bounds is None or (len(text) <= len(str(bounds[1])) and
                              bounds[0] <= int(text) <= bounds[1])


def _provider_named(provider: str) -> str:
    if not provider:
        return "it names no provider (PROVIDER://...)"
    if provider == "file":
        return ("file:// is LCM's event-log file, not a bus, and is not opened (it would be "
                "created or overwritten)")
    return f"{provider}:// is not one"


def shared_lcm_url_problem(url: str) -> str | None:
    """Why `url` is not a bus another process can reach (its provider, from the text, is not
    one of SHARED_LCM_PROVIDERS: an in-process memq:// bus, a file:// log; or LCM cannot open
    it: lcm_url_problem), or None: what a command that talks to another process over LCM
    (`tegrasp hardware` to the arm's driver, `tegrasp emulate` to `tegrasp hardware`) asks of
    its URL. Library code and tests may still run both ends in one process on memq://."""
    form = lcm_url_form_problem(url)
    if form:
        return f"does not parse as an LCM URL: {form}"
    provider = lcm_provider(url)
    if provider in IN_PROCESS_LCM_PROVIDERS:
        return (f"is a bus inside this one process ({provider}://), which no other process "
                f"can reach; give one they share ({_providers_text(SHARED_LCM_PROVIDERS)}), "
                "e.g. udpm://239.255.76.67:7667?ttl=0")
    if provider not in SHARED_LCM_PROVIDERS:
        return (f"is not a bus other processes share: {_provider_named(provider)}; accepted: "
                f"{_providers_text(SHARED_LCM_PROVIDERS)}, e.g. "
                "udpm://239.255.76.67:7667?ttl=0")
    return lcm_url_problem(url)


def same_serial_line(a: str, b: str) -> bool:
    """Whether two configured ports are one line: the same name, or the same device
    (same_path). pyserial URLs (`loop://`, `socket://...`) compare by name only, but spy://,
    which wraps a device, as that device."""
    a, b = wrapped_device(a), wrapped_device(b)
    if a == b:
        return True
    if "://" in a or "://" in b:
        return False
    return same_path(a, b)


def same_path(a: str, b: str) -> bool:
    """Whether two paths are one file or device: the same file after symlinks, or the same
    character device (st_rdev, e.g. /dev/serial/by-id/... and /dev/ttyUSB0). A path not
    there yet is compared by its resolved name."""
    if os.path.realpath(a) == os.path.realpath(b):
        return True
    try:
        first, second = os.stat(a), os.stat(b)
    except OSError:  # a port not there yet is opened (and named) when the devices start
        return False
    return ((first.st_dev, first.st_ino) == (second.st_dev, second.st_ino)
            or (stat.S_ISCHR(first.st_mode) and stat.S_ISCHR(second.st_mode)
                and first.st_rdev == second.st_rdev))


def shared_port_path(a: str, b: str) -> tuple[str, str, str] | None:
    """(path, what it is to `a`, what to `b`) of a device or file both ports open
    (serial_urls.named_paths: a device, spy://'s log file), else None: two spy:// ports
    logging to one file would interleave (and empty) each other's log; a spy log on the other
    device's port would write into that line."""
    for path_a, what_a in named_paths(a).items():
        for path_b, what_b in named_paths(b).items():
            if same_path(path_a, path_b):
                return path_a, what_a, what_b
    return None


def serial_port_problem(port: str) -> str | None:
    """Why `port` cannot be a serial device's port, in words that follow it, or None: a
    folder, a file, a pipe, a block device, or a character device that is no terminal
    (/dev/null takes every command and never answers, so the device would be blamed only
    when it times out). Nothing is opened (opening some boards' ports resets them). A port
    not there yet is opened, and named, when the devices start; a pyserial URL
    (`socket://HOST:PORT`, `loop://`) is checked from its text as pyserial reads it
    (serial_urls.py; its words say what to do)."""
    if is_serial_url(port):
        return serial_url_problem(port, serial_port_problem)
    try:
        mode = os.stat(port)
    except FileNotFoundError:
        return None
    except OSError as error:
        return f"cannot be used ({os_error_text(error)})"
    if stat.S_ISDIR(mode.st_mode):
        return "is a folder, not a serial device"
    if stat.S_ISREG(mode.st_mode):
        return "is a file, not a serial device"
    if not stat.S_ISCHR(mode.st_mode):
        return "is not a character device, so not a serial device"
    if _terminal_device(mode.st_rdev) is False:
        return "is a character device but not a terminal, so not a serial device"
    return None


def _terminal_device(rdev: int) -> bool | None:
    """Whether the character device `rdev` is a terminal (a serial line, a USB serial
    adapter, a pseudo-terminal such as the emulators' /dev/pts/N), by the kernel's class of
    it (sysfs; pseudo-terminals have no entry there, /proc/devices names them 'pts'); None
    where the system says neither."""
    major, minor = os.major(rdev), os.minor(rdev)
    entry = f"/sys/dev/char/{major}:{minor}"
    if os.path.exists(f"{entry}/subsystem"):
        return os.path.basename(os.path.realpath(f"{entry}/subsystem")) == "tty"
    try:
        with open("/proc/devices") as devices:
            for line in devices:
                if line.strip() == "Block devices:":
                    break
                number, _, name = line.strip().partition(" ")
                if number == str(major):
                    return name == "pts" or name.startswith("tty") or name == "/dev/tty"
    except OSError:
        return None
    return None


def gripper_read_period(config: HardwareStationConfig) -> float:
    """[s] between two of the gripper's status reads at the most: gripper.period, or the time
    a read and a command write take on the wire at gripper.baudrate if that is longer."""
    gripper = config.gripper
    on_wire = (registers.transaction_seconds(registers.READ_BYTES, gripper.baudrate)
               + registers.transaction_seconds(registers.WRITE_BYTES, gripper.baudrate))
    return max(gripper.period, on_wire)


def device_update_periods(config: HardwareStationConfig) -> dict[str, float]:
    """{device: the period [s] at which it updates what the watchdog reads}: the JACO2's
    statuses (JACO_LCM_PERIOD, the driver's 100 Hz), the gripper's reads
    (gripper_read_period), the myRIO's frames (TACTILE_FRAME.md, one a millisecond)."""
    return {"arm": JACO_LCM_PERIOD, "gripper": gripper_read_period(config),
            "tactile": TACTILE_FRAME_PERIOD_S}


def gripper_request_timeout_problem(config: HardwareStationConfig,
                                    prefix: str = "") -> str | None:
    """"field 'gripper.request_timeout' ..." when it is not longer than a command write and
    its answer take on the wire at gripper.baudrate (every such request would time out),
    else None."""
    gripper = config.gripper
    least = registers.transaction_seconds(registers.WRITE_BYTES, gripper.baudrate)
    if gripper.request_timeout > least:
        return None
    return (f"field '{prefix}gripper.request_timeout' is {number_text(gripper.request_timeout)}"
            f" s, not longer than a command write and its answer take at "
            f"{gripper.baudrate} baud ({number_text(least)} s on the wire), so every request "
            f"would time out: give more than {number_text(least)} s, or the 2F-85's "
            f"'{prefix}gripper.baudrate' {registers.BAUDRATE}")


def watchdog_least_timeouts(config: HardwareStationConfig, prefix: str = ""
                            ) -> list[tuple[str, float, str, str]]:
    """[(device, the timeout [s] its watchdog timeout must exceed, why, what else may be
    shortened instead, in words)]: more than WATCHDOG_MIN_PERIODS of its update periods
    (device_update_periods), so that one late update never trips it; for the gripper also
    more than one unanswered request (its request_timeout) and then WATCHDOG_MIN_PERIODS
    reads, so that one lost answer never does. The arm's and the myRIO's periods are their
    protocols' (no field sets them), and neither has a request to wait for."""
    rows = [(device, WATCHDOG_MIN_PERIODS * period,
             f"{WATCHDOG_MIN_PERIODS} of the {device}'s updates ({number_text(period)} s each)"
             f", so the watchdog would stop the run on the first late one", "")
            for device, period in device_update_periods(config).items()]
    gripper, read_period = config.gripper, gripper_read_period(config)
    rows.append(("gripper", gripper.request_timeout + WATCHDOG_MIN_PERIODS * read_period,
                 f"one unanswered request (field '{prefix}gripper.request_timeout', "
                 f"{number_text(gripper.request_timeout)} s) and then {WATCHDOG_MIN_PERIODS} "
                 f"of the gripper's reads ({number_text(read_period)} s each), so the "
                 "watchdog would stop the run on the first lost answer",
                 f", or a shorter '{prefix}gripper.request_timeout'"))
    return rows


def watchdog_timeouts_problem(config: HardwareStationConfig, prefix: str = "") -> str | None:
    """"field 'watchdog.<device>_timeout' ..." when a device's watchdog timeout is not longer
    than what the device's own timing lets it be silent for (watchdog_least_timeouts), else
    None. Of a device's rows the longest is said, so that its "give more than" suffices."""
    rows = sorted(watchdog_least_timeouts(config, prefix), key=lambda row: -row[1])
    for device, least, why, other in rows:
        timeout = config.watchdog.timeouts()[device]
        if not timeout > least:
            return (f"field '{prefix}watchdog.{device}_timeout' is {number_text(timeout)} s, not "
                    f"longer than {why}: give more than {number_text(least)} s (default "
                    f"{number_text(DeviceWatchdogConfig().timeouts()[device])} s){other}")
    return None


def validate_hardware_config(config: HardwareStationConfig, source: str,
                             where: str = "") -> HardwareStationConfig:
    """Checks each field's type (a config built in Python met no schema), then what the schema
    cannot (ranges and choices, LCM URL, calibration); ConfigError names the field."""
    prefix = f"{where}." if where else ""
    check_instance(config, source, where)
    check_ranges(config, source, where)
    problem = continuous_joints_problem(config.arm.tracker.continuous_joints)
    if problem:
        raise ConfigError(f"{source}: field '{prefix}arm.tracker.{problem[0]}' {problem[1]}, "
                          f"got {problem[2]}")
    problem = lcm_url_problem(config.arm.lcm_url)
    if problem:
        origin = lcm_url_origin(config.arm.lcm_url, f"field '{prefix}arm.lcm_url'")
        raise ConfigError(f"{source}: {origin} {problem}, got {shown(config.arm.lcm_url)}")
    problem = (gripper_request_timeout_problem(config, prefix)
               or watchdog_timeouts_problem(config, prefix))
    if problem:
        raise ConfigError(f"{source}: {problem}")
    tactile, gripper = config.tactile.port, config.gripper.port
    for field, port in (("tactile.port", tactile), ("gripper.port", gripper)):
        problem = serial_port_problem(port)
        if problem:
            advice = "" if is_serial_url(port) else (
                "; give the device's serial port (e.g. /dev/ttyUSB0, or the /dev/pts/N "
                "`tegrasp emulate` prints)")
            raise ConfigError(f"{source}: field '{prefix}{field}': {port} {problem}{advice}")
    if same_serial_line(tactile, gripper):
        raise ConfigError(
            f"{source}: fields '{prefix}tactile.port' ({shown(tactile)}) and "
            f"'{prefix}gripper.port' ({shown(gripper)}) are one serial line; each device needs "
            "its own (the myRIO's reader would take the gripper's answers): set one of them to "
            "its device's port")
    shared = shared_port_path(tactile, gripper)
    if shared:
        path, what_tactile, what_gripper = shared
        roles = (f"the {what_tactile} of each" if what_tactile == what_gripper else
                 f"the tactile port's {what_tactile}, the gripper port's {what_gripper}")
        raise ConfigError(
            f"{source}: fields '{prefix}tactile.port' ({shown(tactile)}) and "
            f"'{prefix}gripper.port' ({shown(gripper)}) both name {shown(path)} ({roles}); "
            "each port needs its own: give one of them another file")
    if config.tactile.calibration_file:  # read now, not when the devices start
        from tegrasp_drake.hardware.myrio.tactile_calibration import LoadTactileCalibration
        try:
            LoadTactileCalibration(config.tactile.calibration_file)
        except ConfigError as e:
            raise ConfigError(f"{source}: field '{prefix}tactile.calibration_file': "
                              f"{e}") from None
    return config


# The tag of the other station (scenario.SimulatedStationConfig), which a hardware config
# file may hold by mistake: the top-level tag is dropped on reading, so it is asked apart.
_SIMULATED_STATION_TAG = "!SimulatedStationConfig"


@public_api
def LoadHardwareConfig(filename: PathLike, overrides: typing.Sequence[str] = ()
                         ) -> HardwareStationConfig:
    """Reads a HardwareStationConfig mapping from YAML; ConfigError names a bad field.
    `overrides` may not set one key twice to two values (refuse_a_key_set_twice), as
    --config-set and a YAML mapping may not: neither would silently win."""
    refuse_a_key_set_twice(overrides, f"LoadHardwareConfig({shown(str(filename))})",
                           "overrides", kind="argument")
    try:
        data = read_yaml_file(filename, "the hardware config", kind=HardwareStationConfig)
    except ForeignTagError as e:
        if e.tag != _SIMULATED_STATION_TAG:
            raise
        raise ConfigError(f"{filename}: the file is a {_SIMULATED_STATION_TAG}, a simulated "
                          "station, not a hardware config: `tegrasp hardware` needs a "
                          "!HardwareStationConfig (or untagged hardware fields: arm, gripper, "
                          "tactile, ...); a simulated station runs with `tegrasp trial`") from None
    # Not a request for the default devices (/dev/ttyUSB0, /dev/ttyACM0): name them.
    require_fields(data, filename, "the hardware config", "give the devices' fields (arm, "
                   "gripper, tactile, ...; `tegrasp emulate all --write-config FILE` writes "
                   "one)")
    require_mapping(data, filename, "the hardware config", "HardwareStationConfig fields "
                    "(arm, gripper, tactile, watchdog, ...)")
    for assignment in overrides:
        apply_override(data, assignment, "--config-set", "tactile.port")
    return loaded_with_overrides(
        lambda source: validate_hardware_config(
            load_typed(data, HardwareStationConfig, source), source),
        str(filename), overrides, "--config-set")


def hardware_config_to_yaml(config: HardwareStationConfig) -> str:
    return yaml_dump_typed(config)
