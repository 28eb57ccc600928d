"""TactilePads: the 12-taxel capacitive arrays of both fingertip pads, sampled like an AD7147.

Each sample computes, for each pad, the normal force on each taxel from the hydroelastic
contact surfaces that involve the pad's geometry (contact_pressure.py), scales each surface's
taxel forces so that they sum to the normal component of the force the solver actually
applied (`F_Ac_W`; the pressure integral differs from it, see DRAKE-NOTES), then applies the
sensor model: constant offset, Gaussian noise, quantisation. Noise is drawn from a generator
seeded by (seed, sample index), so a trial is reproducible and the Context holds all state.
"""

import dataclasses
import functools

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.plant import ContactResults
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.simulation.capacitive_taxels import CapacitiveTaxelConfig
from tegrasp_drake.simulation.contact_pressure import (polygon_fan_triangles,
                                                       surfaces_taxel_normal_forces)

_NOISE_STREAM = 7001  # separates this sensor's random stream from others seeded alike


@dataclasses.dataclass
class TactileSensorConfig:
    """The capacitive taxel array of each pad (SA channel source).

    AD7147: 12 conversion stages at decimation 64 take about 9.2 ms (about 108 Hz); 1000 Hz
    is also selectable for an idealised sensor.

    transducer: "force", the taxel forces with the noise, quantisation and offset below (an
    ideal force sensor, as in the paper's simulation), or "capacitive", the real pad's
    parallel-plate taxels read by the AD7147 (capacitive_taxels.py, settings in
    `capacitive`; the force noise settings are then unused).
    """
    sample_rate_hz: float = 108.0
    noise_std_n: float = 0.005  # per taxel, Gaussian
    quantization_n: float = 0.001  # per taxel LSB; 0 disables
    offset_n: float = 0.0  # per taxel constant bias
    transducer: str = "force"
    capacitive: CapacitiveTaxelConfig = dataclasses.field(
        default_factory=CapacitiveTaxelConfig)


@dataclasses.dataclass(frozen=True)
class PadGeometry:
    """Where one pad is: its collision geometry and its frame P on body B (X_BP)."""
    geometry_id: object
    body_index: object
    X_BP: RigidTransform


@functools.lru_cache(maxsize=64)
def _fan_triangles(face_data: tuple) -> np.ndarray:
    """polygon_fan_triangles of a face_data tuple, remembered: a held grasp's surfaces keep
    their polygons from sample to sample while their vertices move. Read-only."""
    triangles = polygon_fan_triangles(face_data)
    triangles.flags.writeable = False
    return triangles


def _pad_surfaces(contact_results: ContactResults, X_WP: RigidTransform, geometry_id):
    """[(p_PV, pressure_V, triangles, applied normal force [N])] of each hydroelastic
    contact surface of the pad with `geometry_id`, vertices in the pad frame P."""
    surfaces = []
    X_PW = X_WP.inverse()
    z_W = X_WP.rotation().matrix()[:, 2].copy()
    for i in range(contact_results.num_hydroelastic_contacts()):
        info = contact_results.hydroelastic_contact_info(i)
        surface = info.contact_surface()
        if geometry_id not in (surface.id_M(), surface.id_N()):
            continue
        if surface.is_triangle():
            mesh, field = surface.tri_mesh_W(), surface.tri_e_MN()
            triangles = np.array([[t.vertex(k) for k in range(3)] for t in mesh.triangles()])
        else:
            mesh, field = surface.poly_mesh_W(), surface.poly_e_MN()
            triangles = _fan_triangles(tuple(mesh.face_data()))
        # Drake binds no bulk accessor: one call per vertex (map avoids a Python frame each).
        count = mesh.num_vertices()
        p_WV = np.array(list(map(mesh.vertex, range(count))))
        pressure = np.fromiter(map(field.EvaluateAtVertex, range(count)), float, count)
        p_PV = X_PW.multiply(p_WV.T).T
        applied = abs(float(info.F_Ac_W().translational() @ z_W))
        surfaces.append((p_PV, pressure, triangles, applied))
    return surfaces


