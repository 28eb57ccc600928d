"""LCM URLs are checked before a bus is opened: an in-process bus (memq://) that no other
process shares, a file URL that would overwrite a user's file, or a bad LCM_DEFAULT_URL is
refused in one line naming it, and the file is left whole."""

import os

import pytest

from tests.bad_input.probes import assert_one_line_error, run_cli
from tests.forked_runs import run_tegrasp


def test_a_bus_inside_the_process_is_said_not_to_be_logged(tmp_path):
    from tegrasp_drake.runs import hardware_run
    writer = hardware_run.BusLogWriter("memq://", tmp_path / "run.lcmlog")
    assert "lives inside this process" in writer.unrecorded
    assert writer.problem() is None and writer.close() == 0
    assert not (tmp_path / "run.lcmlog").exists()


# Rule: a command that talks over LCM to another process (the emulators to `tegrasp
# hardware`, `tegrasp hardware` to the arm's driver) refuses a bus that exists inside one
# process (memq://) in one line, before it starts anything; library code may still run both
# ends in one process on it.
@pytest.mark.parametrize("argv, words", [
    (["emulate", "jaco", "--lcm-url", "memq://", "--scheduling", "normal"],
     ["--lcm-url 'memq://'", "no other process can reach"]),
    (["hardware", "--config", "hw.yaml", "--config-set", "arm.lcm_url=memq://"],
     ["hw.yaml: field 'arm.lcm_url'", "no other process can reach"]),
])
def test_an_in_process_lcm_bus_is_refused_by_the_commands(tmp_path, monkeypatch, capfd, argv,
                                                          words):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    code, text = run_cli(argv, capfd)
    assert code == 1 and "\n" not in text.strip(), text
    for word in words:
        assert word in text, text


ACCEPTED_UDPM = ("which LCM's udpm:// does not take (it takes ttl, a multicast TTL, an integer "
                 "from 0 to 255; recv_buf_size, a socket receive buffer's size in bytes, an "
                 "integer from 1 to 2147483647)")


# Rule: an LCM URL's text is checked as LCM's providers read it: a query option the provider
# does not take (LCM would warn on stderr and run without it), an option given twice, a ttl
# no multicast socket takes, or a udpm:// address that is not multicast or a port that is not
# one is refused naming it, in every command that takes a URL (exit 1).
@pytest.mark.parametrize("url, words", [
    ("udpm://239.255.76.99:7699?tll=1", ["has the option 'tll'", ACCEPTED_UDPM]),
    ("udpm://239.255.76.99:7699?ttl=0&x=1", ["has the option 'x'", ACCEPTED_UDPM]),
    ("udpm://239.255.76.99:7699?ttl=0&ttl=1", ["gives the option ttl twice"]),
    ("udpm://239.255.76.99:7699?ttl=300", ["has ttl=300; ttl is a multicast TTL, an integer "
                                               "from 0 to 255"]),
    ("udpm://10.0.0.1:7699", ["has the address '10.0.0.1', which is not a multicast IPv4"]),
    ("udpm://239.255.76.99:0", ["has the port '0'"]),
    ("tcpq://127.0.0.1:7700?ttl=0", ["has the option 'ttl', which LCM's tcpq:// does not take "
                                     "(it takes none)"]),
    ("tcpq://0.0.0.0:7700", ["has the address '0.0.0.0', which is the unspecified address",
                             "expected e.g. tcpq://127.0.0.1:7700"]),
    ("tcpq://239.255.76.99:7700", ["has the address '239.255.76.99', which is a multicast "
                                   "address, not a server's"]),
    ("tcpq://255.255.255.255:7700", ["which is the broadcast address"]),
    ("tcpq://127.0.0.1:0", ["has the port '0', which is not a number from 1 to 65535"]),
    ("tcpq://:7700", ["has no host (LCM would connect to 127.0.0.1)"]),
])
@pytest.mark.parametrize("option", ["--lcm-url", "arm.lcm_url"])
def test_an_lcm_url_option_or_address_lcm_would_not_take_is_refused_naming_it(
        tmp_path, monkeypatch, capfd, url, words, option):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    if option == "--lcm-url":
        # in a process of its own: an emulator that took the URL would run until stopped
        run = run_tegrasp(["emulate", "jaco", "--lcm-url", url], tmp_path, timeout_s=120)
        code, text = run.returncode, run.stderr + run.stdout
    else:
        code, text = run_cli(["hardware", "--config", "hw.yaml", "--config-set",
                              f"arm.lcm_url={url}"], capfd)
    assert code == 1, text
    named = f"--lcm-url {url!r}" if option == "--lcm-url" else "field 'arm.lcm_url'"
    assert_one_line_error(code, text, "tegrasp: error:", named, *words)
    assert "lcm_udpm.c" not in text, text


