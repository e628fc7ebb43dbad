"""A row of balls in a linear ball guide's load zone over time: gaps that close and open,
groups that push and part, and the friction their contacts add (Lin, Duan and Okwudire 2019,
analytical model of physics/ball_guides/ball_to_ball.py), SI units.

The carriage at rail position x moves at u. Ball j sits at p_j in the carriage frame, in a
load zone of length L that the row fills periodically: a ball leaving it at one end stands for
the next one entering at the other (the return channel is frictionless and adds no delay), so
the N balls keep the total clearance L - N D between them.

* Each ball's contact-angle deviations (BL, BR, TR, TL) are constant ones plus a rail-groove
  wave of amplitude A and wavelength lambda under the ball, BL = A sin(2 pi z / lambda) and
  BR = A cos(2 pi z / lambda) at its rail position z = x + p_j (p_j folded into the zone).
* Each ball carries N_y = F_normal / N and the side load N_x = F_side / N + M_yaw p / (N L^2/12)
  (the yaw moment shared over the zone like a linear spring row).
* Alone, a ball rolls at v_B = (1 + epsilon_j) u / 2 (eq. 22). Touching neighbours move as one
  group at the drag-weighted mean epsilon and push each other with the forces of
  :func:`ball_to_ball.group_forces`; a group parts where a force would pull
  (:func:`ball_to_ball.split_groups`), contacts are inelastic (a closed gap stays closed while
  the rear ball pushes). Gaps change at (epsilon_front - epsilon_rear) u / 2.
* Each contact slides at u / cos(beta_0) (eq. 31) and dissipates mu F_c |u| / cos(beta_0), so
  the carriage feels F_friction = -mu sum(F_c) / cos(beta_0) s(u), s the regularised sign.

epsilon and G do not depend on u (eqs. 22, 30): the row's contact forces depend on where the
balls are, not on how fast they roll.

The balls' speeds jump where a gap closes or a group parts. :meth:`BallRow.advance` steps the
row with RK4 substeps and places a substep's end on each such event (bisection on the
substep's length), so that no Runge-Kutta stage straddles a jump and the integration keeps its
order between events.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import ball_to_ball as b2b
from .. import checks
from ..dynamics import MAX_SUBSTEPS, ContinuousModel, rk4_step, substeps
from ..dynamics import regularised_sign

#: a gap at or below this [m] is closed (the reference integrator may overshoot 0 by a little)
CLOSED = 1e-12
#: an RK4 substep moves the balls by at most this share of the shorter of the ball diameter
#: and the groove wave's wavelength
TRAVEL_STEP = 0.05
#: a change of the groups is located to this share of the substep it falls in
EVENT_TOLERANCE = 1e-4


@dataclass(frozen=True)
class RowState:
    """The row at one instant: each ball's epsilon alone and in its group, the groups (indices
    rear first along the motion) and the contact force [N] of each gap (index j: ball j and
    j + 1, the last gap closes the ring)."""

    epsilon: np.ndarray
    moving: np.ndarray
    groups: list
    contact_forces: np.ndarray


class BallRow(ContinuousModel):
    """The row as a continuous-time model: inputs u [m/s], x [m], F_normal, F_side [N],
    M_yaw [N m]; states p_1..p_N [m]; outputs F_friction, contact_force, max_contact_force [N],
    friction_loss [W], groups [-], epsilon_mean [-]."""

    inputs = ("u", "x", "F_normal", "F_side", "M_yaw")
    smooth = False  # a ball's speed jumps where its gap closes or its group parts

    def __init__(self, bearing: b2b.Bearing, balls: int, zone_length: float, deviations,
                 wave_amplitude: float, wavelength: float, velocity_tolerance: float):
        if isinstance(balls, bool) or int(balls) != balls or balls < 2:
            raise ValueError(f"balls must be an integer >= 2, got {balls!r}")
        self.bearing, self.balls = bearing, int(balls)
        self.zone_length = checks.positive("zone_length", zone_length)
        self.diameter = 2 * bearing.radius
        if zone_length <= self.balls * self.diameter:
            raise ValueError(f"zone_length {zone_length!r} m must exceed balls x ball diameter "
                             f"= {self.balls * self.diameter!r} m (the row needs clearance)")
        self.deviations = checks.finite("deviations", deviations)
        if self.deviations.shape != (4,):
            raise ValueError("deviations must hold four angles (BL, BR, TR, TL) [rad]")
        self.wave_amplitude = checks.non_negative("wave_amplitude", wave_amplitude)
        self.wavelength = checks.positive("wavelength", wavelength)
        self.velocity_tolerance = checks.non_negative("velocity_tolerance", velocity_tolerance)
        self.states = tuple(f"p_{j + 1}" for j in range(self.balls))

    def state_scales(self):
        return (self.diameter,) * self.balls

    def initial_state(self, t, inputs):
        """Evenly spaced balls, the first at the zone's rear end (-L/2)."""
        pitch = self.zone_length / self.balls
        return tuple(-self.zone_length / 2 + (j + 0.5) * pitch for j in range(self.balls))

    # -- geometry and loads -----------------------------------------------------------------
    def gaps(self, p) -> np.ndarray:
        """Clearance [m] between ball j and j + 1 (the last one: between ball N and ball 1)."""
        p = np.asarray(p, dtype=float)
        return np.diff(np.append(p, p[0] + self.zone_length)) - self.diameter

    def zone_positions(self, p) -> np.ndarray:
        """p_j folded into the load zone [-L/2, L/2) [m]."""
        half = self.zone_length / 2
        return np.mod(np.asarray(p, dtype=float) + half, self.zone_length) - half

    def ball_deviations(self, x: float, p) -> np.ndarray:
        """(N, 4) contact-angle deviations [rad] of the balls at the carriage position x [m]:
        a ball that re-entered the zone at the front sees the groove where it now is."""
        phase = 2 * np.pi * (x + self.zone_positions(p)) / self.wavelength
        wave = np.zeros((phase.size, 4))
        wave[:, 0], wave[:, 1] = np.sin(phase), np.cos(phase)
        return self.deviations + self.wave_amplitude * wave

    def side_loads(self, inputs, p) -> np.ndarray:
        """N_x [N] of each ball."""
        n, length = self.balls, self.zone_length
        return (inputs["F_side"] / n
                + inputs["M_yaw"] * self.zone_positions(p) / (n * length ** 2 / 12))

    # -- the row ----------------------------------------------------------------------------
    def row(self, state, inputs) -> RowState:
        """Each ball's epsilon, the groups and the contact forces at the state."""
        n, bearing = self.balls, self.bearing
        normal = checks.non_negative("F_normal", inputs["F_normal"]) / n
        zero = np.zeros(n)
        if normal == 0.0:  # no load, no rolling constraint: the balls keep their spacing
            return RowState(zero, zero, [[j] for j in range(n)], zero)
        try:
            upper, lower = b2b.diagonal_loads(bearing, self.side_loads(inputs, state), normal)
        except ValueError as exc:
            raise ValueError(f"inputs F_side, M_yaw against F_normal: {exc}") from None
        deviations = self.ball_deviations(inputs["x"], state).T
        eps = np.asarray(b2b.velocity_deviation(bearing, deviations, upper, lower))
        drags = np.asarray(b2b.drag(bearing, upper, lower))
        closed = self.gaps(state) <= CLOSED
        # order along the motion (rear first), starting after an open gap so no group wraps
        forward = inputs["u"] >= 0.0
        start = int(np.flatnonzero(~closed)[0]) + 1  # clearance > 0: some gap is open
        order = [(start + k) % n for k in range(n)]
        if not forward:
            order = order[::-1]
        touching = [bool(closed[a if forward else b]) for a, b in zip(order, order[1:])]
        local = b2b.split_groups(eps[order], drags[order], touching)
        moving, forces, groups = eps.copy(), np.zeros(n), []
        for group in local:
            balls = [order[i] for i in group]
            common, pushes = b2b.group_forces(eps[balls], drags[balls])
            moving[balls] = common
            for a, b, force in zip(balls, balls[1:], pushes):
                forces[a if forward else b] = force
            groups.append(balls)
        return RowState(eps, moving, groups, forces)

    def derivatives(self, t, state, inputs):
        return tuple(-(1.0 - self.row(state, inputs).moving) * inputs["u"] / 2)

    def advance(self, t: float, state, inputs: dict, h: float) -> np.ndarray:
        """The state after ``h`` [s] with the inputs held: RK4 substeps of at most
        TRAVEL_STEP of travel, each ending where the groups change if they do within it.
        Raises ValueError when the travel or the group changes need more than MAX_SUBSTEPS."""
        state = np.asarray(state, dtype=float)
        travel = TRAVEL_STEP * min(self.diameter, self.wavelength)
        what = "the balls' travel (TRAVEL_STEP of a diameter or wavelength each)"
        longest = h / substeps(h * abs(inputs["u"]) / travel, what)
        done, taken = 0.0, 0
        while h - done > 1e-12 * h:
            taken += 1
            if taken > MAX_SUBSTEPS:
                raise ValueError(f"the step of {h:g} s at u = {inputs['u']:g} m/s needs more "
                                 f"than {MAX_SUBSTEPS} substeps: the balls' groups change too "
                                 f"often within it")
            dt = min(longest, h - done)
            before = self._groups(state, inputs)
            trial = rk4_step(self, t + done, state, inputs, dt)
            if self._groups(trial, inputs) != before:  # bisect: unchanged at short, not at long_
                short, long_ = 0.0, dt
                while long_ - short > EVENT_TOLERANCE * dt:
                    mid = (short + long_) / 2
                    probe = rk4_step(self, t + done, state, inputs, mid)
                    if self._groups(probe, inputs) != before:
                        long_, trial = mid, probe
                    else:
                        short = mid
                dt = long_
            state, done = trial, done + dt
        return state

    def _groups(self, state, inputs) -> tuple:
        return tuple(map(tuple, self.row(state, inputs).groups))

    def outputs(self, t, state, inputs, wanted=None):
        row = self.row(state, inputs)
        u, b = inputs["u"], self.bearing
        total = float(row.contact_forces.sum())
        per_speed = b.friction * total * b2b.contact_slide_speed(b, 1.0)  # loss / |u| (eq. 32)
        return {"F_friction": float(-per_speed * regularised_sign(u, self.velocity_tolerance)),
                "contact_force": total, "max_contact_force": float(row.contact_forces.max()),
                "friction_loss": per_speed * abs(u), "groups": float(len(row.groups)),
                "epsilon_mean": float(row.moving.mean())}


