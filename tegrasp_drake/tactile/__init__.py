"""The live tactile signal chain of Fig. 3.

  mechanoreceptor_channels.py  Eq. 1 (SA) and Eq. 2 (RA) of both fingers
  sliding_window.py            the last N samples of a few channels in a Context's state
  window_normalizer.py         the 0.5 s windows, normalised by their maximum
  max_normalization.py         the paper's normalisation of a window by its maximum
  sampling.py                  sample rates, window lengths and template resampling
  sample_block.py              fast samples kept in C++ and read once per block
  read_batch.py                a tick's fast samples read in one update before the tick
  slip_vibration_band.py       the pads' vibration in the slip band, for Lift-Load
  slip_band_diagram.py         the per-tick slip band as compiled Drake systems
  ra_tick_peak.py              each film's peak |RA| over a controller tick, compiled"""

from tegrasp_drake.tactile.mechanoreceptor_channels import MakeMechanoreceptorChannels
from tegrasp_drake.tactile.sampling import rate_groups, resample_window, samples_per_window
from tegrasp_drake.tactile.window_normalizer import WindowNormalizer, WindowNormalizerConfig