# Rule: an LCM URL whose text does not parse (no PROVIDER://, a udpm:// port or ttl that is
# no number, an address that is no IPv4 address) is named by what does not parse, in the
# same words wherever it is given; as --lcm-url it is a command line that does not parse
# (exit 2, pointing to --help), as a config file's arm.lcm_url a file's field (exit 1). A URL
# that parses and names a provider no bus is (nope://) stays refused as bad input (exit 1).
FORM = "give udpm://GROUP:PORT, e.g. udpm://239.255.76.67:7667?ttl=0"
TCPQ_FORM = ("give tcpq://HOST:PORT with HOST the lcm-tcpq server's IPv4 address, e.g. "
             "tcpq://127.0.0.1:7700")


@pytest.mark.parametrize("url, words", [
    ("udpm://239.255.76.99:7699/", f"port '7699/' is not a decimal integer; {FORM}"),
    ("udpm://239.255.76.99:y", f"port 'y' is not a decimal integer; {FORM}"),
    ("udpm://239.255.76.99:7699?ttl=abc", f"ttl 'abc' is not a decimal integer (ttl is a "
                                            f"multicast TTL, an integer from 0 to 255); {FORM}"),
    ("udpm://bus:7699", f"address 'bus' is not an IPv4 address; {FORM}"),
    ("tcpq://lcm-server:7700", f"address 'lcm-server' is not an IPv4 address (LCM's tcpq:// "
                               f"never resolves a host name: any name would connect to "
                               f"127.0.0.1); {TCPQ_FORM}"),
    ("tcpq://127.1:7700", f"address '127.1' is not an IPv4 address (LCM's tcpq:// never "
                          f"resolves a host name: any name would connect to 127.0.0.1); "
                          f"{TCPQ_FORM}"),
    ("tcpq://127.0.0.1:07700", f"port '07700' has a leading zero (LCM would read it as "
                               f"octal); {TCPQ_FORM}"),
    ("tcpq://127.0.0.1:0x1e14", f"port '0x1e14' is not a decimal integer; {TCPQ_FORM}"),
    ("garbage", "it names no provider (PROVIDER://ADDRESS); give e.g. "
                "udpm://239.255.76.67:7667?ttl=0"),
])
@pytest.mark.parametrize("option", ["--lcm-url", "arm.lcm_url"])
def test_an_lcm_url_that_does_not_parse_is_a_usage_error_as_an_option(
        tmp_path, monkeypatch, capfd, url, words, option):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    if option == "--lcm-url":
        code, text = run_cli(["emulate", "jaco", "--lcm-url", url], capfd)
        assert code == 2, text
        assert_one_line_error(code, text, f"tegrasp: error: argument --lcm-url: "
                              f"{url!r}: {words} (see tegrasp emulate --help)")
    else:
        code, text = run_cli(["hardware", "--config", "hw.yaml", "--config-set",
                              f"arm.lcm_url={url}"], capfd)
        assert code == 1, text
        assert_one_line_error(code, text, "field 'arm.lcm_url' does not parse as an LCM URL: "
                              f"{words}, got {url!r}")


def test_an_lcm_url_of_a_provider_no_bus_is_stays_bad_input(capfd):
    code, text = run_cli(["emulate", "jaco", "--lcm-url", "nope://"], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "tegrasp: error: --lcm-url 'nope://' is not a bus other "
                          "processes share: nope:// is not one; accepted: udpm:// or tcpq://")
    assert "--help" not in text, text


def test_an_lcm_default_url_variable_that_does_not_parse_is_named_not_the_option(tmp_path):
    run = run_tegrasp(["emulate", "jaco"], tmp_path, timeout_s=120,
                      env={**os.environ, "LCM_DEFAULT_URL": "udpm://239.255.76.99:y"})
    assert run.returncode == 1, run.stderr
    assert_one_line_error(run.returncode, run.stderr, "tegrasp: error: the environment "
                          "variable LCM_DEFAULT_URL (the default of --lcm-url) "
                          f"'udpm://239.255.76.99:y' does not parse as an LCM URL: port 'y' "
                          f"is not a decimal integer; {FORM}")


def test_an_lcm_url_lcm_takes_is_accepted():
    from tegrasp_drake.hardware.config import lcm_url_problem
    for url in ("udpm://239.255.76.67:7667?ttl=1&recv_buf_size=2097152",
                "udpm://239.255.76.67:7667", "udpm://239.255.76.67", "memq://"):
        assert lcm_url_problem(url) is None, url


