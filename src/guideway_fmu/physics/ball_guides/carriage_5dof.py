"""A ball-guide carriage as a rigid body on ball springs, five degrees of freedom (Wu et al. 2012,
eqs. 9-22 and A1-A29), SI units.

Coordinates q = (u, v, phi, theta, psi): lateral u along y [m], vertical v along z [m], roll
phi about x, pitch theta about y, yaw psi about z [rad]; x is the direction of travel, the
origin the carriage's centre of mass. Two rows of balls (left 1, right 2) lie at the contact
angle beta, the contact points at d from the x-y plane and e from the x-z plane; ball i of each
row sits at l_i along x. The approach of ball i grows with the carriage's motion as (eq. A3)

    delta_1i = (u - d phi + l_i psi) cos beta + (-v - e phi + l_i theta) sin beta
    delta_2i = -(u - d phi + l_i psi) cos beta + (-v + e phi + l_i theta) sin beta

i.e. delta = G q, whose five columns G_j (arrays over the balls) :func:`contact_directions`
gives. With normal ball stiffnesses k the stiffness matrix is K_ab = sum k G_a G_b (over the
balls), whose entries are the paper's c_21..c_29
(eqs. 14, 22, A12, A20), and the free vibration solves K phi = omega^2 M phi with
M = diag(m, m, J_x, J_y, J_z) (eqs. A5-A9, here as one generalized eigenproblem). The
u-phi-psi block of two rows is singular: the lateral shift with the roll about the rows'
contact lines' crossing point stretches no ball (omega_20 = 0, eq. A13), a rigid-body mode.

:class:`HertzBalls` computes the stiffnesses the paper lists in its Table 2: every ball carries
the preload Q_0 at rest (approach delta_0 = (Q_0 / K_h)^(2/3)); under the external load
F = (F_y, F_z, M_x, M_y, M_z) the carriage settles where G^T (Q - Q_0) = F with
Q = K_h max(delta_0 + G q, 0)^1.5 (the preload is reacted inside the guide), and each
ball's tangent stiffness is 1.5 K_h delta_i^0.5 (eq. 8). A ball whose approach falls to 0 has
lost contact: it carries and stiffens nothing.

:class:`BallCarriageModel` is the carriage as a continuous-time model for time simulation:
states q and dq/dt, inputs the external force vector and the feed velocity (the balls roll
along the load zone at half of it, so their positions shift through one pitch per two pitches of
travel, which modulates the stiffness at the ball-passage frequency).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from .. import checks
from . import hertz_point
from ..dynamics import ContinuousModel
from ..roots import load_steps, newton_system

DOF = ("u", "v", "phi", "theta", "psi")
LOADS = ("F_y", "F_z", "M_x", "M_y", "M_z")  # generalized forces conjugate to DOF [N, N m]
#: mode names of the dominant coordinates (Wu et al. 2012, Fig. 3): u and phi make rolling
MOTION = {"u": "rolling", "phi": "rolling", "v": "vertical", "theta": "pitching", "psi": "yawing"}
LABEL_SHARE = 0.1  # a coordinate names a mode when it holds this share of its kinetic energy
#: Newton iterations of one equilibrium solve at most, and the finest load steps tried after
NEWTON_ITERATIONS, FINEST_LOAD_STEPS = 50, 64


@dataclass(frozen=True)
class CarriageBody:
    """Mass [kg], inertia (J_x, J_y, J_z) [kg m^2], contact angle beta [rad] and the contact
    points' distances d (from the x-y plane) and e (from the x-z plane) [m]."""

    mass: float
    inertia: tuple[float, float, float]
    contact_angle: float
    d: float
    e: float

    def __post_init__(self):
        checks.positive("mass", self.mass)
        if len(self.inertia) != 3:
            raise ValueError(f"inertia must be [J_x, J_y, J_z], got {self.inertia!r}")
        checks.positive("inertia", np.asarray(self.inertia, dtype=float))
        if not 0.0 < self.contact_angle < np.pi / 2:
            raise ValueError(f"contact_angle must lie in (0, 90) degrees, got "
                             f"{np.degrees(self.contact_angle)!r}")
        checks.finite("d", self.d)
        checks.finite("e", self.e)

    @property
    def arm(self) -> float:
        """d cos(beta) + e sin(beta) [m]: the roll's lever on a ball's approach (eq. A3)."""
        return self.d * np.cos(self.contact_angle) + self.e * np.sin(self.contact_angle)

    def mass_matrix(self) -> np.ndarray:
        """diag(m, m, J_x, J_y, J_z)."""
        return np.diag([self.mass, self.mass, *self.inertia])


