"""The emulator walk-through of docs/hardware.md ("On the robot, or against emulators of it")
runs as written and ends Done: its `tegrasp` lines, each in a shell, in a fresh folder.

The lines come from the page itself, so the documented flow is the tested one: the
emulators run at the scheduling `tegrasp emulate` gives them by default, and the control
loop at the hardware config's, with nothing raised by the test. Two departures, neither in
what the commands do: the bus is this test's own (LCM_DEFAULT_URL, which every default LCM
URL honours), so that other runs on the host cannot cross it; and the test waits for the
emulators' "ready" line where a user waits to see it before typing the next command.
`lcm-logplayer` (plays the log back on the bus for minutes) is left out.
"""

import os
import pathlib
import re
import signal
import subprocess
import sys
import time

import pytest

PAGE = pathlib.Path(__file__).resolve().parent.parent / "docs" / "hardware.md"
SECTION = "# On the robot, or against emulators of it"
READY_TIMEOUT_S = 600.0  # a hang guard on a busy host, not a performance criterion


def walkthrough_lines() -> list[str]:
    """The `tegrasp` lines of the section's first code block, without their comments."""
    text = PAGE.read_text(encoding="utf-8")
    section = text[text.index(SECTION):]
    block = re.search(r"\n\n((?:    .*\n)+)", section).group(1)
    lines = [line.split("#")[0].strip() for line in block.splitlines()]
    return [line for line in lines if line.startswith("tegrasp ")]


def test_the_walkthrough_is_demo_emulate_in_the_background_hardware_replay():
    lines = walkthrough_lines()
    assert [line.split()[1] for line in lines] == ["demo", "emulate", "hardware", "replay"]
    assert lines[1].endswith("&") and not lines[2].endswith("&")


@pytest.mark.slow
def test_the_readme_emulator_walkthrough_ends_done(tmp_path):
    demo, emulate, hardware, replay = walkthrough_lines()
    env = dict(os.environ, PATH=f"{pathlib.Path(sys.executable).parent}:{os.environ['PATH']}",
               LCM_DEFAULT_URL=f"udpm://239.255.76.67:{8800 + os.getpid() % 1000}?ttl=0")

    def shell(line, **kwargs):
        return subprocess.run(["bash", "-c", line], cwd=tmp_path, env=env, text=True,
                              capture_output=True, **kwargs)

    assert shell(demo).returncode == 0
    with subprocess.Popen(["bash", "-c", f"exec {emulate.rstrip('&').strip()}"],
                          cwd=tmp_path, env=env, text=True, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT) as emulators:
        try:
            start, lines = time.monotonic(), []
            while not lines or lines[-1].strip() != "ready":
                line = emulators.stdout.readline()
                assert line and time.monotonic() - start < READY_TIMEOUT_S, "".join(lines)
                lines.append(line)
            assert any(line.startswith("scheduling: ") for line in lines)
            run = shell(hardware)
        finally:
            emulators.send_signal(signal.SIGINT)
            try:
                emulated, _ = emulators.communicate(timeout=60)
            except subprocess.TimeoutExpired:
                emulators.kill()
                emulated, _ = emulators.communicate()
        said = (run.stdout + run.stderr + f"\n--- tegrasp emulate (exit {emulators.returncode}) "
                "printed:\n"
                + "".join(lines) + (emulated or ""))
        assert run.returncode == 0, said
        assert re.search(r"-> Done\b", run.stdout), said
        assert shell(replay).returncode == 0