# Rule: each URL option has a declared range (LCM_URL_OPTIONS): a value outside it, or not
# written as a decimal integer LCM reads as written (strtol reads `010` as octal 8, `1e6` as
# 1, a negative ttl wrapped to 255), is refused naming the option and its range, as is a
# port with a leading zero (`07667`: port 4023).
@pytest.mark.parametrize("query, words", [
    ("recv_buf_size=0", "has recv_buf_size=0; recv_buf_size is a socket receive buffer's "
                        "size in bytes, an integer from 1 to 2147483647"),
    ("recv_buf_size=-5", "has recv_buf_size=-5; recv_buf_size is"),
    ("recv_buf_size=2147483648", "has recv_buf_size=2147483648; recv_buf_size is"),
    ("recv_buf_size=99999999999", "an integer from 1 to 2147483647"),
    ("recv_buf_size=1e6", "recv_buf_size '1e6' is not a decimal integer (recv_buf_size is a "
                          "socket receive buffer's size in bytes, an integer from 1 to "
                          "2147483647)"),
    ("recv_buf_size=0x10", "recv_buf_size '0x10' is not a decimal integer"),
    ("recv_buf_size=+5", "recv_buf_size '+5' is not a decimal integer"),
    ("ttl=-1", "has ttl=-1; ttl is a multicast TTL, an integer from 0 to 255"),
    ("ttl=010", "ttl '010' has a leading zero (LCM would read it as octal) (ttl is a "
                "multicast TTL, an integer from 0 to 255)"),
    ("ttl=0&", "has an empty option (a '&' with nothing before or after it)"),
])
def test_an_lcm_url_option_out_of_its_range_is_refused_naming_the_range(query, words):
    from tegrasp_drake.hardware.config import lcm_url_problem
    problem = lcm_url_problem(f"udpm://239.255.76.67:7667?{query}")
    assert problem and words in problem, problem
    problem = lcm_url_problem("udpm://239.255.76.67:07667")
    assert problem and "port '07667' has a leading zero" in problem, problem
    assert lcm_url_problem("udpm://239.255.76.67:7667?recv_buf_size=2147483647&ttl=255") is None


def test_an_lcm_url_option_out_of_range_in_a_hardware_config_names_the_field(tmp_path, capfd):
    _hardware_config(tmp_path, "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=0")
    code, text = run_cli(["hardware", "--config", str(tmp_path / "hw.yaml")], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "field 'arm.lcm_url' has recv_buf_size=0; "
                          "recv_buf_size is a socket receive buffer's size in bytes, an integer "
                          "from 1 to 2147483647")


# Rule: an LCM URL that cannot be used is named where it came from: the LCM_DEFAULT_URL
# environment variable when it gave the default (no field the user wrote), else the field.
@pytest.mark.parametrize("command", [
    ["hardware", "--config", "hw.yaml", "--scenario-name", "box", "--duration", "1"],
    ["emulate", "jaco"],
], ids=["hardware", "emulate"])
def test_a_bad_lcm_default_url_variable_is_named(tmp_path, command):
    (tmp_path / "hw.yaml").write_text("gripper: {port: /dev/ttyUSB0}\n")
    bad = "udpm://239.255.76.67:99999?ttl=0"
    run = run_tegrasp(command, tmp_path, timeout_s=120,
                      env={**os.environ, "LCM_DEFAULT_URL": bad})
    assert run.returncode == 1, run.stderr
    assert_one_line_error(run.returncode, run.stderr, "tegrasp: error:",
                          "environment variable LCM_DEFAULT_URL", bad)

# The same for a control character in the variable: refused naming the variable, not the
# option or field it is the default of, and never echoed raw.
@pytest.mark.parametrize("command, default_of", [
    (["hardware", "--config", "hw.yaml", "--scenario-name", "box", "--duration", "1"],
     "field 'arm.lcm_url'"),
    (["emulate", "jaco"], "--lcm-url"),
], ids=["hardware", "emulate"])
def test_a_control_character_in_the_lcm_default_url_variable_is_named(tmp_path, command,
                                                                     default_of):
    (tmp_path / "hw.yaml").write_text("gripper: {port: /dev/ttyUSB0}\n")
    run = run_tegrasp(command, tmp_path, timeout_s=120,
                      env={**os.environ, "LCM_DEFAULT_URL": "udpm://239.255.76.67:7667\x1b?ttl=0"})
    assert run.returncode == 1, run.stderr
    assert_one_line_error(run.returncode, run.stderr, "tegrasp: error: ", "the environment "
                          f"variable LCM_DEFAULT_URL (the default of {default_of}) holds an "
                          "escape (character 0x1b)", "'udpm://239.255.76.67:7667\\x1b?ttl=0'")
    assert "\x1b" not in run.stderr


PRECIOUS = "precious data\n"