def ball_positions(per_row: int, pitch: float, shift: float = 0.0) -> np.ndarray:
    """l_i [m] of ``per_row`` balls ``pitch`` [m] apart, centred on the carriage (eq. 13 with the
    load zone l_L = per_row * pitch); ``shift`` [m] moves them along x, wrapped into the load zone."""
    checks.positive_integer("per_row", per_row)
    checks.positive("pitch", pitch)
    zone = per_row * pitch
    centred = (per_row - 2 * np.arange(1, per_row + 1) + 1) / 2.0 * pitch
    return (centred + shift + zone / 2.0) % zone - zone / 2.0


def contact_directions(body: CarriageBody, positions) -> tuple:
    """G's five columns (DOF order), each an array over the balls, row 1 then row 2: a ball's
    approach grows by sum_j G_j q_j (eq. A3)."""
    l = np.asarray(positions, dtype=float)
    c, s, arm = np.cos(body.contact_angle), np.sin(body.contact_angle), body.arm
    one = np.ones_like(l)
    return (np.concatenate([c * one, -c * one]), np.concatenate([-s * one, -s * one]),
            np.concatenate([-arm * one, arm * one]), np.concatenate([l * s, l * s]),
            np.concatenate([l * c, -l * c]))


def approach_change(directions, q):
    """G q [m]: each ball's change of approach at the displacement q."""
    return sum([g * x for g, x in zip(directions, q)])


def generalized(directions, ball_forces) -> np.ndarray:
    """G^T f [N, N m]: the generalized force of forces f [N] along the balls' approach."""
    return np.array([np.dot(g, ball_forces) for g in directions])


def stiffness_matrix(directions, ball_stiffness) -> np.ndarray:
    """K = G^T diag(k) G [N/m, N, N m] from each ball's normal stiffness k [N/m]."""
    pushed = [np.asarray(ball_stiffness, dtype=float) * b for b in directions]
    return np.array([[np.dot(a, kb) for kb in pushed] for a in directions])


def rigid_direction(body: CarriageBody) -> np.ndarray:
    """The unit displacement that stretches no ball of either row: the lateral shift with the
    roll about the crossing point of the rows' contact lines (omega_20 = 0, eq. A13)."""
    c, arm = np.cos(body.contact_angle), body.arm
    return np.array([arm, 0.0, c, 0.0, 0.0]) / np.hypot(arm, c)


def balanced(body: CarriageBody, directions, loads, stiffness, rest, external) -> np.ndarray:
    """q where balls of normal load ``loads(q)`` [N] (each ball's ``rest`` at q = 0) and tangent
    stiffness ``stiffness(q)`` [N/m] along ``directions`` balance ``external`` (F_y, F_z, M_x,
    M_y, M_z): Newton's method from the unloaded carriage, in load steps where it does not
    converge, to 1e-9 of the load or the largest rest load. The rigid direction (no ball resists
    it) is held at 0: a stiffness along it in the Jacobian keeps every step off it. ValueError
    if the load drives that direction, or if the balls cannot carry it."""
    f = checks.finite("load", external)
    at_rest = stiffness(np.zeros(5))
    if not np.all(at_rest > 0.0):
        raise ValueError("preload must be > 0 for the start in static equilibrium (unpreloaded "
                         "balls have no stiffness at rest)")
    rigid = rigid_direction(body)
    tolerance = 1e-9 * max(float(np.max(np.abs(f))), float(np.max(rest)))
    if abs(float(np.sum(rigid * f))) > tolerance:
        raise ValueError(f"the load {f.tolist()} (F_y, F_z, M_x, M_y, M_z) drives the motion "
                         f"no ball resists (lateral shift with roll); balance it")
    hold = np.trace(stiffness_matrix(directions, at_rest)) * np.outer(rigid, rigid)

    def solve(load, start):
        return newton_system(lambda q: load - generalized(directions, loads(q) - rest),
                             lambda q: -stiffness_matrix(directions, stiffness(q)) - hold,
                             start, tolerance, NEWTON_ITERATIONS)

    q, error = load_steps(solve, f, np.zeros(5), tolerance, FINEST_LOAD_STEPS)
    if not error <= tolerance:  # NaN: not converged either
        raise ValueError(f"no static equilibrium under the load {f.tolist()} (F_y, F_z, M_x, "
                         f"M_y, M_z): more than the balls can carry")
    return q