def from_parameters(radius, conformity, youngs_modulus, poisson_ratio, friction,
                    nominal_angle, balls, zone_length, deviation_BL, deviation_BR, deviation_TR,
                    deviation_TL, wave_amplitude, wavelength, velocity_tolerance) -> BallRow:
    """The validated row of the BallToBallFriction FMU's parameters (fmus/README.md)."""
    bearing = b2b.Bearing(radius, conformity, youngs_modulus, poisson_ratio, friction,
                          nominal_angle, velocity=1.0)  # v unused: epsilon and G are rate-free
    return BallRow(bearing, balls, zone_length,
                   [deviation_BL, deviation_BR, deviation_TR, deviation_TL], wave_amplitude,
                   wavelength, velocity_tolerance)


def friction_history(model: BallRow, time, x, u, normal: float, side: float = 0.0,
                     yaw: float = 0.0, packed: bool = False) -> np.ndarray:
    """F_friction [N] of the row at the samples of a motion (time [s], position x [m],
    velocity u [m/s], inputs held between samples) under constant loads, the balls starting
    evenly spaced, or ``packed``: touching from the zone's rear end, the clearance in front."""
    t, x, u = (np.asarray(v, dtype=float) for v in (time, x, u))
    inputs = {"u": float(u[0]), "x": float(x[0]), "F_normal": normal, "F_side": side,
              "M_yaw": yaw}
    state = (-model.zone_length / 2 + (np.arange(model.balls) + 0.5) * model.diameter if packed
             else np.array(model.initial_state(t[0], inputs)))
    out = np.empty(t.size)
    for k in range(t.size):
        inputs.update(u=float(u[k]), x=float(x[k]))
        out[k] = model.outputs(t[k], state, inputs)["F_friction"]
        if k + 1 < t.size:
            state = model.advance(t[k], state, inputs, t[k + 1] - t[k])
    return out
