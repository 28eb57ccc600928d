"""LCM's time stamps: `utime` is an integer number of microseconds in every message."""


def utime_from_time(time_s: float) -> int:
    """Microseconds (LCM `utime`) for a time in seconds."""
    return int(round(time_s * 1e6))
