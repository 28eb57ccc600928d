"""FilmLoads: what loads each pad's film over one plant step: the slow modal load
L = F + m a_n [N] and the direct loads d [N] at the step's n internal instants (the impact's
half-sine at a contact's onset, the slip texture). The impact needs the plant's abstract
ports, so this is the chain's one Python system; its memory is in its output, which the
chain holds and feeds back (`held`). docs/model.md, "Vibration (RA) model"."""

import dataclasses
import math
import typing

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialAcceleration, SpatialVelocity
from pydrake.multibody.plant import ContactResults
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.simulation.film_dynamics import (STATE_SIZE, FilmStepMatrices,
                                                    halfsine_mean_forces, impact_pulse)
from tegrasp_drake.simulation.pad_slip_vibration import UPDATE_PERIOD_S as TEXTURE_PERIOD_S
from tegrasp_drake.simulation.pad_slip_vibration import texture_acceleration

if typing.TYPE_CHECKING:  # the films' config lives with the station's sensor settings
    from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig

# A pad's contact begins on the step whose normal force exceeds this [N] after one at or below
# it (the plant's force is exactly zero out of contact).
CONTACT_ONSET_N = 1e-6
# Slip textures weaker than this [m/s^2] are not integrated: 5e4 times below the sensor
# noise (a held object's creep gives about 1e-7).
TEXTURE_FLOOR_MPS2 = 1e-6

# film_loads' layout (FilmLoads' ports).
LOADS = slice(0, 2)
FORCES = slice(2, 4)
ONSETS, IMPULSES, DURATIONS = slice(4, 6), slice(6, 8), slice(8, 10)
PULSES = slice(4, 10)
MEMORY = slice(2, 10)  # what the next step reads back: FORCES and PULSES
DIRECT_START = 10
# The chain's hold: MEMORY one plant step ago, then both films' states.
HELD_SIZE = MEMORY.stop - MEMORY.start + 2 * STATE_SIZE


def film_loads_size(substeps: int) -> int:
    """The size of film_loads for `substeps` internal instants per plant step."""
    return DIRECT_START + 2 * substeps


def _point_velocity_before_step(X_WB: RigidTransform, V_WB: SpatialVelocity,
                                A_WB: SpatialAcceleration, p_WQ: np.ndarray,
                                time_step: float) -> np.ndarray:
    """Velocity [m/s] of body B's material point at p_WQ one plant step earlier."""
    r = p_WQ - X_WB.translation()
    w, alpha = V_WB.rotational(), A_WB.rotational()
    velocity = V_WB.translational() + np.cross(w, r)
    acceleration = A_WB.translational() + np.cross(alpha, r) + np.cross(w, np.cross(w, r))
    return velocity - time_step * acceleration


@dataclasses.dataclass(frozen=True)
class SignalLayout:
    """Where FilmLoads finds each vector signal in `signals`: their sizes in order (0: unused)."""
    forces: int
    gripper_state: int
    texture: int
    substeps: int

    @property
    def sizes(self) -> list[int]:
        return [self.forces, self.gripper_state, 3, 3, self.texture, HELD_SIZE]

    @property
    def names(self) -> list[str]:
        return ["generalized_contact_forces", "gripper_state", "left_pad_frame_acceleration",
                "right_pad_frame_acceleration", "texture_state", "held"]

    def slices(self) -> dict[str, slice]:
        starts = np.concatenate([[0], np.cumsum(self.sizes)]).tolist()
        return {name: slice(start, start + size)
                for name, start, size in zip(self.names, starts, self.sizes)}


