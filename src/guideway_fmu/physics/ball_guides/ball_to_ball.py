"""Ball-to-ball contact friction in a four-point contact linear ball bearing (Lin, Duan and
Okwudire 2019, section 2 and appendix), SI units.

A ball of radius R_B rolls between a fixed bottom groove and a top groove moving at v along z.
It touches the grooves at BL, BR, TR, TL (bottom/top, left/right) at the contact angles
beta_i = beta_0 + Delta beta_i from the -y or +y axis. Its steady motion is the translation v_B
along z and the rotation (omega_x, omega_y).

* **Contact loads** (:func:`contact_loads`). The external load (N_x, -N_y) on the top groove
  is shared by the four Hertz contacts (hertz_point) from the statics of ball and top groove at
  the deviated angles. The contacts are unpreloaded and touch at rest.
* **Friction maps** (:func:`friction_maps`, eqs. A4-A7). Each contact ellipse (semi-axes a
  across, b along z) slides about a velocity centre at c_i from its centre (eqs. 1-3, A1-A3).
  The friction force f_i along z, the moment M_i about the contact centre and the loss P_i,
  normalised by mu F_i (and a_i), depend only on c_i/a_i and b/a. They are integrated once over
  the Hertz pressure on a Gauss-Legendre x uniform polar grid and interpolated, as the paper
  does. Beyond the grid they take their sliding limits.
* **Numerical model** (:func:`solve_group`, eqs. 4-10). Each ball is in quasi-static
  equilibrium of its four friction forces and moments (eq. 4). Balls in contact share one
  velocity and push each other with F_B2B. The friction at a ball-to-ball contact (eqs. 5-7)
  adds its moment (-f_y, f_x) to both balls. Solved with scipy.optimize.root.
* **Analytical model** (eqs. 11-33). The friction force is linear in c_i/a_i with slope k_f,
  the moment sits at its spin value (eq. 11). The velocity deviation is eq. 22 and the contact
  force eq. 30. k_f is the least-squares slope of the normalised friction force over
  |c/a| <= 0.5 from the map (1.382 for b/a = 0.2; the paper reads 1.38 off its Fig. 5).
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from scipy.optimize import root

from .. import checks
from . import hertz_point

CONTACTS = ("BL", "BR", "TR", "TL")
#: side of each contact: x sign of its normal and y sign (bottom -1, top +1)
_SX = np.array([-1.0, 1.0, 1.0, -1.0])
_SY = np.array([-1.0, -1.0, 1.0, 1.0])
LINEAR_RANGE = 0.5  # |c/a| over which the friction force is taken as linear (paper, Fig. 5)
#: c/a grid of the maps: fine near the contact, coarser out to the sliding limit
_GRID = np.unique(np.concatenate([np.linspace(-3, 3, 601), np.geomspace(3, 60, 60),
                                  -np.geomspace(3, 60, 60)]))


@dataclass(frozen=True)
class FrictionMaps:
    """Normalised friction force f/(sgn(omega) mu F), moment M/(sgn(omega) mu F a) and loss
    P/(|omega| mu F a) against c/a, for one b/a."""

    aspect: float
    ratio: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    loss: np.ndarray

    def at(self, ratio):
        """(force, moment, loss) at c/a, interpolated; sliding limits beyond the grid."""
        k = np.asarray(ratio, dtype=float)
        inside = np.abs(k) <= self.ratio[-1]
        force = np.where(inside, np.interp(k, self.ratio, self.force), -np.sign(k))
        moment = np.where(inside, np.interp(k, self.ratio, self.moment), 0.0)
        loss = np.where(inside, np.interp(k, self.ratio, self.loss), np.abs(k))
        return force, moment, loss

    @property
    def slope(self) -> float:
        """k_f: least-squares slope of -force over |c/a| <= LINEAR_RANGE, through 0."""
        near = np.abs(self.ratio) <= LINEAR_RANGE
        k = self.ratio[near]
        return float(-np.sum(k * self.force[near]) / np.sum(k * k))


def integrate_maps(aspect: float, ratios, radial: int = 64, angular: int = 512) -> np.ndarray:
    """(n, 3) normalised force, moment and loss at the c/a values ``ratios`` (eqs. A4-A6 divided
    by mu F = mu sigma_0 2 pi a b / 3), by quadrature on the unit disc: r = sin(psi) with
    Gauss-Legendre in psi (smooth at the rim), midpoints in the polar angle."""
    x, w = np.polynomial.legendre.leggauss(radial)
    psi, w_psi = (x + 1) * np.pi / 4, w * np.pi / 4
    r = np.sin(psi)
    theta = (np.arange(angular) + 0.5) * 2 * np.pi / angular
    t = np.outer(r, np.cos(theta)).ravel()
    s = np.outer(r, np.sin(theta)).ravel()
    weight = np.outer(np.cos(psi) ** 2 * r * w_psi, np.full(angular, 2 * np.pi / angular)).ravel()
    out = np.empty((len(ratios), 3))
    for i, k in enumerate(np.asarray(ratios, dtype=float)):
        speed = np.sqrt((t - k) ** 2 + (aspect * s) ** 2)
        out[i] = (weight @ ((t - k) / speed),
                  weight @ ((t * t - k * t + aspect**2 * s * s) / speed), weight @ speed)
    return 3.0 / (2.0 * np.pi) * out


@functools.lru_cache(maxsize=16)
def friction_maps(aspect: float) -> FrictionMaps:
    """The maps for the ellipse ratio b/a = ``aspect`` (0 < b/a <= 1), computed once."""
    checks.in_range("aspect", aspect, 1e-6, 1.0)
    values = integrate_maps(aspect, _GRID)
    return FrictionMaps(aspect, _GRID, values[:, 0], values[:, 1], values[:, 2])


@dataclass(frozen=True)
class Bearing:
    """Ball radius R_B [m], groove conformity R_G / (2 R_B), materials, metal friction mu,
    nominal contact angle beta_0 [rad] and the top groove's velocity v [m/s]."""

    radius: float
    conformity: float
    youngs_modulus: float
    poisson_ratio: float
    friction: float
    nominal_angle: float
    velocity: float

    def __post_init__(self):
        checks.positive("radius", self.radius)
        checks.positive("youngs_modulus", self.youngs_modulus)
        checks.in_range("poisson_ratio", self.poisson_ratio, 0.0, 0.5)
        checks.positive("friction", self.friction)
        if not 0.0 < self.nominal_angle < np.pi / 2:
            raise ValueError(f"nominal_angle must lie in (0, 90) degrees, got "
                             f"{np.degrees(self.nominal_angle)!r}")
        checks.positive("velocity", self.velocity)
        self.groove  # checks the conformity

    @functools.cached_property
    def groove(self) -> hertz_point.BallGroove:
        return hertz_point.BallGroove(2 * self.radius, self.conformity, self.youngs_modulus,
                                      self.poisson_ratio, self.youngs_modulus, self.poisson_ratio)

    @functools.cached_property
    def hertz(self) -> float:
        """K [N/m^1.5] of one ball-groove contact."""
        return hertz_point.constant(self.groove)

    @functools.cached_property
    def psi(self) -> float:
        """Psi [(m^2/N)^(1/3)] of a = Psi (R_B F)^(1/3) (eq. 15)."""
        a, _ = hertz_point.semi_axes(self.groove, 1.0)
        return float(a / self.radius ** (1 / 3))

    @functools.cached_property
    def aspect(self) -> float:
        """b/a of every contact ellipse (fixed by the conformity)."""
        return 1.0 / hertz_point.ellipse(self.groove).kappa

    @property
    def maps(self) -> FrictionMaps:
        return friction_maps(round(self.aspect, 12))


