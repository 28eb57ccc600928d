"""TactilePads: the 12-taxel arrays of both fingertip pads, sampled at the taxel rate. Each sample
integrates each contact surface's pressure over the taxels (contact_pressure.py), scales it to the
solver's normal force (docs/model.md, "Taxel forces from the contact surface"), then adds offset,
noise seeded by (seed, sample index) and quantisation."""

import dataclasses
import functools
import itertools

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import SurfaceTriangle
from pydrake.math import RigidTransform
from pydrake.multibody.plant import ContactResults
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.modelgen.robotiq_sdf import PAD_MODULUS
from tegrasp_drake.rig.ranges import (SAMPLE_RATE, bounded, within,
                                      chosen)
from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.robotiq.units import FORCE_MAX_N
from tegrasp_drake.simulation.capacitive_taxels import (TAXEL_TRANSDUCERS, CapacitiveTaxelConfig,
                                                        capacitive_readings,
                                                        counts_above_baseline,
                                                        noise_std_at_decimation)
from tegrasp_drake.simulation.contact_pressure import (cell_pressure_integrals,
                                                       polygon_fan_triangles,
                                                       surfaces_taxel_normal_forces)
from tegrasp_drake.rig.api_boundary import public_dataclass

_NOISE_STREAM = 7001  # separates this sensor's random stream from others seeded alike


@public_dataclass
@dataclasses.dataclass
class TactileSensorConfig:
    """The taxel array of each pad (docs/model.md, "The fingertip and its taxels") and the
    pad's elastomer. transducer: "capacitive" (the real pad's AD7147, settings in
    `capacitive`) or "force" (an ideal force sensor with the noise, quantisation and offset
    below, as the paper's simulation)."""
    # The pad elastomer's modulus [Pa]: the pads' hydroelastic modulus in contact (the hand's
    # model is given it when the station is built) and the E of the capacitive taxels'
    # compression d0 p / E; one number for both. The paper does not name the elastomer; the
    # default is the hand models' PAD_MODULUS (modelgen/robotiq_sdf.py), its plausible range
    # in docs/model.md ("What was guessed").
    pad_modulus_pa: float = bounded(PAD_MODULUS, low=1e5, high=5e7, unit="Pa",
                                    why="an elastomer: a gel-soft silicone is about 0.1 MPa, "
                                        "a hard rubber tens of MPa")
    sample_rate_hz: float = within(108.0, SAMPLE_RATE)
    # per taxel, Gaussian
    noise_std_n: float = bounded(0.005, low=0.0, high=1.0, unit="N",
                                 why="a taxel's noise is a few mN; 1 N would bury the 0.3 N "
                                     "contact threshold",
                                 below="must be zero (no noise) or positive [N]")
    # per taxel LSB; 0 disables
    quantization_n: float = bounded(0.001, low=0.0, high=1.0, unit="N",
                                    why="an LSB of the 12-bit taxel reading, far below the 0.3 N "
                                        "contact threshold",
                                    below="must be zero (no noise) or positive [N]")
    # per taxel constant bias
    offset_n: float = bounded(0.0, low=-5.0, high=5.0, unit="N",
                              why="a bias within the taxel's 5 N calibration point")
    transducer: str = chosen("capacitive", names=TAXEL_TRANSDUCERS,
                             why="ideal force taxels, or the AD7147's parallel-plate taxels")
    capacitive: CapacitiveTaxelConfig = dataclasses.field(
        default_factory=CapacitiveTaxelConfig)


# How far a taxel's Gaussian noise can carry one reading from its noise-free value, in noise
# sigmas. A trial logs at most 24 taxels x 20 kHz x 85 s = 4e7 readings (the largest taxel rate
# and the longest run, trial_log_file.most_transitions); a Gaussian passes 10 sigma on one side
# with probability 7.6e-24, so no trial's noise reaches it (6 sigma, 1e-9 a reading, could).
TAXEL_NOISE_SIGMAS = 10.0