@dataclass(frozen=True)
class Modes:
    """Natural frequencies [Hz] in ascending order, mass-normalised shapes (columns, over DOF)
    and each mode's kinetic-energy share per coordinate (rows sum to 1)."""

    frequencies: np.ndarray
    shapes: np.ndarray
    participation: np.ndarray

    def label(self, index: int) -> str:
        """'rigid' for a zero mode, else the motions of the coordinates holding LABEL_SHARE of
        its energy, dominant first (e.g. 'pitching-vertical')."""
        if self.frequencies[index] == 0.0:
            return "rigid"
        share = self.participation[index]
        names = []
        for j in np.argsort(-share):
            if share[j] >= LABEL_SHARE and MOTION[DOF[j]] not in names:
                names.append(MOTION[DOF[j]])
        return "-".join(names)


def modes(stiffness: np.ndarray, mass: np.ndarray) -> Modes:
    """Solve K phi = omega^2 M phi (scipy.linalg.eigh). Eigenvalues within 1e-9 of the largest
    (round-off of a singular K) count as rigid-body modes, frequency 0."""
    values, shapes = eigh(stiffness, mass)
    values = np.where(values > 1e-9 * values.max(), values, 0.0)
    energy = np.diag(mass)[:, None] * shapes**2
    return Modes(np.sqrt(values) / (2 * np.pi), shapes, (energy / energy.sum(axis=0)).T)


def paper_frequencies(body: CarriageBody, positions, row_stiffness) -> dict:
    """Wu et al.'s closed forms (eqs. 19-22) [Hz] for per-row ball stiffnesses K_ni [N/m] used
    in both rows: f_RYL, f_PVL, f_PVH, f_RYH (with equal K_ni: f_Y, f_P, f_V, f_R)."""
    l, k = np.asarray(positions, dtype=float), np.asarray(row_stiffness, dtype=float)
    c, s = np.cos(body.contact_angle), np.sin(body.contact_angle)
    m, (jx, jy, jz) = body.mass, body.inertia
    arm = body.arm
    c21, c22, c23 = (np.sum(k * 2 * c**2), np.sum(k * -2 * c * arm), np.sum(k * 2 * arm**2))
    c24, c25, c26 = np.sum(k * 2 * l * c**2), np.sum(k * 2 * l**2 * c**2), np.sum(k * -2 * l * c * arm)
    c27, c28, c29 = np.sum(k * 2 * s**2), np.sum(k * -2 * l * s**2), np.sum(k * 2 * l**2 * s**2)
    a1 = -(c21 * jx * jz + c23 * m * jz + c25 * m * jx)
    a2 = -(c24**2 * jx + c26**2 * m + c22**2 * jz - c23 * c25 * m - c21 * c25 * jx - c21 * c23 * jz)
    root_ry = np.sqrt(a1**2 - 4 * a2 * m * jx * jz)
    pv = c29 * m + c27 * jy
    root_pv = np.sqrt(pv**2 - 4 * m * jy * (c27 * c29 - c28**2))
    omega2 = {"f_RYL": (-a1 - root_ry) / (2 * m * jx * jz), "f_PVL": (pv - root_pv) / (2 * m * jy),
              "f_PVH": (pv + root_pv) / (2 * m * jy), "f_RYH": (-a1 + root_ry) / (2 * m * jx * jz)}
    return {name: float(np.sqrt(w2) / (2 * np.pi)) for name, w2 in omega2.items()}


