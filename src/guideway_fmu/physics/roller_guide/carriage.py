"""Vertical dynamics of the carriage (Soleimanian et al. 2020, eq. 1b):
M y'' = M g + F_e(t) + F_ext - F_contact.

y [m] is positive in the direction of gravity and of the external load. F_e(t) is the external
load of eq. 1b (static plus harmonic, :class:`ExternalLoad`), known at every instant; F_ext [N]
is a further force held over the step. :meth:`CarriageModel.acceleration` is the one home of the
equation: the FMU, the reference and the step below all call it.

Over one communication step (:func:`step`) the contact force is taken as its value at the start
of the step plus its tangent, F_contact(t) = F0 + K (y - y0) + C (y' - v0), with the contact
model's tangent stiffness K [N/m] and damping C [N s/m] (K = C = 0: the force is held
constant), or, when the contact hands over its force law (``rows``, an
:class:`~.roller_law.OpposedRows`), as that law evaluated at every instant,
F_contact = rows.force(y, t - t0) + C y'. The ODE is integrated with the classical fourth-order
Runge-Kutta method on equal substeps of at most SUBSTEP_PHASE / omega, omega the largest of
sqrt(K/M) (K the law's stiffness at both ends of the step when there is a law), C/M and the
load's angular frequency: stable at any communication step for the linear tangent, with a phase
error of (omega h)^4 / 120, 8e-7 rad per radian of motion (about 2e-4 of the range of the
undamped dry contact's response over a Soleimanian cycle; 0.05 rad would take twice the
substeps for no error that matters, 0.2 rad gives 0.3-0.9 %: docs/speed.md).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .. import checks
from ..papers import soleimanian2020 as paper
from ..dynamics import ContinuousModel, substeps
from .roller_law import OpposedRows

STANDARD_GRAVITY = 9.80665  # m/s^2
SUBSTEP_PHASE = 0.1  # rad, largest omega * substep of the Runge-Kutta integration (module doc)
# Nominal magnitudes of y and y' for absolute tolerances: a preloaded rolling contact's approach
# (about a micrometre) and that amplitude at a natural frequency near 6.6 kHz.
LENGTH_SCALE = 1.04e-6  # m
SPEED_SCALE = 0.043  # m/s


@dataclass(frozen=True)
class Carriage:
    """The moving body of eq. 1b; the default mass is the project's assumption
    (papers.soleimanian2020.RAIL_MASS: the paper gives none)."""

    mass: float = paper.RAIL_MASS  # kg
    gravity: float = STANDARD_GRAVITY  # m/s^2

    def validate(self) -> None:
        checks.check_fields(self, {"mass": checks.positive, "gravity": checks.finite})


@dataclass(frozen=True)
class ExternalLoad:
    """F_e(t) = static + amplitude sin(2 pi frequency t + phase) [N] (Soleimanian et al. 2020, eq. 1b)."""

    static: float = 0.0  # N
    amplitude: float = 0.0  # N
    frequency: float = 0.0  # Hz
    phase: float = 0.0  # rad

    def validate(self) -> None:
        checks.check_fields(self, {"static": checks.finite, "amplitude": checks.finite,
                                   "frequency": checks.non_negative, "phase": checks.finite})

    def __call__(self, t: float) -> float:
        return self.static + self.amplitude * math.sin(2.0 * math.pi * self.frequency * t + self.phase)


class CarriageModel(ContinuousModel):
    """The carriage under its external load as a continuous-time model (module doc).

    Inputs F_contact, F_ext [N]; states and outputs y [m], y_dot [m/s]; output y_ddot [m/s^2].
    """

    inputs = ("F_contact", "F_ext")
    states = ("y", "y_dot")

    def __init__(self, carriage: Carriage, load: ExternalLoad, y_start: float = 0.0,
                 y_dot_start: float = 0.0):
        self.carriage, self.load = carriage, load
        self.start = (float(y_start), float(y_dot_start))

    def acceleration(self, t: float, f_contact: float, f_ext: float) -> float:
        """y'' [m/s^2] of eq. 1b at the time t [s] under the contact force and F_ext [N]."""
        return self.loaded_acceleration(self.load(t), f_contact, f_ext)

    def loaded_acceleration(self, f_load: float, f_contact: float, f_ext: float) -> float:
        """y'' [m/s^2] of eq. 1b under the external load F_e [N] (its value at the instant),
        the contact force and F_ext [N]."""
        return self.carriage.gravity + (f_load + f_ext - f_contact) / self.carriage.mass

    def state_scales(self):
        return (LENGTH_SCALE, SPEED_SCALE)

    def initial_state(self, t, inputs):
        return self.start

    def derivatives(self, t, state, inputs):
        return (state[1], self.acceleration(t, inputs["F_contact"], inputs["F_ext"]))

    def outputs(self, t, state, inputs, wanted=None):
        return {"y": state[0], "y_dot": state[1],
                "y_ddot": self.acceleration(t, inputs["F_contact"], inputs["F_ext"])}

    def step(self, y: float, v: float, t: float, h: float, f_ext: float, f_contact: float,
             k_contact: float = 0.0, c_contact: float = 0.0, rows: OpposedRows | None = None):
        """Advance (y [m], v [m/s]) from the time t [s] by the step h [s]; returns (y, v, y'')
        at t + h, y'' [m/s^2] under the step's contact force.

        With ``rows`` the contact force is that law plus c_contact y' (f_contact and k_contact
        are not used), else the tangent F0 + K dy + C dv (module doc).
        """
        for name, value in (("k_contact", k_contact), ("c_contact", c_contact)):
            if not 0.0 <= value < math.inf:
                raise ValueError(f"{name} must be finite and >= 0, got {value!r}")
        m = self.carriage.mass
        if rows is None:
            y0, v0 = y, v

            def contact(tau, yy, vv):
                return f_contact + k_contact * (yy - y0) + c_contact * (vv - v0)

            kk = k_contact / m
        else:
            force = rows.force

            def contact(tau, yy, vv):
                return force(yy, tau) + c_contact * vv

            kk = max(rows.stiffness(y, 0.0), rows.stiffness(y, h)) / m

        accelerate, load = self.loaded_acceleration, self.load
        omega = max(math.sqrt(kk), c_contact / m, 2.0 * math.pi * self.load.frequency)
        n = substeps(h * omega / SUBSTEP_PHASE, "the body's motion (omega h <= SUBSTEP_PHASE)")
        dt = h / n
        f_end = load(t)  # F_e at the substep's end, the next one's start: evaluated once
        for i in range(n):
            tau = i * dt
            f_start, f_mid, f_end = f_end, load(t + tau + 0.5 * dt), load(t + tau + dt)
            a1 = accelerate(f_start, contact(tau, y, v), f_ext)
            y2, v2 = y + 0.5 * dt * v, v + 0.5 * dt * a1
            a2 = accelerate(f_mid, contact(tau + 0.5 * dt, y2, v2), f_ext)
            y3, v3 = y + 0.5 * dt * v2, v + 0.5 * dt * a2
            a3 = accelerate(f_mid, contact(tau + 0.5 * dt, y3, v3), f_ext)
            y4, v4 = y + dt * v3, v + dt * a3
            a4 = accelerate(f_end, contact(tau + dt, y4, v4), f_ext)
            y, v = (y + dt / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4),
                    v + dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4))
        return y, v, accelerate(f_end, contact(h, y, v), f_ext)


def from_parameters(mass, gravity, load_static, load_amplitude, load_frequency, load_phase,
                    y_start, y_dot_start) -> CarriageModel:
    """The validated model of the VerticalDynamics FMU's parameters (fmus/README.md).

    Raises ValueError naming the parameter that is wrong.
    """
    carriage = Carriage(mass=mass, gravity=gravity)
    carriage.validate()
    load = ExternalLoad(static=load_static, amplitude=load_amplitude, frequency=load_frequency,
                        phase=load_phase)
    load.validate()
    checks.finite("y_start", y_start)
    checks.finite("y_dot_start", y_dot_start)
    return CarriageModel(carriage, load, y_start, y_dot_start)