def contact_angles(bearing: Bearing, deviations) -> np.ndarray:
    """beta_i = beta_0 + Delta beta_i [rad] of BL, BR, TR, TL."""
    return bearing.nominal_angle + checks.finite("deviations", deviations)


def _normals(angles) -> np.ndarray:
    """(4, 2) unit normals from the ball centre to the contacts, in the cross-section (x, y)."""
    return np.column_stack([_SX * np.sin(angles), _SY * np.cos(angles)])


def contact_loads(bearing: Bearing, angles, side: float, normal: float) -> np.ndarray:
    """F_i [N] of BL, BR, TR, TL under the load (side, -normal) on the top groove: N_y =
    ``normal`` > 0 presses it down, N_x = ``side`` pushes it along +x. The ball and the top
    groove settle in equilibrium on the four unpreloaded Hertz contacts. ValueError when a
    contact would have to pull (the ball is no longer in four-point contact)."""
    checks.positive("normal", normal)
    n = _normals(angles)
    k = bearing.hertz
    top = _SY > 0

    def approaches(z):
        ball, groove = z[:2], z[2:]
        return n @ ball - np.where(top, n @ groove, 0.0)

    def residual(z):
        loads = k * np.maximum(approaches(z), 0.0) ** 1.5
        on_ball = -(loads[:, None] * n).sum(axis=0)
        on_groove = (loads[top, None] * n[top]).sum(axis=0) + (side, -normal)
        return np.concatenate([on_ball, on_groove]) / normal

    reach = (np.array(diagonal_loads(bearing, side, normal)) / k) ** (2 / 3)  # the start
    groove = np.linalg.solve(n[[0, 1]] / 2, reach)  # ball halfway: BL-TR and BR-TL equal
    found = root(residual, np.concatenate([groove / 2, groove]), method="hybr", tol=1e-14)
    loads = k * np.maximum(approaches(found.x), 0.0) ** 1.5
    if not np.max(np.abs(residual(found.x))) <= 1e-9:  # NaN: not converged either
        raise ValueError(f"no four-point contact equilibrium under N_x = {side:g} N, "
                         f"N_y = {normal:g} N")
    slack = [name for name, f in zip(CONTACTS, loads) if f < 1e-3 * normal]
    if slack:
        raise ValueError(f"contact {', '.join(slack)} carries (almost) nothing under N_x = "
                         f"{side:g} N, N_y = {normal:g} N: the ball is out of four-point contact, "
                         f"which the model does not cover")
    return loads


