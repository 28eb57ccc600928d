"""Names and order of the four mechanoreceptor channels used everywhere in the project.

Eq. 1 of the paper gives the slowly adapting (SA) channel of finger i as the sum of its 12
taxel normal forces [N]; Eq. 2 gives the rapidly adapting (RA) channel as the magnitude of
its pad's vibration signal [m/s^2]. Every vector of the four channels uses this order.
"""

CHANNEL_NAMES = ("sa_left", "sa_right", "ra_left", "ra_right")
SA_CHANNELS = (0, 1)
RA_CHANNELS = (2, 3)
FINGER_NAMES = ("left", "right")
TAXELS_PER_PAD = 12