class HertzBalls:
    """Preloaded Hertz balls in both rows: loads, stiffnesses and the static equilibrium."""

    def __init__(self, body: CarriageBody, positions, k_h: float, preload: float):
        self.body = body
        self.directions = contact_directions(body, positions)
        self.k_h = checks.positive("k_h", k_h)
        self.preload = float(checks.non_negative("preload", preload))
        self.rest = float(hertz_point.approach(k_h, preload))
        #: each ball's load at rest as the Hertz law gives it back (the preload to rounding,
        #: computed as every load is): the carriage at rest then feels no force at all
        self.rest_loads = self.loads(np.zeros(5))

    def approaches(self, q) -> np.ndarray:
        """delta_i [m] of every ball (row 1, then row 2) at the displacement q."""
        return self.rest + approach_change(self.directions, np.asarray(q, dtype=float))

    def loads(self, q) -> np.ndarray:
        """Q_i [N] of every ball."""
        return hertz_point.load(self.k_h, self.approaches(q))

    def ball_stiffness(self, q) -> np.ndarray:
        """Tangent normal stiffness of every ball [N/m] (0 where contact is lost)."""
        return hertz_point.stiffness(self.k_h, self.approaches(q))

    def restoring(self, q) -> np.ndarray:
        """Generalized force of the balls on the carriage, -G^T (Q - Q_0)."""
        return -generalized(self.directions, self.loads(q) - self.rest_loads)

    def tangent(self, q) -> np.ndarray:
        """Tangent stiffness matrix G^T diag(k) G at q."""
        return stiffness_matrix(self.directions, self.ball_stiffness(q))

    def equilibrium(self, external) -> np.ndarray:
        """q where the balls balance ``external`` (F_y, F_z, M_x, M_y, M_z) (:func:`balanced`)."""
        return balanced(self.body, self.directions, self.loads, self.ball_stiffness,
                        self.rest_loads, external)