@dataclass(frozen=True)
class Ball:
    """One ball: its contact angles [rad] and contact loads [N], BL, BR, TR, TL."""

    angles: np.ndarray
    loads: np.ndarray


def _contact_state(bearing: Bearing, ball: Ball, v_b, wx, wy):
    """omega_i [rad/s], c_i [m] and the semi-axes a_i [m] of the four contacts (eqs. 2, A1-A3)."""
    s, c, r = np.sin(ball.angles), np.cos(ball.angles), bearing.radius
    v = bearing.velocity
    spin = np.array([wx * s[0] + wy * c[0], -wx * s[1] + wy * c[1],
                     -wx * s[2] - wy * c[2], wx * s[3] - wy * c[3]])
    centre = np.array([v_b - (wx * c[0] - wy * s[0]) * r, v_b - (wx * c[1] + wy * s[1]) * r,
                       v_b - v + (wx * c[2] - wy * s[2]) * r, v_b - v + (wx * c[3] + wy * s[3]) * r])
    a = bearing.psi * (r * ball.loads) ** (1 / 3)
    return spin, centre / spin, a


def groove_friction(bearing: Bearing, ball: Ball, v_b, wx, wy):
    """(f_i [N], M_i [N m], P_i [W]) of the four contacts at the motion (v_B, omega_x,
    omega_y) (eqs. A4-A7 through the maps)."""
    spin, centre, a = _contact_state(bearing, ball, v_b, wx, wy)
    ratio = np.divide(centre, a, out=np.zeros(4), where=a > 0)  # an unloaded contact: no friction
    force, moment, loss = bearing.maps.at(ratio)
    mu_f = bearing.friction * ball.loads
    return (np.sign(spin) * mu_f * force, np.sign(spin) * mu_f * a * moment,
            np.abs(spin) * mu_f * a * loss)


