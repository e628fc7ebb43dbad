"""Raceway wear of a linear ball guide and the preload it costs over the running distance
(Zhang, Wang and Jiang, fractal-creep wear, eqs. 23-31 and 48-63), SI units.

The slider (the paper's Fig. 3) runs on four rows of n_s balls at the contact angle alpha; a
vertical load F [N, toward the rail] presses the two upper rows and relieves the two lower
ones. A ball sits between its slider and rail grooves, two Hertz contacts in series
(hertz_point.ball_constant): Q = K delta^1.5. Every row is built with the interference delta_0
(the ball's approach at rest, Table 1's initial deformation); a row whose raceways have worn by
h (ball and raceway together) keeps delta_0 - 0.5 h of it (eqs. 60, 63).

* **Statics** (eqs. 28-31): the slider sinks by z until
  F = 2 n_s cos(alpha) (Q(delta_u + z cos alpha) - Q(delta_l - z cos alpha)), the load shared
  by statics rather than equally among the balls; a row whose approach falls to 0 lets go.
* **One ball** (:meth:`Guide.contact`): its contact ellipse on the slider groove (eqs. 23-26,
  hertz_point; a along the rolling, b across), the rolling friction mu_b (eqs. 36-37) and the
  tangential force that keeps the ball rolling, mu_b Q, unless a fixed ratio P_x / (mu Q) is
  given; Carter's creep from it (physics/wear/creep.py): the micro-slip area S_s and creep rate
  zeta_x.
* **Fractal wear** (physics/wear/fractal.py): the differential surfaces of the slip area carry the
  Hertz mean pressure P_m = Q / (pi a b) (eq. 21) and shed V_0 per metre slid (eq. 53); over the
  running distance L a ball slides |zeta_x| L (eq. 54) and the row wears
  V = n_s K_f V_0 |zeta_x| L (eq. 55), spread over the raceway strip of length
  l_r = (D_w (n_s - 1) + 1) D_b and width 2 b (eqs. 57-58):
  dh/dL = n_s K_f V_0 |zeta_x| / (2 l_r b). Eq. 56 as printed carries a stray S_0 and twice the
  factor of eqs. 51-55, which are used instead. The rate is computed once on a grid of ball
  loads and interpolated (:attr:`Guide.rate_table`).
* **Preload** (eqs. 60-63): the wear depth w = (h_u + h_l) / 4 is the slider's share of the
  wear, averaged over the opposed rows; the preload deformation, every ball's approach at rest
  without load, is delta_0 - w, and the preload is lost when w reaches delta_0 (the slider then
  has clearance). The vertical displacement is z: elastic, plus what wear adds (eq. 62).

:func:`simulate` integrates h_u, h_l over the distance with SciPy (RK45) and locates the
preload loss as an event; :meth:`Guide.advance` steps them over one distance increment.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from .. import checks
from . import creep, fractal
from ..ball_guides import hertz_point
from ..papers import zhang_wang_jiang as paper
from ..roots import bracketed_root

#: ball loads of the rate table: geometric from the load where the Hertz mean pressure reaches
#: the yield strength (no wear below it) up to this multiple of it
RATE_TABLE_SPAN = 1e4
RATE_TABLE_POINTS = 800
#: the distance integration's relative tolerance and absolute one in metres of wear
RTOL, ATOL = 1e-8, 1e-15
#: evaluations of the wear rate one distance integration may take: the paper's runs take up to
#: about 1200 (1e10 m under 500 N); past the preload's loss the upper rows' wear accelerates
#: without end
MAX_RATE_EVALUATIONS = 5_000


@dataclass(frozen=True)
class BallContact:
    """One ball's contact under the load Q [N]: semi-axes a (along) and b (across) [m], the
    ball's approach [m], Hertz mean pressure [Pa], rolling friction mu_b [-], tangential force
    ratio P_x / (mu Q) [-], Carter's creep, and the row's wear rate dh/dL [m/m]."""

    load: float
    along: float
    across: float
    approach: float
    pressure: float
    rolling_friction: float
    tangential_ratio: float
    creep: creep.Creep
    wear_rate: float


@dataclass(frozen=True)
class Guide:
    """A linear ball guide's slider and its wear parameters; the defaults are the LG20 of the
    paper (papers.zhang_wang_jiang: Table 1, E and nu that give its E* = 1.143e5 MPa, and the
    project's reading of the fractal dimension D), except where it states none: ``friction``
    (mu of Carter's creep), ``spacing_ratio`` (D_w, touching balls)."""

    ball_diameter: float = paper.BALL_DIAMETER  # D_b [m]
    conformity: float = paper.CONFORMITY  # f, groove radius / ball diameter
    balls_per_row: int = paper.BALLS_PER_ROW  # n_s
    contact_angle: float = math.radians(paper.CONTACT_ANGLE_DEG)  # alpha [rad]
    preload_deformation: float = paper.PRELOAD_DEFORMATION  # delta_0 [m], approach at rest
    youngs_modulus: float = paper.YOUNGS_MODULUS  # E [Pa], balls and raceways
    poisson_ratio: float = paper.POISSON_RATIO  # nu
    yield_strength: float = paper.YIELD_STRENGTH  # sigma_s [Pa]
    hardness: float | None = None  # H [Pa]; None: paper.HARDNESS_PER_YIELD sigma_s
    fractal_dimension: float = paper.FRACTAL_DIMENSION  # D of the raceway surface, 2 < D < 3
    fractal_scale: float = paper.FRACTAL_SCALE  # G [m]
    wear_coefficient: float = paper.WEAR_COEFFICIENT  # K_f
    friction: float = 0.1  # mu
    hysteresis: float = paper.HYSTERESIS  # tau
    spacing_ratio: float = 1.0  # D_w, ball centre distance over diameter
    tangential_ratio: float | None = None  # P_x / (mu Q); None: mu_b / mu (rolling resistance)
    lateral_ratio: float = 0.0  # P_y / (mu Q)
    groove: hertz_point.BallGroove = field(init=False, repr=False, compare=False)
    surface: fractal.FractalSurface = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        checks.positive_integer("balls_per_row", self.balls_per_row)
        if not 0.0 < self.contact_angle < np.pi / 2:
            raise ValueError(f"contact_angle must lie in (0, 90) degrees, got "
                             f"{math.degrees(self.contact_angle)!r}")
        for name in ("preload_deformation", "wear_coefficient", "hysteresis"):
            checks.non_negative(name, getattr(self, name))
        for name in ("friction", "spacing_ratio"):
            checks.positive(name, getattr(self, name))
        if self.spacing_ratio < 1.0:
            raise ValueError(f"spacing_ratio must be >= 1 (balls cannot overlap), got "
                             f"{self.spacing_ratio!r}")
        if self.tangential_ratio is not None:
            creep.adhesion_ratio("tangential_ratio", self.tangential_ratio)
        creep.adhesion_ratio("lateral_ratio", self.lateral_ratio)
        object.__setattr__(self, "groove", hertz_point.BallGroove(
            self.ball_diameter, self.conformity, self.youngs_modulus, self.poisson_ratio,
            self.youngs_modulus, self.poisson_ratio))
        e_star = self.groove.e_reduced / 2  # 1/E* = sum (1 - nu^2)/E (eq. 11)
        object.__setattr__(self, "surface", fractal.FractalSurface(
            self.fractal_dimension, self.fractal_scale, e_star, self.yield_strength,
            paper.HARDNESS_PER_YIELD * self.yield_strength if self.hardness is None
            else self.hardness))

    # -- one ball ---------------------------------------------------------------------------
    @functools.cached_property
    def ball_constant(self) -> float:
        """K [N/m^1.5] of Q = K delta^1.5 for a ball between its two grooves."""
        return hertz_point.ball_constant(self.groove)

    @functools.cached_property
    def strip_length(self) -> float:
        """l_r [m] (eq. 58): the raceway strip a row of balls covers."""
        return (self.spacing_ratio * (self.balls_per_row - 1) + 1) * self.ball_diameter

    def contact(self, load: float) -> BallContact:
        """One ball's contact, creep and the row's wear rate at the ball load Q [N] > 0."""
        q = float(checks.positive("load", load))
        across, along = (float(v) for v in hertz_point.semi_axes(self.groove, q))
        approach = float(hertz_point.approach(self.ball_constant, q))
        mu_b = creep.rolling_friction(along, self.ball_diameter / 2, approach, self.hysteresis)
        ratio = mu_b / self.friction if self.tangential_ratio is None else self.tangential_ratio
        state = creep.creep(along, across, self.ball_diameter, self.friction, ratio,
                            self.lateral_ratio)
        pressure = q / (np.pi * along * across)
        volume = self.surface.wear_per_length(state.slip_area, pressure)
        rate = (self.balls_per_row * self.wear_coefficient * volume * abs(state.creep_along)
                / (2 * self.strip_length * across))
        return BallContact(q, along, across, approach, pressure, mu_b, ratio, state, rate)

    @functools.cached_property
    def threshold_load(self) -> float:
        """The ball load [N] at which the Hertz mean pressure reaches sigma_s: below it the
        lubricant carries the asperities and nothing wears."""
        across, along = hertz_point.semi_axes(self.groove, 1.0)  # both grow as Q^(1/3)
        return float((self.yield_strength * np.pi * along * across) ** 1.5)

    @functools.cached_property
    def rate_table(self) -> tuple[np.ndarray, np.ndarray]:
        """(ln Q, dh/dL) on the grid of ball loads the rate is interpolated in; it ends before
        a load at which the balls would slide (the tangential force reaching mu Q)."""
        loads = self.threshold_load * np.geomspace(1.0 + 1e-9, RATE_TABLE_SPAN, RATE_TABLE_POINTS)
        rates = []
        for q in loads:
            try:
                rates.append(self.contact(q).wear_rate)
            except ValueError:
                break
        if len(rates) < 2:
            raise ValueError(f"the balls slide at every load above the threshold "
                             f"{self.threshold_load:.4g} N: the tangential force reaches mu Q")
        return np.log(loads[:len(rates)]), np.array(rates)

    def wear_rate(self, load: float) -> float:
        """dh/dL [m/m] of a row whose balls carry Q [N]: 0 up to the threshold load,
        interpolated in ln Q above it (computed directly beyond the table)."""
        q = float(load)
        if q <= self.threshold_load:
            return 0.0
        log_q, rates = self.rate_table
        if math.log(q) > log_q[-1]:
            return self.contact(q).wear_rate
        return float(np.interp(math.log(q), log_q, rates))

    # -- the slider -------------------------------------------------------------------------
    def settle(self, load: float, upper: float, lower: float) -> tuple[float, float, float]:
        """(z [m], Q_upper, Q_lower [N]): the slider's sinking under the vertical load F [N] and
        its balls' loads, the upper and lower rows built with the interferences ``upper``,
        ``lower`` [m] (negative: clearance)."""
        f = float(checks.finite("load", load))
        k, n, c = self.ball_constant, self.balls_per_row, math.cos(self.contact_angle)

        def balance(z):
            return 2 * n * c * (hertz_point.load(k, upper + z * c)
                                - hertz_point.load(k, lower - z * c)) - f

        reach = abs(upper) + abs(lower) + (abs(f) / (2 * n * c * k)) ** (2 / 3)
        z = bracketed_root(balance, -reach / c, reach / c,
                           f"the slider's sinking under {f:.6g} N (interferences {upper:.6g}, "
                           f"{lower:.6g} m)", xtol=1e-18, rtol=1e-13)
        return float(z), float(hertz_point.load(k, upper + z * c)), float(
            hertz_point.load(k, lower - z * c))

    def interferences(self, wear) -> tuple[float, float]:
        """(delta_u, delta_l) [m] left to the rows whose wear depths are (h_u, h_l) [m]."""
        h_u, h_l = wear
        return self.preload_deformation - 0.5 * h_u, self.preload_deformation - 0.5 * h_l

    def rates(self, load: float, wear) -> tuple[float, float]:
        """(dh_u/dL, dh_l/dL) [m/m] under the vertical load F [N] at the wear depths (h_u, h_l)."""
        _, q_u, q_l = self.settle(load, *self.interferences(wear))
        return self.wear_rate(q_u), self.wear_rate(q_l)

    def state(self, load: float, wear) -> dict:
        """The slider at the rows' wear depths (h_u, h_l) [m] under F [N]: wear depth w and
        preload deformation delta_0 - w [m], the preload Q_0 [N] per ball, z [m], the balls'
        loads [N] and the slider's raceway wear 0.5 h of each row [m] (eq. 60)."""
        upper, lower = self.interferences(wear)
        z, q_u, q_l = self.settle(load, upper, lower)
        depth = (wear[0] + wear[1]) / 4
        at_rest = self.preload_deformation - depth
        return {"wear_depth": depth, "preload_deformation": at_rest,
                "preload": float(hertz_point.load(self.ball_constant, at_rest)),
                "vertical_displacement": z, "ball_load_upper": q_u, "ball_load_lower": q_l,
                "wear_upper": 0.5 * float(wear[0]), "wear_lower": 0.5 * float(wear[1])}

    def advance(self, load: float, wear, distance: float) -> np.ndarray:
        """(h_u, h_l) [m] after running ``distance`` [m] >= 0 under the load F [N] held."""
        d = float(checks.non_negative("distance", distance))
        wear = np.asarray(wear, dtype=float)
        if d == 0.0:
            return wear
        return self.integrate(load, d, wear).y[:, -1]

    def integrate(self, load: float, distance: float, wear, **options):
        """SciPy's solution of (h_u, h_l) [m] from ``wear`` over ``distance`` [m] > 0 under the
        load F [N] held (``options``: solve_ivp's t_eval, events, dense_output). Raises
        RuntimeError naming the distance and the load when it fails or needs more than
        MAX_RATE_EVALUATIONS evaluations of the rates."""
        what = f"wear integration over {distance:g} m under {load:g} N"
        evaluations = 0

        def rates(s, h):
            nonlocal evaluations
            evaluations += 1
            if evaluations > MAX_RATE_EVALUATIONS:
                raise RuntimeError(f"{what}: more than {MAX_RATE_EVALUATIONS} evaluations of "
                                   f"the wear rate (the wear keeps accelerating): shorten the "
                                   f"distance or lower the load")
            return self.rates(load, h)

        sol = solve_ivp(rates, (0.0, distance), wear, rtol=RTOL, atol=ATOL, **options)
        if not sol.success:
            raise RuntimeError(f"{what} failed: {sol.message}")
        return sol


@dataclass(frozen=True)
class WearHistory:
    """The slider over the running distance: each key of :meth:`Guide.state` as an array over
    ``distance`` [m], and the distance [m] at which the preload is lost (None: not within)."""

    distance: np.ndarray
    columns: dict
    preload_lost_at: float | None


def simulate(guide: Guide, load: float, distance: float, points: int = 101) -> WearHistory:
    """The slider under the vertical load F [N] over ``distance`` [m] of running, at ``points``
    equally spaced distances from 0."""
    total = float(checks.positive("distance", distance))
    checks.finite("load", load)
    if isinstance(points, bool) or not isinstance(points, int) or points < 2:
        raise ValueError(f"points must be a whole number >= 2, got {points!r}")

    def lost(s, h):
        return guide.preload_deformation - (h[0] + h[1]) / 4

    lost.terminal, lost.direction = False, -1
    grid = np.linspace(0.0, total, points)
    sol = guide.integrate(load, total, [0.0, 0.0], t_eval=grid, events=lost, dense_output=True)
    rows = [guide.state(load, sol.y[:, i]) for i in range(grid.size)]
    columns = {key: np.array([row[key] for row in rows]) for key in rows[0]}
    at = sol.t_events[0]
    return WearHistory(grid, columns, float(at[0]) if at.size else None)


class DistanceModel:
    """The slider's wear as the Wear FMU steps it: inputs F_load [N] (vertical load) and
    distance [m] (running distance); states the rows' wear depths (h_u, h_l) [m], advanced along
    the distance, not in time (the monolithic reference, which integrates in time, has no
    model of it)."""

    inputs = ("F_load", "distance")
    states = ("row_wear_upper", "row_wear_lower")

    def __init__(self, guide: Guide):
        self.guide = guide

    def advance(self, state, inputs: dict, distance: float) -> np.ndarray:
        """The state after ``distance`` [m] of running under the load input held."""
        return self.guide.advance(inputs["F_load"], state, distance)

    def outputs(self, state, inputs: dict) -> dict:
        """:meth:`Guide.state` at the state under the load input."""
        return self.guide.state(inputs["F_load"], state)


def from_parameters(ball_diameter, conformity, balls_per_row, contact_angle,
                    initial_deformation, youngs_modulus, poisson_ratio, yield_strength, hardness,
                    fractal_dimension, fractal_scale, wear_coefficient, friction, hysteresis,
                    spacing_ratio, rolling_resistance, tangential_ratio,
                    lateral_ratio) -> DistanceModel:
    """The validated model of the Wear FMU's parameters (fmus/README.md): ``hardness`` 0 takes
    2.8 yield_strength; ``rolling_resistance`` true takes the tangential force from the rolling
    friction, false the fixed ``tangential_ratio``."""
    return DistanceModel(Guide(
        ball_diameter, conformity, balls_per_row, contact_angle, initial_deformation,
        youngs_modulus, poisson_ratio, yield_strength, hardness if hardness != 0 else None,
        fractal_dimension, fractal_scale, wear_coefficient, friction, hysteresis, spacing_ratio,
        None if rolling_resistance else tangential_ratio, lateral_ratio))
