"""TaxelForceDisplay: each pad's 12 taxel forces drawn in Meshcat, live and in the
recording: a bar per taxel on the back of its finger, growing with the force, yellow to dark
red; below the threshold a thin grey tile. The recording gets "material.color" and the live
viewer "color": Meshcat's SetProperty of "material.color" turns the live bar black."""

import dataclasses

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import Box, Rgba
from pydrake.math import RigidTransform
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.rig.taxel_layout import CELL_X, CELL_Y, taxel_centers

# Yellow -> orange -> red -> dark red (ColorBrewer YlOrRd's FED976, FD8D3C, E31A1C, 800026)
# at 0, 1/3, 2/3 and 1 of full scale; its paler steps vanish against the table.
_FORCE_COLORS = np.array([[0.996, 0.851, 0.463], [0.992, 0.553, 0.235], [0.890, 0.102, 0.110],
                          [0.502, 0.000, 0.149]])
_IDLE_COLOR = (0.55, 0.57, 0.62)  # a taxel below the threshold
_BAR_FILL = 0.8  # a bar's cross-section, as a fraction of its taxel cell
_TILE_LENGTH_M = 0.0005  # the grey tile of an idle taxel


@dataclasses.dataclass
class TaxelForceDisplayConfig:
    """How the taxel forces are drawn; display scales, chosen so that a 25 N grip on one row
    of 3 taxels (about 8 N each) gives the longest bars (2 cm) and the darkest colour."""
    meters_per_newton: float = 0.0025
    full_scale_n: float = 8.0  # the darkest colour
    visible_threshold_n: float = 0.05  # 10 x the taxels' noise (TactileSensorConfig)
    back_offset_m: float = 0.015  # pad face to finger back: 4 mm pad, 10 mm finger, 1 mm gap
    publish_period_s: float = 1.0 / 32.0  # as Drake's ContactVisualizer


def taxel_force_color(force_n: float, full_scale_n: float) -> tuple[float, float, float]:
    """The bar colour (r, g, b in 0..1) of a taxel force [N]: linear between the anchors."""
    x = float(np.clip(force_n / full_scale_n, 0.0, 1.0)) * (len(_FORCE_COLORS) - 1)
    i = min(int(x), len(_FORCE_COLORS) - 2)
    return tuple(float(c) for c in _FORCE_COLORS[i] + (x - i) * (_FORCE_COLORS[i + 1] -
                                                                   _FORCE_COLORS[i]))


def taxel_bar_length(force_n: float, config: TaxelForceDisplayConfig) -> float:
    """The bar's length [m] for a taxel force [N]; the tile's below the threshold."""
    if force_n < config.visible_threshold_n:
        return _TILE_LENGTH_M
    return max(force_n * config.meters_per_newton, _TILE_LENGTH_M)


class TaxelForceDisplay(LeafSystem):
    """Draws both pads' taxel forces in Meshcat (see the module docstring).

    .. pydrake_system::

        name: TaxelForceDisplay
        input_ports:
        - body_poses
        - left_taxel_forces
        - right_taxel_forces

    Ports: body_poses (the plant's X_WB); *_taxel_forces (12, N).
    """

    def __init__(self, *, meshcat, pads: dict, config: TaxelForceDisplayConfig,
                 prefix: str = "taxel_forces"):
        super().__init__()
        self._meshcat = meshcat  # a resource, as Drake's visualizers hold it; no state
        self._pads = pads  # finger name -> PadGeometry (body index, X_BP)
        self._config = config
        self._prefix = f"/{prefix.strip('/')}"
        self._poses_port = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()]))
        self._force_ports = {finger: self.DeclareVectorInputPort(
            f"{finger}_taxel_forces", TAXELS_PER_PAD) for finger in FINGER_NAMES}
        self.DeclarePeriodicPublishEvent(config.publish_period_s, 0.0, self._publish)
        self.DeclareForcedPublishEvent(self._publish)
        self._add_bars()

    def _bar_path(self, finger: str, k: int) -> str:
        return f"{self._prefix}/{finger}/taxel_{k:02d}"

    def _add_bars(self):
        """One unit bar per taxel on the finger's back, scaled in z [m] outward (pad frame -z)."""
        bar = Box(_BAR_FILL * CELL_X, _BAR_FILL * CELL_Y, 1.0)
        for finger in FINGER_NAMES:
            for k, p_PoTk_P in enumerate(taxel_centers()):
                path = self._bar_path(finger, k)
                base = p_PoTk_P - [0.0, 0.0, self._config.back_offset_m]
                self._meshcat.SetTransform(path, RigidTransform(base))
                self._meshcat.SetObject(f"{path}/bar", bar, Rgba(*_IDLE_COLOR, 1.0))
                self._meshcat.SetTransform(f"{path}/bar", RigidTransform([0.0, 0.0, -0.5]))
                self._meshcat.SetProperty(path, "scale", [1.0, 1.0, _TILE_LENGTH_M])

    def _publish(self, context):
        time = context.get_time()
        poses = self._poses_port.Eval(context)
        recording = self._meshcat.get_mutable_recording()
        frame = recording.frame(time)
        for finger in FINGER_NAMES:
            pad = self._pads[finger]
            self._meshcat.SetTransform(f"{self._prefix}/{finger}",
                                       poses[int(pad.body_index)] @ pad.X_BP, time)
            forces = self._force_ports[finger].Eval(context)
            for k, force in enumerate(forces):
                path = self._bar_path(finger, k)
                self._meshcat.SetProperty(path, "scale",
                                          [1.0, 1.0, taxel_bar_length(force, self._config)],
                                          time)
                rgb = (_IDLE_COLOR if force < self._config.visible_threshold_n
                       else taxel_force_color(force, self._config.full_scale_n))
                self._meshcat.SetProperty(f"{path}/bar", "color", [*rgb, 1.0])
                recording.SetProperty(frame, f"{path}/bar/<object>", "material.color",
                                      list(rgb))