def _equilibrium(bearing: Bearing, ball: Ball, f, m) -> np.ndarray:
    """The three rows of eq. 4: force along z, moments about x and y over R_B [N]."""
    s, c = np.sin(ball.angles), np.cos(ball.angles)
    moment = -m / bearing.radius
    return np.array([f.sum(),
                     np.dot([-c[0], -c[1], c[2], c[3]], f) + np.dot([s[0], -s[1], -s[2], s[3]], moment),
                     np.dot([s[0], -s[1], -s[2], s[3]], f) + np.dot([c[0], c[1], -c[2], -c[3]], moment)])


def contact_friction(bearing: Bearing, w_rear, w_front, force: float):
    """Friction (f_x, f_y) [N] on the rear ball at its contact with the front one under the
    normal force [N] (eqs. 5, 6) and the loss mu F |Delta v| [W] there (eq. 7), from the two
    balls' (omega_x, omega_y) [rad/s]."""
    slide = bearing.radius * np.array([w_rear[1] + w_front[1], -(w_rear[0] + w_front[0])])
    speed = float(np.hypot(*slide))
    friction = -slide / speed * bearing.friction * force if speed > 0 else np.zeros(2)
    return friction, bearing.friction * force * speed


@dataclass(frozen=True)
class GroupMotion:
    """A group of balls in contact, rear first: common velocity v_B [m/s], each ball's
    (omega_x, omega_y) [rad/s], the contact forces between neighbours [N], the ball-to-ball
    friction loss [W] and the groove friction loss [W]."""

    velocity: float
    spins: np.ndarray
    contact_forces: np.ndarray
    contact_loss: float
    groove_loss: float


def solve_group(bearing: Bearing, balls: list[Ball], start: GroupMotion | None = None,
                _depth: int = 0) -> GroupMotion:
    """The numerical model of balls in contact (eqs. 4-10): unknowns the common v_B, each ball's
    (omega_x, omega_y) and the N - 1 contact forces; one ball alone is eq. 4. Started from
    ``start`` or from pure rolling; if that fails, by continuation from pure rolling with the
    deviations and load differences growing in ten steps."""
    n = len(balls)
    half = bearing.velocity / 2
    roll = half / (bearing.radius * np.cos(bearing.nominal_angle))
    force_scale = bearing.friction * float(np.mean([b.loads.mean() for b in balls]))

    def unpack(z):
        return half * (1 + z[0]), roll * z[1:1 + 2 * n].reshape(n, 2), force_scale * z[1 + 2 * n:]

    def residual(z):
        v_b, spins, forces = unpack(z)
        out = []
        frictions = [contact_friction(bearing, spins[j], spins[j + 1], forces[j])[0]
                     for j in range(n - 1)]
        for j, ball in enumerate(balls):
            f, m, _ = groove_friction(bearing, ball, v_b, *spins[j])
            rows = _equilibrium(bearing, ball, f, m)
            for i, sign in ((j, -1.0), (j - 1, 1.0)):  # front contact pushes back, rear forward
                if 0 <= i < n - 1:
                    rows = rows + np.array([sign * forces[i], -frictions[i][1], frictions[i][0]])
            out.append(rows)
        return np.concatenate(out) / force_scale

    if start is None:
        z0 = np.concatenate([[0.0], np.tile([1.0, 0.0], n), np.zeros(n - 1)])
    else:
        z0 = np.concatenate([[start.velocity / half - 1], (start.spins / roll).ravel(),
                             start.contact_forces / force_scale])
    found = root(residual, z0, method="hybr", tol=1e-13)
    error = np.max(np.abs(residual(found.x)))
    if not error <= 1e-8:  # NaN: not converged either
        if _depth > 0 or start is not None:
            loads = ", ".join(f"{b.loads.max():.3g}" for b in balls)
            raise ValueError(f"no quasi-static ball motion found for the balls whose largest "
                             f"contact loads are {loads} N ({found.message}; residual "
                             f"{error:.2g})")
        # continuation from pure rolling: the deviations and the load asymmetry grow in steps
        motion = None
        for fraction in np.linspace(0.1, 1.0, 10):
            step = [Ball(bearing.nominal_angle + fraction * (b.angles - bearing.nominal_angle),
                         b.loads.mean() + fraction * (b.loads - b.loads.mean())) for b in balls]
            motion = solve_group(bearing, step, motion, _depth=1)
        return motion
    v_b, spins, forces = unpack(found.x)
    groove_loss = sum(groove_friction(bearing, b, v_b, *spins[j])[2].sum()
                      for j, b in enumerate(balls))
    contact_loss = sum(contact_friction(bearing, spins[j], spins[j + 1], forces[j])[1]
                       for j in range(n - 1))
    return GroupMotion(float(v_b), spins, forces, float(contact_loss), float(groove_loss))