def taxel_reading_range(config: TactileSensorConfig) -> tuple[float, float]:
    """The lowest and highest reading a taxel of `config` logs [N; counts above the baseline
    with the capacitive output "counts"]: its transducer's model (apply_sensor_model,
    capacitive_readings) at no force and at the most force, with TAXEL_NOISE_SIGMAS of noise.
    The force transducer does not clip: its reading is the offset plus noise at rest (below
    zero for a negative offset or noise) and at most the 2F-85's whole grip force (235 N,
    FORCE_MAX_N: a taxel carries a share of its pad's normal force, which the gripper's
    force-limited drive sets) plus offset and noise. The capacitive one clips at the AD7147's
    16-bit range, and its calibrated newtons at zero; its most is the elastomer at its
    minimum gap, or the converter's full scale."""
    if config.transducer == "capacitive":
        c = config.capacitive
        spread = TAXEL_NOISE_SIGMAS * noise_std_at_decimation(c)
        read = counts_above_baseline if c.output == "counts" else capacitive_readings
        return (float(read(0.0, c, -spread, pad_modulus_pa=config.pad_modulus_pa)),
                float(read(np.inf, c, spread, pad_modulus_pa=config.pad_modulus_pa)))
    spread = TAXEL_NOISE_SIGMAS * config.noise_std_n + config.quantization_n / 2
    return config.offset_n - spread, FORCE_MAX_N + config.offset_n + spread


@dataclasses.dataclass(frozen=True)
class PadGeometry:
    """Where one pad is: its collision geometry and its frame P on body B (X_BP)."""
    geometry_id: object
    body_index: object
    X_BP: RigidTransform


@functools.lru_cache(maxsize=64)
def _fan_triangles(face_data: tuple) -> np.ndarray:
    """polygon_fan_triangles remembered (a held grasp's polygons persist); read-only."""
    triangles = polygon_fan_triangles(face_data)
    triangles.flags.writeable = False
    return triangles


def triangle_corners(mesh) -> np.ndarray:
    """Vertex indices (T, 3) of a TriangleSurfaceMesh's triangles. pydrake binds no bulk
    accessor: one call per index, mapped (no Python frame per call)."""
    triangles = mesh.triangles()
    count = len(triangles)
    return np.column_stack([
        np.fromiter(map(SurfaceTriangle.vertex, triangles, itertools.repeat(k, count)), np.intp,
                    count) for k in range(3)])


def surface_arrays(surface) -> tuple:
    """(p_WV (V, 3) [m, world], pressure_V (V,) [Pa], triangles (T, 3)) of a ContactSurface,
    either representation (a polygon mesh fan-triangulated)."""
    if surface.is_triangle():
        mesh, field = surface.tri_mesh_W(), surface.tri_e_MN()
        triangles = triangle_corners(mesh)
        count = mesh.num_vertices()
        p_WV = np.concatenate(mesh.vertices()).reshape(count, 3)  # one call for all vertices
    else:
        mesh, field = surface.poly_mesh_W(), surface.poly_e_MN()
        triangles = _fan_triangles(tuple(mesh.face_data()))
        count = mesh.num_vertices()  # no bulk vertex accessor: one call per vertex, mapped
        p_WV = np.concatenate(list(map(mesh.vertex, range(count)))).reshape(count, 3)
    pressure = np.fromiter(map(field.EvaluateAtVertex, range(count)), float, count)
    return p_WV, pressure, triangles


def _surface_in_frame(info, X_PW: RigidTransform, z_W: np.ndarray, read_surface):
    """(p_PV, pressure_V, triangles, applied normal force [N]) of one contact, in frame P."""
    p_WV, pressure, triangles = read_surface(info.contact_surface())
    p_PV = X_PW.multiply(p_WV.T).T
    applied = abs(float(info.F_Ac_W().translational() @ z_W))
    return p_PV, pressure, triangles, applied