class FilmLoads(LeafSystem):
    """Both pads' film loads over the plant step that ends now.

    .. pydrake_system::

        name: FilmLoads
        input_ports:
        - signals
        - contact_results
        - body_poses
        - body_spatial_velocities
        - body_spatial_accelerations
        output_ports:
        - film_loads

    Ports:
        signals: the vector inputs, one after the other (SignalLayout; one port, one read
            from Python a step): the gripper's generalized contact forces (entry
            force_indices[k] finger k's, positive pushing its pad outward [N]; or
            PadNormalForces' output; or, with `pad_statics`, the whole instance's), its
            state (with `pad_statics` only), each pad frame's acceleration without gravity
            (3, m/s^2, pad frame), PadSlipVibration's texture_state (6, with `with_texture`
            only) and the chain's hold (HELD_SIZE).
        contact_results, body_poses, body_spatial_velocities, body_spatial_accelerations:
            the plant's; read only on the plant step where a pad's contact begins.
        film_loads: (10 + 2 n) the loads of the step that ends now: [0:2] L of the left
            and right pads [N]; [2:4] F [N]; each pad's impact onset [s] [4:6], impulse
            [N s] [6:8] (0: none) and duration [s] [8:10]; then d of the left, then the
            right pad at the n instants, oldest first [N].
    """

    def __init__(self, *, plant, pads: dict, force_indices, config: "VibrationSensorConfig",
                 pad_modulus_pa: float, matrices: FilmStepMatrices, with_texture: bool = False,
                 pad_statics=None):
        """pad_modulus_pa: the pads' elastomer modulus [Pa] (tactile.pad_modulus_pa), which
        the impact's stiffness follows (impact_stiffness); matrices: the film's step
        (film_step_matrices); pad_statics: or None."""
        from tegrasp_drake.simulation.pad_vibration_sensor import impact_stiffness
        super().__init__()
        self._dt = plant.time_step()
        self._pads = [pads[finger] for finger in FINGER_NAMES]
        self._config = config
        self._impact_stiffness = impact_stiffness(config.film, pad_modulus_pa)  # [N/m]
        self._matrices = matrices
        self._midpoints = matrices.substep_starts + 0.5 * matrices.h
        self._texture_period_m = config.slip_texture_period_m
        # For a contact onset: each collision geometry's body, its mass, inf if welded.
        self._geometry_body = {}
        self._mass = {}
        for i in range(plant.num_bodies()):
            body = plant.get_body(BodyIndex(i))
            self._mass[i] = body.default_mass()
            for geometry in plant.GetCollisionGeometriesForBody(body):
                self._geometry_body[geometry] = i
        for body in plant.GetBodiesWeldedTo(plant.world_body()):
            self._mass[int(body.index())] = math.inf

        self._statics = pad_statics
        left_index, right_index = (int(i) for i in force_indices)
        self.layout = SignalLayout(
            forces=(max(left_index, right_index) + 1 if pad_statics is None
                    else pad_statics.velocities),
            gripper_state=0 if pad_statics is None else pad_statics.states,
            texture=3 * len(FINGER_NAMES) if with_texture else 0, substeps=matrices.substeps)
        where = self.layout.slices()
        self._forces, self._gripper_state = where["generalized_contact_forces"], \
            where["gripper_state"]
        self._left_force, self._right_force = (self._forces.start + left_index,
                                               self._forces.start + right_index)
        # The accelerations' normal (z) entries; the last step's forces and pulses.
        self._normal_accelerations = (where["left_pad_frame_acceleration"].start + 2,
                                      where["right_pad_frame_acceleration"].start + 2)
        held = where["held"].start - MEMORY.start  # film_loads' index i is at held + i
        self._previous_forces = slice(held + FORCES.start, held + FORCES.stop)
        self._previous_pulses = slice(held + PULSES.start, held + PULSES.stop)
        self._texture = where["texture_state"] if with_texture else None
        self._signals = self.DeclareVectorInputPort("signals", sum(self.layout.sizes))
        self._contacts = self.DeclareAbstractInputPort(
            "contact_results", AbstractValue.Make(ContactResults()))
        self._poses = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()]))
        self._velocities = self.DeclareAbstractInputPort(
            "body_spatial_velocities", AbstractValue.Make([SpatialVelocity()]))
        self._body_accelerations = self.DeclareAbstractInputPort(
            "body_spatial_accelerations", AbstractValue.Make([SpatialAcceleration()]))
        self._no_direct = [0.0] * (2 * matrices.substeps)
        self.DeclareVectorOutputPort("film_loads", film_loads_size(matrices.substeps),
                                     self._calc)

    @property
    def impact_stiffness_n_per_m(self) -> float:
        """The pad's stiffness [N/m] its impact model uses (impact_stiffness)."""
        return self._impact_stiffness

    def _calc(self, context, output):
        # Python floats: per plant step numpy's scalar overhead would exceed the arithmetic.
        signals = self._signals.Eval(context)
        values = signals.tolist()
        if self._statics is None:
            left, right = values[self._left_force], values[self._right_force]
        else:
            left, right = self._statics.normal_forces(values[self._forces],
                                                      values[self._gripper_state])
        time = context.get_time()
        if time < 0.5 * self._dt:  # no plant step has ended yet
            output.SetFromVector([0.0, 0.0, left, right, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
                                 + self._no_direct)
            return
        before_left, before_right = values[self._previous_forces]
        pulses = values[self._previous_pulses]  # onsets, impulses, durations
        m = self._config.film.mode_mass_kg
        loads = [left + m * values[self._normal_accelerations[0]],
                 right + m * values[self._normal_accelerations[1]], left, right]
        onsets = (abs(left) > CONTACT_ONSET_N >= abs(before_left),
                  abs(right) > CONTACT_ONSET_N >= abs(before_right))
        step_start = time - self._dt
        if self._config.film.impact_enabled and (onsets[0] or onsets[1]):
            self._start_impacts(context, onsets, step_start, pulses)
        direct = None
        if pulses[2] > 0.0 or pulses[3] > 0.0:  # an impulse is under way
            direct = self._impact_loads(step_start, pulses)
        if self._texture is not None and (left != 0.0 or right != 0.0):
            texture = self._texture_loads(signals[self._texture], step_start)
            if texture is not None:
                direct = texture if direct is None else direct + texture
        written = output.get_mutable_value()
        written[:DIRECT_START] = loads + pulses
        written[DIRECT_START:] = 0.0 if direct is None else direct.T.ravel()

    def _impact_loads(self, step_start: float, pulses: list):
        """(n, 2) impact forces [N] over the step's instants, or None; marks delivered pulses."""
        impulses = pulses[2:4]
        if impulses[0] <= 0.0 and impulses[1] <= 0.0:
            return None
        direct = None
        for k in (0, 1):
            onset, duration = pulses[k], pulses[4 + k]
            if impulses[k] <= 0.0 or step_start >= onset + duration:
                continue
            if direct is None:
                direct = np.zeros((self._matrices.substeps, 2))
            direct[:, k] = halfsine_mean_forces(step_start, self._matrices.substep_starts,
                                                self._matrices.h, onset, impulses[k], duration)
            if step_start + self._dt >= onset + duration:
                pulses[2 + k] = 0.0  # delivered
        return direct

    def _texture_loads(self, texture: np.ndarray, step_start: float):
        """(n, 2) texture inertial loads [N] over the step's instants, or None below the floor."""
        if (abs(texture.item(1)) <= TEXTURE_FLOOR_MPS2
                and abs(texture.item(4)) <= TEXTURE_FLOOR_MPS2):
            return None
        phase, amplitude, speed = texture[0::3], texture[1::3], texture[2::3]
        # The texture sample in force was taken at the last multiple of its period before now.
        sampled_at = TEXTURE_PERIOD_S * math.floor((step_start + 0.5 * self._dt)
                                                   / TEXTURE_PERIOD_S)
        elapsed = (step_start - sampled_at + self._midpoints)[:, np.newaxis]
        return self._config.film.mode_mass_kg * texture_acceleration(
            phase, amplitude, speed, elapsed, self._texture_period_m)

    def _start_impacts(self, context, onsets, step_start: float, pulses: list):
        """Sets, in `pulses`, the impact pulse of each pad whose contact began this step."""
        contacts = self._contacts.Eval(context)
        poses = self._poses.Eval(context)
        velocities = self._velocities.Eval(context)
        accelerations = self._body_accelerations.Eval(context)
        for k in (k for k in range(2) if onsets[k]):
            touch = self._strongest_contact(contacts, self._pads[k].geometry_id)
            if touch is None:
                continue
            other, p_WC = touch
            pad_body = int(self._pads[k].body_index)
            X_WP = poses[pad_body] @ self._pads[k].X_BP
            normal = X_WP.rotation().matrix()[:, 2].copy()  # inward
            v_pad, v_other = (_point_velocity_before_step(
                poses[b], velocities[b], accelerations[b], p_WC, self._dt)
                for b in (pad_body, other))
            impulse, duration = impact_pulse(
                float(np.dot(v_pad - v_other, normal)), self._config.film.mode_mass_kg,
                self._mass[other], self._impact_stiffness,
                self._config.film.pad_dissipation_s_per_m)
            pulses[k], pulses[2 + k], pulses[4 + k] = step_start, impulse, duration

    def _strongest_contact(self, contacts: ContactResults, pad_geometry):
        """(other body index, point in world) of the pad's largest contact force, or None."""
        best, best_force = None, -1.0
        for i in range(contacts.num_hydroelastic_contacts()):
            info = contacts.hydroelastic_contact_info(i)
            surface = info.contact_surface()
            ids = (surface.id_M(), surface.id_N())
            if pad_geometry not in ids:
                continue
            other = ids[1] if ids[0] == pad_geometry else ids[0]
            force = float(np.linalg.norm(info.F_Ac_W().translational()))
            if force > best_force:
                best, best_force = (self._geometry_body[other], surface.centroid()), force
        for i in range(contacts.num_point_pair_contacts()):
            info = contacts.point_pair_contact_info(i)
            ids = (info.point_pair().id_A, info.point_pair().id_B)
            if pad_geometry not in ids:
                continue
            other = ids[1] if ids[0] == pad_geometry else ids[0]
            force = float(np.linalg.norm(info.contact_force()))
            if force > best_force:
                best, best_force = (self._geometry_body[other], info.contact_point()), force
        return best
