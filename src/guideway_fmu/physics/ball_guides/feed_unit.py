"""The four-slider ball-guide feed unit of Zhang, Wang and Le (2019): the worktable's static
equilibrium under a load, each ball's load and contact angle, the sliders' stiffness and the
five errors delta_y, delta_z, epsilon_x, epsilon_y, epsilon_z; SI units.

Frame: origin at the table's centre in the plane of the ball rows' centres, x along the travel,
y across, z up. The table is rigid, the rails fixed. Its displacement q = (delta_y, delta_z,
epsilon_x, epsilon_y, epsilon_z) moves a table point (x, y, z) by the small-angle transform
of the paper's eq. 1 (:func:`displacement`). The travel x itself is the feed drive's: the drive
takes F_x at the origin, the guides carry the rest.

Layout: sliders 1..4 at (+W_x, +W_y), (+W_x, -W_y), (-W_x, -W_y), (-W_x, +W_y); each with four
rows of balls at (s_y L_y/2, s_z L_z/2) from its centre (rows 1..4: s = (+,+), (-,+), (-,-),
(+,-)), ``balls_per_row`` balls ``pitch`` apart centred on the slider. A row's contact line lies
in the y-z plane at the contact angle alpha to the y axis; moving the slider toward the rail's
centre along c = -(s_y cos alpha, s_z sin alpha) compresses its balls: the upper rows carry
downward loads, the lower ones lifting loads, each side's pair a lateral load (a four-row guide
rated alike in all directions; at 45 deg its vertical and lateral stiffness are equal).

Ball: two Hertz point contacts in series (hertz_point.ball_constant), preloaded to Q_0 with the
approach delta_p. The grooves' curvature centres lie L_0 = (2 f - 1) D + delta_p apart (eq. 2,
preloaded). Under the displacement d of the slider groove's curvature centre:

* with the contact-angle change (eqs. 5, 7, 9, 10): v = L_0 c + d, the approach is
  delta = delta_p + |v| - L_0 and the contact normal turns to v / |v|;
* at a constant angle: delta = delta_p + c . d, the normal stays c.

Q = K delta^1.5 (0 once a ball loses contact) pushes the table along minus the normal. The
table settles where the balls' forces and moments balance the load (eq. 20); solved by Newton's
method with the analytic tangent stiffness (roots.newton_system), from the last answer, with
load steps where it does not converge. The paper's rigid-table relations (eqs. 16, 17, 19)
follow from the transform and need no separate equations here. Per-ball quantities are 1-D
arrays over the balls (slider by slider, row by row, along x), a pair (y, z) for a vector.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import checks
from . import hertz_point
from .carriage_5dof import ball_positions
from ..dynamics import ContinuousModel
from ..roots import load_steps, newton_system

ERRORS = ("delta_y", "delta_z", "epsilon_x", "epsilon_y", "epsilon_z")
SLIDER_SIGNS = ((1, 1), (1, -1), (-1, -1), (-1, 1))  # (x, y) sides of sliders 1..4
ROW_SIGNS = ((1, 1), (-1, 1), (-1, -1), (1, -1))  # (y, z) sides of rows 1..4 on a slider
SLIDER_X, SLIDER_Y = np.array(SLIDER_SIGNS, dtype=float).T
ROW_Y, ROW_Z = np.array(ROW_SIGNS, dtype=float).T
#: static contact-pressure limit of ball bearings behind ISO 76's basic static load rating [Pa]
PRESSURE_LIMIT = 4.2e9
#: where the direct solve does not converge, the load is applied in 4, then 16, then 64 steps
FINEST_CONTINUATION = 64
#: Newton iterations of one solve at most (from a near start it converges in 2-4)
NEWTON_ITERATIONS = 50


@dataclass(frozen=True)
class Layout:
    """Half spans W_x, W_y of the sliders [m], row spacings L_y, L_z on a slider [m], contact
    angle alpha [rad], balls per row and their pitch [m]."""

    half_span_x: float
    half_span_y: float
    row_spacing_y: float
    row_spacing_z: float
    contact_angle: float
    balls_per_row: int
    pitch: float

    def __post_init__(self):
        for name in ("half_span_x", "half_span_y", "row_spacing_y", "row_spacing_z", "pitch"):
            checks.positive(name, getattr(self, name))
        checks.positive_integer("balls_per_row", self.balls_per_row)
        if not 0.0 < self.contact_angle < np.pi / 2:
            raise ValueError(f"contact_angle must lie in (0, 90) degrees, got "
                             f"{np.degrees(self.contact_angle)!r}")
        if self.balls_per_row * self.pitch > 2.0 * self.half_span_x:
            raise ValueError(f"balls_per_row * pitch ({self.balls_per_row * self.pitch:g} m) "
                             f"must not exceed 2 half_span_x ({2 * self.half_span_x:g} m): the "
                             f"sliders would overlap")

    def balls(self) -> tuple:
        """Every ball's point (x, y, z) [m], compressing direction (c_y, c_z) and slider index
        0..3, each an array over the balls: slider by slider, row by row, along x."""
        n = self.balls_per_row
        row_y, row_z = np.tile(np.repeat(ROW_Y, n), 4), np.tile(np.repeat(ROW_Z, n), 4)
        x = np.repeat(SLIDER_X * self.half_span_x, 4 * n) + np.tile(ball_positions(n, self.pitch), 16)
        y = np.repeat(SLIDER_Y * self.half_span_y, 4 * n) + row_y * self.row_spacing_y / 2
        z = row_z * self.row_spacing_z / 2
        compress = (-np.cos(self.contact_angle) * row_y, -np.sin(self.contact_angle) * row_z)
        return (x, y, z), compress, np.repeat(np.arange(4), 4 * n)


def displacement(q, x, y, z) -> tuple:
    """(d_x, d_y, d_z) [m] of the table point (x, y, z) [m] (numbers or arrays) at the
    displacement q (eq. 1)."""
    return (q[3] * z - q[4] * y, q[0] + q[4] * x - q[2] * z, q[1] + q[2] * y - q[3] * x)


def moment(point, force) -> tuple:
    """The moment r x F [N m] of the force (F_x, F_y, F_z) [N] at the point (x, y, z) [m] about
    the origin (numbers or arrays)."""
    (x, y, z), (f_x, f_y, f_z) = point, force
    return (y * f_z - z * f_y, z * f_x - x * f_z, x * f_y - y * f_x)


def generalized_load(force, point, moment_=(0.0, 0.0, 0.0)) -> np.ndarray:
    """(F_y, F_z, M_x, M_y, M_z) on the table [N, N m] of the force (F_x, F_y, F_z) [N] at the
    point (x, y, z) [m] plus the moment (M_x, M_y, M_z) [N m]; F_x goes to the drive at the
    origin, its moment about the origin to the guides."""
    f = checks.finite("force", force)
    torque = np.array(moment(checks.finite("point", point), f)) + checks.finite("moment", moment_)
    return np.array([f[1], f[2], *torque])


def point_displacement(q, point) -> np.ndarray:
    """(d_x, d_y, d_z) [m] of the table point (x, y, z) [m] at the displacement q (eq. 1)."""
    return np.array(displacement(np.asarray(q, dtype=float), *point))


@dataclass(frozen=True)
class Equilibrium:
    """The table at rest under a load: q, each ball's load [N], approach [m] and contact angle
    [rad], each ball's stiffness (t_yy, t_yz, t_zz) against its slider's (d_y, d_z) [N/m] and
    the table's tangent stiffness (5 x 5)."""

    q: np.ndarray
    loads: np.ndarray
    approaches: np.ndarray
    angles: np.ndarray
    ball_tangents: tuple
    tangent: np.ndarray

    @property
    def errors(self) -> dict[str, float]:
        """The five errors at the table's centre [m, rad]."""
        return dict(zip(ERRORS, map(float, self.q)))


