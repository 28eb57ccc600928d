"""A virtual null-modem cable (like `socat pty pty`): two pseudo-terminals whose masters a
thread joins, so an emulated device and the driver under test both open a tty by name.
`connected = False` unplugs it (bytes discarded both ways); `to_device` maps what the host
sends to what reaches the device (e.g. a framer that drops what a real receiver would), and
`answer_host` lets that map reply to the host itself (what a receiver answers on its own)."""

import os
import select
import threading
import tty


def open_raw_pty() -> tuple[int, int, str]:
    """A pseudo-terminal (master fd, slave fd, slave tty name) with the slave in raw mode."""
    master, slave = os.openpty()
    tty.setraw(slave)
    os.set_blocking(master, False)
    return master, slave, os.ttyname(slave)


class NullModem:
    """Joins two pseudo-terminals, `device_port` and `host_port`; the relay wakes at least every
    `poll_interval` [s]. Use as a context manager."""

    def __init__(self, *, poll_interval: float = 0.02, to_device=None):
        self._poll_interval = poll_interval
        self._to_device = to_device
        self._device = open_raw_pty()
        self._host = open_raw_pty()
        self._stop = threading.Event()
        self.connected = True
        self.bytes_relayed = 0
        self.bytes_dropped = 0  # the reading side's buffer was full (a UART overrun)
        self._thread = threading.Thread(target=self._relay, name="null modem", daemon=True)
        self._thread.start()

    @property
    def device_port(self) -> str:
        return self._device[2]

    @property
    def host_port(self) -> str:
        return self._host[2]

    def _relay(self):
        masters = {self._device[0]: self._host[0], self._host[0]: self._device[0]}
        while not self._stop.is_set():
            readable, _, _ = select.select(list(masters), [], [], self._poll_interval)
            for source in readable:
                try:
                    data = os.read(source, 4096)
                except OSError:  # nothing after all, or the tty is being reopened
                    continue
                if data and self.connected:
                    if source == self._host[0] and self._to_device is not None:
                        data = self._to_device(data)
                    if data:
                        self._forward(masters[source], data)

    def answer_host(self, data: bytes):
        """Sends `data` to the host as if from the device (unplugged: discarded)."""
        if self.connected:
            self._forward(self._host[0], data)

    def _forward(self, master, data):
        try:
            written = os.write(master, data)
        except BlockingIOError:
            written = 0
        self.bytes_relayed += written
        self.bytes_dropped += len(data) - written

    def close(self):
        self._stop.set()
        self._thread.join(2.0)
        for master, slave, _ in (self._device, self._host):
            os.close(master)
            os.close(slave)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
