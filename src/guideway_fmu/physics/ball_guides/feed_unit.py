"""The four-slider ball-guide feed unit of Zhang, Wang and Le (2019): the worktable's static
equilibrium under a load, each ball's load and contact angle, the sliders' stiffness and the
five errors delta_y, delta_z, epsilon_x, epsilon_y, epsilon_z; SI units.

Frame: origin at the table's centre in the plane of the ball rows' centres, x along the travel,
y across, z up. The table is rigid, the rails fixed. Its displacement q = (delta_y, delta_z,
epsilon_x, epsilon_y, epsilon_z) moves a table point r = (x, y, z) by the small-angle transform
of the paper's eq. 1: d_x = epsilon_y z - epsilon_z y, d_y = delta_y + epsilon_z x - epsilon_x z,
d_z = delta_z + epsilon_x y - epsilon_y x. The travel x itself is the feed drive's: the drive
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
table settles where the balls' forces and moments balance the load (eq. 20); solved by
scipy.optimize.root with the analytic tangent stiffness. The paper's rigid-table relations
(eqs. 16, 17, 19) follow from the transform and need no separate equations here.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import root

from .. import checks
from . import hertz_point
from .carriage_5dof import ball_positions
from ..dynamics import ContinuousModel

ERRORS = ("delta_y", "delta_z", "epsilon_x", "epsilon_y", "epsilon_z")
SLIDER_SIGNS = ((1, 1), (1, -1), (-1, -1), (-1, 1))  # (x, y) sides of sliders 1..4
ROW_SIGNS = ((1, 1), (-1, 1), (-1, -1), (1, -1))  # (y, z) sides of rows 1..4 on a slider
#: static contact-pressure limit of ball bearings behind ISO 76's basic static load rating [Pa]
PRESSURE_LIMIT = 4.2e9
#: load steps tried, in turn, when the direct solve does not converge
CONTINUATION_STEPS = (4, 16, 64)


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

    def balls(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every ball's point (N, 3) [m], compressing direction c (N, 2) and slider index 0..3,
        slider by slider, row by row."""
        along = ball_positions(self.balls_per_row, self.pitch)
        c, s = np.cos(self.contact_angle), np.sin(self.contact_angle)
        points, directions, sliders = [], [], []
        for m, (sx, sy) in enumerate(SLIDER_SIGNS):
            for ry, rz in ROW_SIGNS:
                for x in along:
                    points.append((sx * self.half_span_x + x,
                                   sy * self.half_span_y + ry * self.row_spacing_y / 2,
                                   rz * self.row_spacing_z / 2))
                    directions.append((-ry * c, -rz * s))
                    sliders.append(m)
        return np.array(points), np.array(directions), np.array(sliders)


def transfer(points) -> np.ndarray:
    """(N, 2, 5) matrices taking q to the (d_y, d_z) of each table point (N, 3) [m]."""
    p = np.atleast_2d(np.asarray(points, dtype=float))
    g = np.zeros((len(p), 2, 5))
    g[:, 0, 0], g[:, 0, 2], g[:, 0, 4] = 1.0, -p[:, 2], p[:, 0]
    g[:, 1, 1], g[:, 1, 2], g[:, 1, 3] = 1.0, p[:, 1], -p[:, 0]
    return g


def generalized_load(force, point, moment=(0.0, 0.0, 0.0)) -> np.ndarray:
    """(F_y, F_z, M_x, M_y, M_z) on the table [N, N m] of the force (F_x, F_y, F_z) [N] at the
    point (x, y, z) [m] plus the moment (M_x, M_y, M_z) [N m]; F_x goes to the drive at the
    origin, its moment about the origin to the guides."""
    f = checks.finite("force", force)
    r = checks.finite("point", point)
    torque = np.cross(r, f) + checks.finite("moment", moment)
    return np.array([f[1], f[2], *torque])


def point_displacement(q, point) -> np.ndarray:
    """(d_x, d_y, d_z) [m] of the table point (x, y, z) [m] at the displacement q (eq. 1)."""
    q = np.asarray(q, dtype=float)
    x, y, z = np.asarray(point, dtype=float)
    return np.array([q[3] * z - q[4] * y, *(transfer([(x, y, z)])[0] @ q)])