class FeedUnit:
    """Preloaded Hertz balls under the worktable, with or without the contact-angle change."""

    def __init__(self, layout: Layout, ball: hertz_point.BallGroove, preload: float,
                 angle_change: bool = True):
        self.layout, self.ball, self.angle_change = layout, ball, bool(angle_change)
        self.preload = float(checks.positive("preload", preload))
        self.k_h = hertz_point.ball_constant(ball)
        self.rest = float(hertz_point.approach(self.k_h, self.preload))
        self.distance = (2.0 * ball.conformity - 1.0) * ball.diameter + self.rest
        (self.x, self.y, self.z), (self.c_y, self.c_z), self.slider = layout.balls()

    def contact(self, q):
        """(approach [m], unit normal (n_y, n_z), centre distance |v| [m]) of every ball at q;
        at a constant angle the distance is inf: the contact line keeps its direction, as if
        the grooves' centres lay infinitely far apart."""
        _, d_y, d_z = displacement(q, self.x, self.y, self.z)
        if not self.angle_change:
            approach = self.rest + self.c_y * d_y + self.c_z * d_z
            return approach, (self.c_y, self.c_z), np.full_like(approach, np.inf)
        v_y, v_z = self.distance * self.c_y + d_y, self.distance * self.c_z + d_z
        length = np.hypot(v_y, v_z)
        return self.rest + length - self.distance, (v_y / length, v_z / length), length

    def generalized(self, f_y, f_z) -> np.ndarray:
        """(F_y, F_z, M_x, M_y, M_z) [N, N m] of the forces (0, f_y, f_z) [N] at the balls."""
        torque = moment((self.x, self.y, self.z), (0.0, f_y, f_z))
        return np.array([np.sum(f_y), np.sum(f_z), *(np.sum(m) for m in torque)])

    def restoring(self, q) -> np.ndarray:
        """Generalized force of the balls on the table [N, N m]: each pushes along minus its
        normal with its load."""
        approach, (n_y, n_z), _ = self.contact(q)
        loads = hertz_point.load(self.k_h, approach)
        return self.generalized(-loads * n_y, -loads * n_z)

    def ball_tangents(self, q) -> tuple:
        """(t_yy, t_yz, t_zz): each ball's stiffness against its slider's (d_y, d_z) [N/m],
        k n n^T plus the turning of the contact line (Q / |v|)(I - n n^T) (0 at a constant
        angle)."""
        approach, (n_y, n_z), length = self.contact(q)
        k = hertz_point.stiffness(self.k_h, approach)
        turn = hertz_point.load(self.k_h, approach) / length
        return (k * n_y**2 + turn * (1.0 - n_y**2), (k - turn) * n_y * n_z,
                k * n_z**2 + turn * (1.0 - n_z**2))

    def tangent(self, q, ball_tangents=None) -> np.ndarray:
        """Tangent stiffness of the table, sum G^T T G (5 x 5) [N/m, N, N m]: G's column a is
        the balls' (d_y, d_z) under a unit q_a (eq. 1), T each ball's stiffness."""
        t_yy, t_yz, t_zz = self.ball_tangents(q) if ball_tangents is None else ball_tangents
        columns = [displacement(unit, self.x, self.y, self.z)[1:] for unit in np.eye(5)]
        pushed = [(t_yy * g_y + t_yz * g_z, t_yz * g_y + t_zz * g_z) for g_y, g_z in columns]
        return np.array([[np.dot(g_y, p_y) + np.dot(g_z, p_z) for p_y, p_z in pushed]
                         for g_y, g_z in columns])

    def equilibrium(self, load, start=None) -> Equilibrium:
        """The table's rest under the generalized load (F_y, F_z, M_x, M_y, M_z) [N, N m],
        searched from ``start`` (default: unloaded). Converged when the force balance holds to
        1e-9 of the load or the preload; load steps are tried if a direct solve fails."""
        load = checks.finite("load", load)
        tolerance = 1e-9 * max(float(np.max(np.abs(load))), self.preload)

        def solve(part, begin):
            return newton_system(lambda q: self.restoring(q) + part, lambda q: -self.tangent(q),
                                 begin, tolerance, NEWTON_ITERATIONS)

        q, error = load_steps(solve, load, np.zeros(5) if start is None else start, tolerance,
                              FINEST_CONTINUATION)
        if not error <= tolerance:  # NaN: not converged either
            raise ValueError(f"no static equilibrium found under the load {load.tolist()} "
                             f"(F_y, F_z, M_x, M_y, M_z): force balance off by {error:.3g}")
        approach, (n_y, n_z), _ = self.contact(q)
        tangents = self.ball_tangents(q)
        return Equilibrium(q, hertz_point.load(self.k_h, approach), approach,
                           np.arctan2(np.abs(n_z), np.abs(n_y)), tangents,
                           self.tangent(q, tangents))

    def slider_stiffness(self, state: Equilibrium) -> np.ndarray:
        """(4, 2) lateral and vertical tangent stiffness [N/m] of each slider: its balls' shares
        summed, the slider moved in y or z alone."""
        t_yy, _, t_zz = state.ball_tangents
        return np.array([(np.sum(t_yy[self.slider == m]), np.sum(t_zz[self.slider == m]))
                         for m in range(4)])

    def unit_stiffness(self, state: Equilibrium) -> tuple[float, float]:
        """Lateral and vertical stiffness of the whole unit [N/m]: a force at the table's centre
        over the centre's displacement, rotations free (1 / compliance)."""
        compliance = np.linalg.inv(state.tangent)
        return 1.0 / compliance[0, 0], 1.0 / compliance[1, 1]

    def max_pressure(self, state: Equilibrium) -> float:
        """Largest Hertz contact pressure 3 Q / (2 pi a b) of any ball [Pa]."""
        q = float(state.loads.max())
        a, b = hertz_point.semi_axes(self.ball, q)
        return float(1.5 * q / (np.pi * a * b)) if q > 0 else 0.0


