"""Names and order of the four mechanoreceptor channels: SA of finger i, the sum of its 12
taxel forces [N] (Eq. 1); RA, the magnitude of its pad's vibration [m/s^2] (Eq. 2)."""

CHANNEL_NAMES = ("sa_left", "sa_right", "ra_left", "ra_right")
SA_CHANNELS = (0, 1)
RA_CHANNELS = (2, 3)
FINGER_NAMES = ("left", "right")
TAXELS_PER_PAD = 12