@dataclass(frozen=True)
class Equilibrium:
    """The table at rest under a load: q, each ball's load [N], approach [m] and contact angle
    [rad], and the tangent stiffness (5 x 5) with each ball's 2 x 2 share."""

    q: np.ndarray
    loads: np.ndarray
    approaches: np.ndarray
    angles: np.ndarray
    ball_tangents: np.ndarray
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
        self.points, self.compress, self.slider = layout.balls()
        self.g = transfer(self.points)

    def contact(self, q):
        """(approach [m], unit normal (N, 2), centre distance |v| [m]) of every ball at q."""
        d = self.g @ np.asarray(q, dtype=float)
        if not self.angle_change:
            return self.rest + np.einsum("ij,ij->i", self.compress, d), self.compress, None
        v = self.distance * self.compress + d
        length = np.linalg.norm(v, axis=1)
        return self.rest + length - self.distance, v / length[:, None], length

    def restoring(self, q) -> np.ndarray:
        """Generalized force of the balls on the table, - sum G^T Q n [N, N m]."""
        approach, normal, _ = self.contact(q)
        loads = hertz_point.load(self.k_h, approach)
        return -np.einsum("nij,ni->j", self.g, loads[:, None] * normal)

    def ball_tangents(self, q) -> np.ndarray:
        """(N, 2, 2) stiffness of each ball against its slider's (d_y, d_z) [N/m]: k n n^T, plus
        the turning of the contact line (Q / |v|)(I - n n^T) with the angle change."""
        approach, normal, length = self.contact(q)
        k = hertz_point.stiffness(self.k_h, approach)
        nn = normal[:, :, None] * normal[:, None, :]
        out = k[:, None, None] * nn
        if length is not None:
            loads = hertz_point.load(self.k_h, approach)
            out += (loads / length)[:, None, None] * (np.eye(2) - nn)
        return out

    def tangent(self, q, ball_tangents=None) -> np.ndarray:
        """Tangent stiffness of the table, sum G^T T G (5 x 5) [N/m, N, N m]."""
        t = self.ball_tangents(q) if ball_tangents is None else ball_tangents
        return np.einsum("nia,nij,njb->ab", self.g, t, self.g)

    def _solve(self, load, start):
        def residual(q):
            return self.restoring(q) + load

        def jacobian(q):
            return -self.tangent(q)

        found = root(residual, start, jac=jacobian, method="hybr")
        return found.x, float(np.max(np.abs(residual(found.x))))

    def equilibrium(self, load, start=None) -> Equilibrium:
        """The table's rest under the generalized load (F_y, F_z, M_x, M_y, M_z) [N, N m],
        searched from ``start`` (default: the linear answer). Converged when the force balance
        holds to 1e-9 of the load or the preload; load steps are tried if a direct solve fails."""
        load = checks.finite("load", load)
        scale = max(float(np.max(np.abs(load))), self.preload)
        q0 = (np.linalg.solve(self.tangent(np.zeros(5)), load) if start is None
              else np.asarray(start, dtype=float))
        q, error = self._solve(load, q0)
        for steps in CONTINUATION_STEPS:
            if error <= 1e-9 * scale:
                break
            q = np.zeros(5)
            for fraction in np.arange(1, steps + 1) / steps:
                q, error = self._solve(fraction * load, q)
        if not error <= 1e-9 * scale:  # NaN: not converged either
            raise ValueError(f"no static equilibrium found under the load {load.tolist()} "
                             f"(F_y, F_z, M_x, M_y, M_z): force balance off by {error:.3g}")
        approach, normal, _ = self.contact(q)
        tangents = self.ball_tangents(q)
        return Equilibrium(q, hertz_point.load(self.k_h, approach), approach,
                           np.arctan2(np.abs(normal[:, 1]), np.abs(normal[:, 0])), tangents,
                           self.tangent(q, tangents))

    def slider_stiffness(self, state: Equilibrium) -> np.ndarray:
        """(4, 2) lateral and vertical tangent stiffness [N/m] of each slider: its balls' shares
        summed, the slider moved in y or z alone."""
        out = np.zeros((4, 2))
        for m in range(4):
            t = state.ball_tangents[self.slider == m].sum(axis=0)
            out[m] = t[0, 0], t[1, 1]
        return out

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
    [N]. Each solve starts from the last one's answer."""

    inputs = ("F_x", "F_y", "F_z", "point_x", "point_y", "point_z", "x_feed")

    def __init__(self, unit: FeedUnit):
        self.unit, self._last = unit, None

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
