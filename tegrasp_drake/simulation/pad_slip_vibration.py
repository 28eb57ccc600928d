"""Vibration that sliding excites in a pad's piezo film (the RA response to slip). The pad's cover
is a texture of height h and period lambda: at slip speed v (the object's point at the pad centre
relative to the pad, in the pad plane) the film is driven at f = v / lambda with amplitude h (2 pi
v / lambda)^2 along the pad normal, its phase the integrated slip distance."""

import math
import typing

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialVelocity
from pydrake.systems.framework import BasicVector, LeafSystem

from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD

if typing.TYPE_CHECKING:  # the films (pad_vibration_sensor.py) read this module's texture
    from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig

CONTACT_FORCE_N = 0.2  # a pad's summed true force [N] above which it slides on the object
UPDATE_PERIOD_S = 0.005  # slip speed sampling; the vibration itself is output at any time


def texture_acceleration_amplitude(slip_speed: float, height_m: float, period_m: float) -> float:
    """Peak acceleration [m/s^2] of a film dragged at slip_speed [m/s] over the texture."""
    omega = 2.0 * math.pi * slip_speed / period_m
    return height_m * omega ** 2


def texture_acceleration(phase, amplitude, speed, elapsed, period_m: float):
    """The texture's acceleration [m/s^2] `elapsed` [s] after a (phase, amplitude, speed) sample."""
    return amplitude * np.sin(phase + 2.0 * np.pi * speed * elapsed / period_m)


def cross_product(a, b) -> np.ndarray:
    """a x b of two 3-vectors, numpy's arithmetic without np.cross's set-up (30 times the cost)."""
    a0, a1, a2 = a.tolist()
    b0, b1, b2 = b.tolist()
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def tangential_slip_speed(X_WP: RigidTransform, V_WPad: SpatialVelocity, p_WPad_origin,
                          V_WObj: SpatialVelocity, p_WObj_origin) -> float:
    """Speed [m/s] of the object's point at pad centre P relative to the pad, in the pad plane."""
    p_WP = X_WP.translation()

    def point_velocity(V, origin):
        return V.translational() + cross_product(V.rotational(), p_WP - origin)

    v_rel = point_velocity(V_WObj, p_WObj_origin) - point_velocity(V_WPad, p_WPad_origin)
    normal = X_WP.rotation().matrix()[:, 2]
    return float(np.linalg.norm(v_rel - normal * np.dot(v_rel, normal)))


class PadSlipVibration(LeafSystem):
    """The texture vibration of both pads, sampled every UPDATE_PERIOD_S.

    .. pydrake_system::

        name: PadSlipVibration
        input_ports:
        - body_poses
        - body_spatial_velocities
        - true_taxel_forces
        output_ports:
        - left_slip_vibration
        - right_slip_vibration
        - texture_state

    Ports: body_poses, body_spatial_velocities (the plant's, read while a pad touches);
    true_taxel_forces (24, N, TactilePads'); *_slip_vibration (3, m/s^2 on the pad frame's z);
    texture_state (6: per pad the phase [rad], amplitude [m/s^2] and slip speed [m/s]).
    """

    def __init__(self, *, pads: dict, object_body_index, config: "VibrationSensorConfig"):
        super().__init__()
        self._pads = pads  # finger name -> PadGeometry (body_index, X_BP)
        self._object_body = int(object_body_index)
        self._height = config.slip_texture_height_m
        self._period_m = config.slip_texture_period_m
        self._dt = UPDATE_PERIOD_S
        self._poses = self.DeclareAbstractInputPort(
            "body_poses", AbstractValue.Make([RigidTransform()]))
        self._velocities = self.DeclareAbstractInputPort(
            "body_spatial_velocities", AbstractValue.Make([SpatialVelocity()]))
        self._forces = self.DeclareVectorInputPort("true_taxel_forces", 2 * TAXELS_PER_PAD)
        # Per pad: texture phase [rad], acceleration amplitude [m/s^2], slip speed [m/s].
        self._state = self.DeclareDiscreteState(3 * len(FINGER_NAMES))
        self.DeclarePeriodicDiscreteUpdateEvent(self._dt, 0.0, self._update)
        for k, finger in enumerate(FINGER_NAMES):
            self.DeclareVectorOutputPort(
                f"{finger}_slip_vibration", 3,
                lambda context, output, k=k: self._calc_vibration(context, output, k),
                prerequisites_of_calc={self.xd_ticket(), self.time_ticket()})
        # The films read it on every plant step: a state output port, no Python call.
        self.DeclareStateOutputPort("texture_state", self._state)

    def _update(self, context, discrete_state):
        state = context.get_discrete_state(self._state).get_value().copy()
        forces = self._forces.Eval(context).reshape(len(FINGER_NAMES), TAXELS_PER_PAD)
        touching = forces.sum(axis=1) > CONTACT_FORCE_N
        if not touching.any() and not state[2::3].any():
            return  # nothing touches and nothing slid: the state stays as it is
        poses = self._poses.Eval(context) if touching.any() else None
        velocities = self._velocities.Eval(context) if touching.any() else None
        for k, finger in enumerate(FINGER_NAMES):
            pad = self._pads[finger]
            body = int(pad.body_index)
            speed = 0.0
            if touching[k]:
                X_WObj = poses[self._object_body]
                X_WB = poses[body]
                speed = tangential_slip_speed(X_WB @ pad.X_BP, velocities[body],
                                              X_WB.translation(), velocities[self._object_body],
                                              X_WObj.translation())
            # Advance the phase over the last period at the speed sampled then.
            phase = state[3 * k] + 2.0 * math.pi * state[3 * k + 2] * self._dt / self._period_m
            state[3 * k:3 * k + 3] = (math.fmod(phase, 2.0 * math.pi),
                                      texture_acceleration_amplitude(speed, self._height,
                                                                     self._period_m), speed)
        discrete_state.get_mutable_vector(self._state).SetFromVector(state)

    def _calc_vibration(self, context, output: BasicVector, k: int):
        state = context.get_discrete_state(self._state).get_value()
        phase, amplitude, speed = state[3 * k:3 * k + 3]
        if amplitude == 0.0:
            output.SetZero()
            return
        since_sample = math.fmod(context.get_time(), self._dt)
        output.SetFromVector([0.0, 0.0, texture_acceleration(phase, amplitude, speed,
                                                             since_sample, self._period_m)])