def _pads_surfaces(contact_results: ContactResults, geometry_ids, pad_poses,
                   read_surface=surface_arrays) -> list[list]:
    """Per pad: [(p_PV [m, pad frame], pressure_V, triangles, applied normal force [N])]."""
    per_pad = [[] for _ in geometry_ids]
    frames = None
    for i in range(contact_results.num_hydroelastic_contacts()):
        info = contact_results.hydroelastic_contact_info(i)
        surface = info.contact_surface()
        ids = (surface.id_M(), surface.id_N())
        for k, geometry_id in enumerate(geometry_ids):
            if geometry_id in ids:
                if frames is None:
                    frames = [(X_WP.inverse(), X_WP.rotation().matrix()[:, 2].copy())
                              for X_WP in pad_poses()]
                per_pad[k].append(_surface_in_frame(info, *frames[k], read_surface))
    return per_pad


def pads_forces(contact_results: ContactResults, geometry_ids, pad_poses, *,
                read_surface=surface_arrays,
                cell_integrals=cell_pressure_integrals) -> list[np.ndarray]:
    """Each pad's 12 noise-free taxel forces [N]: pressure integrals scaled to the solver's.
    read_surface and cell_integrals: surface_arrays' and cell_pressure_integrals' signatures
    (benchmarks and tests pass the plain ways of doing the same)."""
    per_pad = _pads_surfaces(contact_results, geometry_ids, pad_poses, read_surface)
    surfaces = [surface for pad in per_pad for surface in pad]
    raws = iter(surfaces_taxel_normal_forces([s[:3] for s in surfaces], cell_integrals)
                if surfaces else [])
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

    Ports: contact_results, body_poses: the plant's; left_taxel_forces, right_taxel_forces:
    (12) measured forces [N] (rig/taxel_layout.py's order); true_taxel_forces: (24)
    noise-free, left then right; each output updated at `sample_rate_hz`.
    """

    def __init__(self, *, pads: dict, config: TactileSensorConfig, seed: int):
        super().__init__()
        self._pads = [pads[name] for name in FINGER_NAMES]  # PadGeometry of each finger
        self._geometry_ids = [pad.geometry_id for pad in self._pads]
        self._config = config
        self._seed = int(seed)
        self._period = 1.0 / config.sample_rate_hz
        self._contact_port = self.DeclareAbstractInputPort(
            "contact_results", AbstractValue.Make(ContactResults()))
        self._poses_port = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()]))
        # One state group per output port (state output ports need no Python call).
        self._measured = [self.DeclareDiscreteState(TAXELS_PER_PAD) for _ in FINGER_NAMES]
        self._true = self.DeclareDiscreteState(len(FINGER_NAMES) * TAXELS_PER_PAD)
        self.DeclarePeriodicDiscreteUpdateEvent(self._period, 0.0, self._sample)
        for finger, measured in zip(FINGER_NAMES, self._measured):
            self.DeclareStateOutputPort(f"{finger}_taxel_forces", measured)
        self.DeclareStateOutputPort("true_taxel_forces", self._true)

    def _pad_poses(self, context) -> list[RigidTransform]:
        """X_WP of each finger's pad."""
        poses = self._poses_port.Eval(context)
        return [poses[int(pad.body_index)] @ pad.X_BP for pad in self._pads]

    def _sample(self, context, discrete_state):
        contact_results = self._contact_port.Eval(context)
        true_forces = np.concatenate(pads_forces(
            contact_results, self._geometry_ids, lambda: self._pad_poses(context)))
        sample_index = int(round(context.get_time() / self._period))
        rng = np.random.default_rng((self._seed, _NOISE_STREAM, sample_index))
        c = self._config
        measured = apply_sensor_model(true_forces, rng, c.noise_std_n, c.quantization_n,
                                      c.offset_n)
        for k, group in enumerate(self._measured):
            discrete_state.set_value(
                group, measured[k * TAXELS_PER_PAD:(k + 1) * TAXELS_PER_PAD])
        discrete_state.set_value(self._true, true_forces)