# Rule: an LCM URL is checked from its text before LCM is given it: only the buses
# udpm:// and tcpq:// (and, for library code, memq://) are opened; file://, LCM's event-log
# provider, is refused without being opened, so checking it never creates or truncates the
# file it names (with ?mode=w, lcm.LCM(url) truncated it).
def test_a_file_lcm_url_is_refused_by_its_text_and_its_file_left_whole(tmp_path):
    from tegrasp_drake.hardware.config import lcm_url_problem, shared_lcm_url_problem
    precious = tmp_path / "precious.txt"
    precious.write_text(PRECIOUS)
    absent = tmp_path / "absent.lcmlog"
    for check in (lcm_url_problem, shared_lcm_url_problem):
        for url in (f"file://{precious}?mode=w", f"file://{absent}?mode=w"):
            problem = check(url)
            assert problem and "file://" in problem and "udpm://" in problem, problem
            assert "tcpq://" in problem, problem
    assert precious.read_text() == PRECIOUS
    assert not absent.exists()


def _hardware_config(tmp_path, url):
    """hw.yaml with arm.lcm_url `url`, or with no arm.lcm_url (its default) when None."""
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    config = HardwareStationConfig()
    text = hardware_config_to_yaml(config)
    line = f"  lcm_url: {config.arm.lcm_url}\n"
    assert line in text, text
    (tmp_path / "hw.yaml").write_text(
        text.replace(line, "" if url is None else f"  lcm_url: {url!r}\n"))


def _tegrasp(argv, cwd, environment=None):
    """(exit code, stderr) of `tegrasp ARGV` in its own process; an emulator that accepted
    the URL would run until stopped, so a run past the timeout fails the test."""
    done = run_tegrasp(argv, cwd, env=environment, timeout_s=60)
    return done.returncode, done.stderr


# Rule (the commands): `tegrasp hardware` (arm.lcm_url, or LCM_DEFAULT_URL as its default)
# and `tegrasp emulate` (--lcm-url, or LCM_DEFAULT_URL as its default) refuse a file:// URL
# in one line naming the field or variable and the providers accepted, and leave the file
# as it was.
@pytest.mark.parametrize("case", ["hardware", "hardware-variable", "emulate",
                                  "emulate-variable"])
def test_the_commands_refuse_a_file_lcm_url_and_leave_the_file_whole(tmp_path, case):
    precious = tmp_path / "precious.txt"
    precious.write_text(PRECIOUS)
    url = f"file://{precious}?mode=w"
    environment = dict(os.environ, PYTHONPATH=os.getcwd())
    if case.endswith("variable"):
        environment["LCM_DEFAULT_URL"] = url
    if case.startswith("hardware"):
        _hardware_config(tmp_path, None if case.endswith("variable") else url)
        argv = ["hardware", "--config", "hw.yaml", "--scenario-name", "box", "--set",
                "random_seed=690", "--log", "hw/run.lcmlog"]
        named = ("LCM_DEFAULT_URL" if case.endswith("variable")
                 else "hw.yaml: field 'arm.lcm_url'")
    else:
        argv = ["emulate", "jaco", "--scheduling", "normal"]
        if not case.endswith("variable"):
            argv += ["--lcm-url", url]
        named = "LCM_DEFAULT_URL" if case.endswith("variable") else "--lcm-url"
    code, text = _tegrasp(argv, tmp_path, environment)
    assert code == 1 and text.strip().count("\n") == 0, text
    for word in (named, "file://", "udpm://", "tcpq://"):
        assert word in text, text
    assert precious.read_text() == PRECIOUS
    assert not (tmp_path / "hw").exists()


def _tcpq_server():
    """A socket on 127.0.0.1 that answers LCM's tcpq handshake (the server's magic word and
    protocol version); its port."""
    import socket
    import struct
    import threading
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)

    def serve():
        while True:
            try:
                client, _ = server.accept()
            except OSError:
                return
            client.recv(8)
            client.sendall(struct.pack(">II", 0x287617fa, 0x0100))
            client.close()
    threading.Thread(target=serve, daemon=True).start()
    return server


# Rule: LCM 1.5.3's tcpq:// never resolves a host name: any name connects to 127.0.0.1. A
# name is refused even when a server listens on this host (which LCM would silently reach),
# and the server's IPv4 address is taken.
def test_a_tcpq_host_name_is_refused_though_lcm_would_reach_a_local_server(capfd):
    from tegrasp_drake.hardware.config import lcm_url_problem
    server = _tcpq_server()
    try:
        port = server.getsockname()[1]
        assert lcm_url_problem(f"tcpq://127.0.0.1:{port}") is None
        problem = lcm_url_problem(f"tcpq://lcm-server:{port}")
        assert problem is not None and "never resolves a host name" in problem, problem
    finally:
        server.close()