def pads_forces_from_contacts(contact_results: ContactResults, pads) -> list[np.ndarray]:
    """The 12 taxel normal forces [N] (noise-free) of each pad (X_WP, geometry_id) in
    `pads`: each surface's pressure integral (contact_pressure.py, all surfaces of all pads
    in one pass) scaled to the normal force the solver applied on it."""
    per_pad = [_pad_surfaces(contact_results, X_WP, geometry_id) for X_WP, geometry_id in pads]
    surfaces = [surface for pad in per_pad for surface in pad]
    raws = iter(surfaces_taxel_normal_forces([s[:3] for s in surfaces]) if surfaces else [])
    result = []
    for pad in per_pad:
        forces = np.zeros(TAXELS_PER_PAD)
        for (_, _, _, applied), raw in zip(pad, raws):
            total = raw.sum()
            if total > 0:
                forces += raw * (applied / total)
        result.append(forces)
    return result


def apply_sensor_model(true_forces: np.ndarray, rng: np.random.Generator, noise_std: float,
                       quantization: float, offset: float) -> np.ndarray:
    """Measured taxel forces: offset plus Gaussian noise, then quantised to the LSB."""
    measured = true_forces + offset
    if noise_std > 0:
        measured = measured + rng.normal(0.0, noise_std, size=true_forces.shape)
    if quantization > 0:
        measured = np.round(measured / quantization) * quantization
    return measured


class TactilePads(LeafSystem):
    """Samples both pads' taxel arrays at a fixed rate.

    .. pydrake_system::

        name: TactilePads
        input_ports:
        - contact_results
        - body_poses
        output_ports:
        - left_taxel_forces
        - right_taxel_forces
        - true_taxel_forces

    Ports (the outputs are updated at `sample_rate_hz` and held in between):
        contact_results: the plant's ContactResults.
        body_poses: the plant's body poses (X_WB per body index).
        left_taxel_forces, right_taxel_forces: (12) measured normal forces [N] each, taxel
            order of taxel_layout.py.
        true_taxel_forces: (24) noise-free forces [N] (left then right), for evaluation.
    """

    def __init__(self, *, pads: dict, config: TactileSensorConfig, seed: int):
        super().__init__()
        self._pads = pads  # finger name -> PadGeometry
        self._config = config
        self._seed = int(seed)
        self._period = 1.0 / config.sample_rate_hz
        self._contact_port = self.DeclareAbstractInputPort(
            "contact_results", AbstractValue.Make(ContactResults()))
        self._poses_port = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()]))
        size = 2 * TAXELS_PER_PAD
        self._state = self.DeclareDiscreteState(2 * size)  # measured then true
        self.DeclarePeriodicDiscreteUpdateEvent(self._period, 0.0, self._sample)
        for k, finger in enumerate(FINGER_NAMES):
            self.DeclareVectorOutputPort(
                f"{finger}_taxel_forces", TAXELS_PER_PAD,
                lambda context, output, k=k: output.SetFromVector(
                    context.get_discrete_state(self._state).value()[
                        k * TAXELS_PER_PAD:(k + 1) * TAXELS_PER_PAD]),
                prerequisites_of_calc={self.discrete_state_ticket(self._state)})
        self.DeclareVectorOutputPort(
            "true_taxel_forces", size,
            lambda context, output: output.SetFromVector(
                context.get_discrete_state(self._state).value()[size:]),
            prerequisites_of_calc={self.discrete_state_ticket(self._state)})

    def _sample(self, context, discrete_state):
        contact_results = self._contact_port.Eval(context)
        poses = self._poses_port.Eval(context)
        true_forces = np.concatenate(pads_forces_from_contacts(contact_results, [
            (poses[int(pad.body_index)] @ pad.X_BP, pad.geometry_id)
            for pad in (self._pads[name] for name in FINGER_NAMES)]))
        sample_index = int(round(context.get_time() / self._period))
        rng = np.random.default_rng((self._seed, _NOISE_STREAM, sample_index))
        c = self._config
        measured = apply_sensor_model(true_forces, rng, c.noise_std_n, c.quantization_n,
                                      c.offset_n)
        discrete_state.set_value(self._state, np.concatenate([measured, true_forces]))
