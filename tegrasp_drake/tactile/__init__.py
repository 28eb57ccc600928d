"""The live tactile signal chain of Fig. 3: Eq. 1-2 channels (mechanoreceptor_channels),
the 0.5 s sliding window (sliding_window) and its max-normalisation (window_normalizer),
the sample rates and window lengths they share (sampling), the slip band
(slip_vibration_band) and the blocks in which the fast samples are taken (sample_block)."""

from tegrasp_drake.tactile.mechanoreceptor_channels import MakeMechanoreceptorChannels
from tegrasp_drake.tactile.sampling import rate_groups, resample_window, samples_per_window
from tegrasp_drake.tactile.window_normalizer import WindowNormalizer, WindowNormalizerConfig