class FeedUnitModel(ContinuousModel):
    """The feed unit as a stateless model: inputs the force (F_x, F_y, F_z) [N] at the load point
    (point_x - x_feed, point_y, point_z) [m] on the table (x_feed the table's travel, for a tool
    that stands while the table moves); outputs the five errors at the table's centre, the
    displacement of the load point (tool_d_x, tool_d_y, tool_d_z) [m] and the largest ball load
    [N]. Each solve starts from the last one's answer (the first from the unloaded table)."""

    inputs = ("F_x", "F_y", "F_z", "point_x", "point_y", "point_z", "x_feed")

    def __init__(self, unit: FeedUnit):
        self.unit, self._last = unit, np.zeros(5)

    def outputs(self, t, state, inputs, wanted=None):
        point = (inputs["point_x"] - inputs["x_feed"], inputs["point_y"], inputs["point_z"])
        load = generalized_load((inputs["F_x"], inputs["F_y"], inputs["F_z"]), point)
        found = self.unit.equilibrium(load, self._last)
        self._last = found.q
        tool = point_displacement(found.q, point)
        return {**found.errors, "tool_d_x": float(tool[0]), "tool_d_y": float(tool[1]),
                "tool_d_z": float(tool[2]), "max_ball_load": float(found.loads.max())}


def from_parameters(half_span_x, half_span_y, row_spacing_y, row_spacing_z, contact_angle,
                    balls_per_row, pitch, ball_diameter, conformity, preload, youngs_modulus,
                    poisson_ratio, angle_change) -> FeedUnitModel:
    """The validated model of the FeedUnitErrors FMU's parameters (fmus/README.md)."""
    checks.positive("youngs_modulus", youngs_modulus)
    checks.in_range("poisson_ratio", poisson_ratio, 0.0, 0.5)
    layout = Layout(half_span_x, half_span_y, row_spacing_y, row_spacing_z, contact_angle,
                    balls_per_row, pitch)
    ball = hertz_point.BallGroove(ball_diameter, conformity, youngs_modulus, poisson_ratio,
                                  youngs_modulus, poisson_ratio)
    return FeedUnitModel(FeedUnit(layout, ball, preload, angle_change))