# -- the analytical model (eqs. 11-33) ----------------------------------------------------------
def diagonal_loads(bearing: Bearing, side, normal):
    """(F_U, F_D) [N]: the BL-TR and BR-TL loads at the nominal angle (Sec. 2.4.1), of one
    ball or of arrays of balls."""
    c, s = np.cos(bearing.nominal_angle), np.sin(bearing.nominal_angle)
    side, normal = np.asarray(side, dtype=float), np.asarray(normal, dtype=float)
    upper, lower = (normal / c - side / s) / 2, (normal / c + side / s) / 2
    if np.min(np.minimum(upper, lower)) <= 0:
        worst = np.max(np.abs(side / normal))
        raise ValueError(f"side_ratio {worst:g} leaves the ball in two-point contact "
                         f"(|N_x / N_y| must stay below tan(beta_0) = {s / c:.3g})")
    return upper[()], lower[()]


def velocity_deviation(bearing: Bearing, deviations, upper, lower):
    """epsilon of eq. 22: v_B = (1 + epsilon) v / 2, from Delta beta_i [rad] (BL, BR, TR, TL
    along the first axis) and the diagonal loads F_U, F_D [N]."""
    d_bl, d_br, d_tr, d_tl = checks.finite("deviations", deviations)
    wu, wd = np.asarray(upper) ** (2 / 3), np.asarray(lower) ** (2 / 3)
    return ((1 - np.cos(2 * bearing.nominal_angle))
            * ((-d_bl + d_tr) * wu + (-d_br + d_tl) * wd) / (2 * (wu + wd)))[()]


def drag(bearing: Bearing, upper, lower):
    """G [N]: the push that changes a ball's epsilon by 1 (eq. 30: F_B2B = G1 G2 /
    (G1 + G2) (epsilon_1 - epsilon_2))."""
    return (2 * bearing.maps.slope * bearing.friction * bearing.radius ** (2 / 3)
            * (np.asarray(upper) ** (2 / 3) + np.asarray(lower) ** (2 / 3))
            / (bearing.psi * (1 - np.cos(2 * bearing.nominal_angle))))[()]


def contact_slide_speed(bearing: Bearing, velocity: float | None = None) -> float:
    """|Delta v_B2B| = |v| / cos(beta_0) [m/s] (eq. 31), v the bearing's or ``velocity`` [m/s]."""
    v = bearing.velocity if velocity is None else velocity
    return abs(v) / np.cos(bearing.nominal_angle)