class BallCarriageModel(ContinuousModel):
    """The carriage in time: states q, dq/dt (DOF order) and the balls' shift s [m] along x;
    inputs the generalized loads LOADS, the feed velocity u_feed [m/s] (ds/dt = u_feed / 2) and
    the balls' preload [N] (a ball's load at rest; it may change during a run, as raceway wear
    takes it away).

    M d2q/dt2 = F + F_0 + R(q, s) - C(q, s) dq/dt, with F_0 the ``static_load`` (LOADS order),
    R the balls' restoring force and C = G^T diag(c) G over the balls in contact
    (``ball_damping`` c [N s/m] per ball). The springs are nonlinear Hertz balls of constant
    ``k_h`` that may lose contact, or, where ``ball_stiffness`` gives one value per ball of a
    row (used for both rows), linear springs, always in contact, for which the preload plays no
    part. Outputs: q, dq/dt and each row's total normal ball load (with linear springs, its
    change from rest) [N]."""

    inputs = LOADS + ("u_feed", "preload")
    states = (*DOF, *(f"{n}_dot" for n in DOF), "ball_shift")

    def __init__(self, body: CarriageBody, per_row: int, pitch: float, *, k_h=None,
                 ball_stiffness=(), ball_damping: float = 0.0, static_load=(0.0,) * 5):
        self.body, self.per_row, self.pitch = body, per_row, pitch
        self.static_load = np.asarray(checks.finite("static_load", static_load), dtype=float)
        ball_positions(per_row, pitch)  # checks per_row and pitch
        k = np.asarray(ball_stiffness, dtype=float)
        if k.size:
            checks.positive("ball_stiffness", k)
            if k.size != per_row:
                raise ValueError(f"ball_stiffness needs {per_row} values (per_row), got {k.size}")
        elif k_h is None:
            raise ValueError("give either ball_stiffness or the Hertz constant")
        self.linear = np.concatenate([k, k])  # empty: Hertz balls
        self.k_h = 0.0 if k_h is None else checks.positive("k_h", k_h)
        self.damping = checks.non_negative("ball_damping", ball_damping)
        self.mass = np.diag(body.mass_matrix())

    def balls(self, shift: float, preload: float):
        """(directions, loads(q), stiffness(q), each ball's load at rest [N]) of the balls at
        the shift [m] and preload [N] (linear springs: their change from rest)."""
        positions = ball_positions(self.per_row, self.pitch, shift)
        if self.linear.size:
            g = contact_directions(self.body, positions)
            loads, stiffness = lambda q: self.linear * approach_change(g, q), lambda q: self.linear
            rest = np.zeros_like(self.linear)
        else:
            hertz = HertzBalls(self.body, positions, self.k_h, preload)
            g, loads, stiffness = hertz.directions, hertz.loads, hertz.ball_stiffness
            rest = hertz.rest_loads
        return g, loads, stiffness, rest

    def state_scales(self):
        return (1e-6,) * 5 + (1e-3,) * 5 + (self.pitch,)

    def load(self, inputs) -> np.ndarray:
        """The generalized load F + F_0 of the inputs."""
        return np.array([inputs[name] for name in LOADS], dtype=float) + self.static_load

    def initial_state(self, t, inputs):
        """Static equilibrium under the load at t, at rest, balls unshifted."""
        q = balanced(self.body, *self.balls(0.0, inputs["preload"]), self.load(inputs))
        return (*q, *np.zeros(5), 0.0)

    def derivatives(self, t, state, inputs):
        y = np.asarray(state, dtype=float)
        q, rate = y[:5], y[5:10]
        g, loads, _, rest = self.balls(y[10], inputs["preload"])
        forces = loads(q)
        in_contact = np.where(self.linear.size > 0, True, forces > 0.0)  # linear: always
        restoring = -generalized(g, forces - rest)
        damping = self.damping * generalized(g, in_contact * approach_change(g, rate))
        acceleration = (self.load(inputs) + restoring - damping) / self.mass
        return (*rate, *acceleration, 0.5 * inputs["u_feed"])

    def outputs(self, t, state, inputs, wanted=None):
        y = np.asarray(state, dtype=float)
        loads = self.balls(y[10], inputs["preload"])[1]
        q_loads = loads(y[:5])
        out = {name: float(value) for name, value in zip(self.states[:10], y[:10])}
        out["row_load_1"] = float(np.sum(q_loads[:self.per_row]))
        out["row_load_2"] = float(np.sum(q_loads[self.per_row:]))
        return out

    def highest_frequency(self, state, preload: float) -> float:
        """Highest natural frequency [Hz] of the carriage linearised at the state (for the
        integrator's substeps: the balls stiffen under load and as the preload rises)."""
        y = np.asarray(state, dtype=float)
        g, _, stiffness, _ = self.balls(y[10], preload)
        values = eigh(stiffness_matrix(g, stiffness(y[:5])), np.diag(self.mass), eigvals_only=True)
        return float(np.sqrt(max(values[-1], 0.0)) / (2 * np.pi))


def from_parameters(mass, inertia_x, inertia_y, inertia_z, contact_angle, d, e, balls_per_row,
                    pitch, ball_diameter, conformity, ball_stiffness, ball_damping,
                    static_F_y, static_F_z, static_M_x, static_M_y, static_M_z) -> BallCarriageModel:
    """The validated model of the BallCarriage5DOF FMU's parameters (fmus/README.md):
    ``ball_stiffness`` a space-separated list of per-row values [N/m] for linear springs, or
    empty for the Hertz balls of ``ball_diameter`` and ``conformity`` (their preload is an
    input); the static_* loads are added to the load inputs."""
    body = CarriageBody(mass, (inertia_x, inertia_y, inertia_z), contact_angle, d, e)
    static = (static_F_y, static_F_z, static_M_x, static_M_y, static_M_z)
    try:
        values = [float(v) for v in str(ball_stiffness).split()]
    except ValueError:
        raise ValueError(f"ball_stiffness must be numbers separated by spaces, got "
                         f"{ball_stiffness!r}") from None
    k_h = hertz_point.ball_constant(hertz_point.BallGroove(ball_diameter, conformity))
    return BallCarriageModel(body, balls_per_row, pitch, k_h=k_h, ball_stiffness=values,
                             ball_damping=ball_damping, static_load=static)