def group_forces(epsilon, drags) -> tuple[float, np.ndarray]:
    """Common epsilon and the contact forces [N] between neighbours of balls pushed into one
    group (analytical model): each ball's velocity changes by its net push over its drag."""
    e, g = np.asarray(epsilon, dtype=float), np.asarray(drags, dtype=float)
    common = float(np.sum(g * e) / np.sum(g))
    return common, np.cumsum(g * (e - common))[:-1]


def split_groups(epsilon, drags, touching) -> list[list[int]]:
    """Balls (rear first) into groups moving together: neighbours ``touching`` (bool per gap)
    stay together while the rear one pushes (every internal force > 0)."""
    groups = [[0]]
    for j in range(1, len(epsilon)):
        if touching[j - 1]:
            groups[-1].append(j)
        else:
            groups.append([j])
    settled = False
    while not settled:
        settled = True
        out = []
        for group in groups:
            _, forces = group_forces([epsilon[i] for i in group], [drags[i] for i in group])
            if np.any(forces <= 0):
                cut = int(np.argmin(forces)) + 1
                out += [group[:cut], group[cut:]]
                settled = False
            else:
                out.append(group)
        groups = out
    return groups


@dataclass(frozen=True)
class TwoBallCase:
    """The paper's module (Fig. 7): ball 1 behind ball 2, touching, each with its contact-angle
    deviations [rad] (BL, BR, TR, TL) and side load (N_x of ball 1 is +rho N_y, of ball 2
    -rho N_y, both pressed by N_y)."""

    bearing: Bearing
    deviations: tuple  # per ball: (BL, BR, TR, TL) [rad]
    normal: float  # N_y [N]
    side_ratio: float  # rho = N_x / N_y of ball 1

    def sides(self) -> tuple[float, float]:
        return self.side_ratio * self.normal, -self.side_ratio * self.normal


def analytical(case: TwoBallCase) -> dict:
    """Eqs. 22, 30, 32: each ball's velocity deviation, the contact force [N] (0 when ball 1 is
    not faster) and the ball-to-ball friction loss [W]."""
    b = case.bearing
    diagonals = [diagonal_loads(b, side, case.normal) for side in case.sides()]
    eps = [velocity_deviation(b, d, *f) for d, f in zip(case.deviations, diagonals)]
    g = [drag(b, *f) for f in diagonals]
    force = max(g[0] * g[1] / (g[0] + g[1]) * (eps[0] - eps[1]), 0.0)
    return {"epsilon": eps, "contact_force": force,
            "friction_loss": b.friction * force * contact_slide_speed(b), "k_f": b.maps.slope}


def numerical(case: TwoBallCase) -> dict:
    """Eqs. 4-10 with the contact loads from statics: each ball's velocity deviation alone, the
    contact force [N] of the pair once it moves together (0 when it would pull), the
    ball-to-ball and the groove friction loss [W]."""
    b = case.bearing
    balls = []
    for deviation, side in zip(case.deviations, case.sides()):
        angles = contact_angles(b, deviation)
        balls.append(Ball(angles, contact_loads(b, angles, side, case.normal)))
    alone = [solve_group(b, [ball]) for ball in balls]
    eps = [m.velocity / (b.velocity / 2) - 1 for m in alone]
    pair = solve_group(b, balls) if eps[0] > eps[1] else None
    if pair is None or pair.contact_forces[0] <= 0:
        return {"epsilon": eps, "contact_force": 0.0, "friction_loss": 0.0,
                "groove_loss": float(sum(m.groove_loss for m in alone)),
                "epsilon_together": None,
                "contact_loads": [ball.loads.tolist() for ball in balls]}
    return {"epsilon": eps, "contact_force": float(pair.contact_forces[0]),
            "friction_loss": pair.contact_loss, "groove_loss": pair.groove_loss,
            "epsilon_together": pair.velocity / (b.velocity / 2) - 1,
            "contact_loads": [ball.loads.tolist() for ball in balls]}
