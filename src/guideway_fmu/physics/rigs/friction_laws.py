"""Friction laws that extend Coulomb friction, each a plain function of the feed motion, SI units.

Every law returns the friction force ON the moving part (opposing its motion), like
physics/roller_guide/friction.py, and is written for numpy arrays over a whole record (the discrepancy
workflow fits them) and for one value at a time (the FMUs evaluate them per communication step).
``coulomb`` [N] is the Coulomb level, the friction force at steady sliding; s(u) is
:func:`..dynamics.regularised_sign`.

* Stribeck (lubrication): F = -(F_c + (F_s - F_c) exp(-(|u| / v_s)^d)) s(u) - c_v |u|^b sgn(u):
  from the static level F_s friction falls (or rises) to F_c as the film builds over the
  Stribeck velocity v_s (shape exponent d, 2 for Gaussian), and the viscous shear c_v |u|^b
  grows with speed (b = 1: Newtonian; b < 1: shear thinning).
* Dahl (pre-sliding hysteresis): each element gives F = -F_c z with dz/dx = (sgn(dx) - z) / delta
  along the path: after a reversal friction builds up over the pre-sliding distance delta
  instead of switching at once (delta = F_c / sigma_0 of Dahl's rest stiffness sigma_0); elements
  with different delta in parallel form a Maxwell-slip-like model. :func:`dahl_update` is the
  exact solution over one monotone displacement step.
* Position-dependent friction: the Coulomb level times a factor interpolated linearly in a table
  of equally spaced positions x (waviness, defects, recirculation).
* Preload loss: the Coulomb level falls with the running distance D (the accumulated |dx|),
  F_c (1 - loss g(D)): empirically g = 1 - exp(-D / wear_distance); or by wear
  (physics/wear/raceway_wear.py), the share ``loss`` of the level that the preload carries following the
  preload Q_0 ~ delta_0^n (n = 1.5 for Hertz balls, 10/9 for Palmgren's rollers) while the
  raceways wear its deformation delta_0 away at a steady rate, g = 1 - (1 - D / D_loss)_+^n
  with D_loss [m] (``wear_distance``) the running distance at which the preload is gone.
* Ball-to-ball contact (ball guides): neighbouring balls of the train slide on each other, which
  raises the friction level and makes it vary irregularly as the train's arrangement changes
  with the distance run; the level is F_c times a factor interpolated in a table over the
  running distance D, with nodes about a ball diameter apart.

The friction FMUs of the discrepancy workflow carry these laws on FrictionCoulomb's interface:
the model classes below take one FMU's parameters keyword for keyword; their Coulomb level is F_c = coefficient 2 N (F_upper + F_lower) [N] from the per-roller loads. Path states
evolve along the feed velocity u: the Dahl states by dz/dt = (u - |u| z) / delta, the running
distance by dD/dt = |u|. The FMUs advance them along the position input instead, exactly
(:meth:`DahlModel.update`, D + |dx|), which solves the same equations over a monotone step.
"""
from __future__ import annotations

from abc import abstractmethod

import numpy as np

from .. import checks
from ..dynamics import ContinuousModel
from ..dynamics import regularised_sign


def stribeck_friction(u, coulomb, static, stribeck_velocity, viscous, velocity_tolerance=0.0,
                      stribeck_exponent=2.0, viscous_exponent=1.0):
    """Stribeck + viscous friction force on the moving part [N] at feed velocity u [m/s].

    coulomb F_c and static F_s [N], stribeck_velocity v_s [m/s] > 0, viscous c_v
    [N (s/m)^b], stribeck_exponent d > 0, viscous_exponent b > 0.
    """
    u = np.asarray(u, dtype=float)
    speed = np.abs(u)
    level = coulomb + (static - coulomb) * np.exp(-(speed / stribeck_velocity) ** stribeck_exponent)
    return -level * regularised_sign(u, velocity_tolerance) - viscous * speed**viscous_exponent * np.sign(u)


def dahl_update(z, dx, presliding_distance):
    """Dahl state z [-] after a monotone displacement dx [m] from state z (exact solution).

    z relaxes towards sgn(dx) as exp(-|dx| / delta); dx = 0 leaves z unchanged.
    """
    dx = np.asarray(dx, dtype=float)
    target = np.sign(dx)
    return target + (z - target) * np.exp(-np.abs(dx) / presliding_distance)


def dahl_state(x, presliding_distances, z0=0.0):
    """Dahl state z [-] along the position record x [m] (samples), for each pre-sliding distance.

    ``presliding_distances`` [m] (scalar or 1-D array, all > 0); returns shape (len(x),) for a
    scalar, (len(x), len(distances)) otherwise. z[0] = z0 and z[k] = dahl_update(z[k-1],
    x[k] - x[k-1], delta), the same step the FMU takes between communication points, summed in
    closed form over each run of steps in one direction (a step dx = 0 leaves z as it is).
    """
    x = np.asarray(x, dtype=float)
    delta = np.atleast_1d(np.asarray(presliding_distances, dtype=float))
    dx = np.diff(x)
    direction = np.sign(dx)
    moved = np.flatnonzero(direction)
    z = np.empty((x.size, delta.size))
    z[0] = z0
    if moved.size == 0:
        z[1:] = z0
    else:  # a still step takes the direction before it (the first moving one at the start)
        direction = direction[moved[np.maximum(np.searchsorted(moved, np.arange(dx.size),
                                                               side="right") - 1, 0)]]
        starts = np.r_[0, np.flatnonzero(np.diff(direction)) + 1]
        for a, b in zip(starts, np.r_[starts[1:], dx.size]):
            travel = np.cumsum(np.abs(dx[a:b]))[:, None]
            z[a + 1:b + 1] = direction[a] + (z[a] - direction[a]) * np.exp(-travel / delta)
    return z[:, 0] if np.ndim(presliding_distances) == 0 else z


def dahl_friction(z, coulomb):
    """Dahl friction force on the moving part [N] for the state z [-]: -F_c z."""
    return -coulomb * np.asarray(z, dtype=float)


def table_factor(s, start, end, factors):
    """Factor [-] at s, interpolated linearly in ``factors`` given at equally spaced nodes from
    ``start`` to ``end`` (> start), held at the end values outside."""
    nodes = np.linspace(start, end, len(factors))
    return np.interp(np.asarray(s, dtype=float), nodes, factors)


def position_dependent_friction(u, x, coulomb, start, end, factors, velocity_tolerance=0.0):
    """Coulomb friction [N] whose level F_c * table_factor(x) varies along the rail, x [m]."""
    level = coulomb * table_factor(x, start, end, factors)
    return -level * regularised_sign(u, velocity_tolerance)


def running_distance(x):
    """Accumulated sliding distance D [m] along the position record x [m], D[0] = 0."""
    x = np.asarray(x, dtype=float)
    return np.concatenate(([0.0], np.cumsum(np.abs(np.diff(x)))))


PRELOAD_LAWS = ("exponential", "wear", "table")


def preload_loss_factor(distance, loss, wear_distance, law="exponential", exponent=1.5,
                        profile=(0.0, 1.0)):
    """Remaining friction level [-] after the running distance D [m], 1 - loss g(D): ``law``
    "exponential", g = 1 - exp(-D / wear_distance), loss [-] the final fraction lost; "wear",
    g = 1 - (1 - D / wear_distance)_+^exponent, loss the share the preload carries and
    wear_distance [m] > 0 where it is gone; "table", g interpolated in ``profile`` (rising
    from 0 to 1, :func:`monotone_profile`) at equally spaced distances from 0 to
    wear_distance, loss lost there: any monotone loss (running-in that levels off, wear that
    speeds up)."""
    d = np.asarray(distance, dtype=float)
    if law == "wear":
        return 1.0 - loss * (1.0 - np.maximum(1.0 - d / wear_distance, 0.0) ** exponent)
    if law == "table":
        return 1.0 - loss * table_factor(d, 0.0, wear_distance, profile)
    return 1.0 - loss * -np.expm1(-d / wear_distance)


def monotone_profile(text) -> np.ndarray:
    """The profile of a "table" preload loss: numbers separated by spaces (:func:`parse_factors`)
    that rise from 0 to 1 without falling back."""
    profile = parse_factors(text)
    if profile[0] != 0.0 or profile[-1] != 1.0 or np.any(np.diff(profile) < 0.0):
        raise ValueError(f"parameter profile must rise from 0 to 1 without falling back, "
                         f"got {text!r}")
    return profile


def preload_loss_friction(u, distance, coulomb, loss, wear_distance, velocity_tolerance=0.0,
                          law="exponential", exponent=1.5, profile=(0.0, 1.0)):
    """Coulomb friction [N] with the level drifting down over the running distance D [m]
    (:func:`preload_loss_factor`)."""
    level = coulomb * preload_loss_factor(distance, loss, wear_distance, law, exponent, profile)
    return -level * regularised_sign(u, velocity_tolerance)


def ball_to_ball_friction(u, distance, coulomb, start, end, factors, velocity_tolerance=0.0):
    """Coulomb friction [N] of a ball guide whose level F_c * table_factor(D) varies with the
    running distance D [m] (ball-to-ball sliding; table nodes about a ball diameter apart)."""
    level = coulomb * table_factor(distance, start, end, factors)
    return -level * regularised_sign(u, velocity_tolerance)


def parse_factors(text) -> np.ndarray:
    """The factors of a table parameter: numbers separated by spaces (at least 2, finite)."""
    try:
        factors = np.array([float(v) for v in str(text).split()])
    except ValueError:
        raise ValueError(f"parameter factors must be numbers separated by spaces, "
                         f"got {text!r}") from None
    if factors.size < 2 or not np.all(np.isfinite(factors)):
        raise ValueError(f"parameter factors needs at least 2 finite numbers, got {text!r}")
    return factors


class EffectModel(ContinuousModel):
    """A friction effect on FrictionCoulomb's interface: inputs F_upper, F_lower [N] (per
    roller), u [m/s]; output F_friction [N]. Subclasses give :meth:`force`."""

    inputs = ("F_upper", "F_lower", "u")

    def __init__(self, coefficient, rollers_per_groove, velocity_tolerance):
        self.coefficient = checks.non_negative("coefficient", coefficient)
        self.rollers = checks.positive_integer("rollers_per_groove", rollers_per_groove)
        self.velocity_tolerance = checks.non_negative("velocity_tolerance", velocity_tolerance)

    def total_load(self, inputs) -> float:
        """2 N (F_upper + F_lower) [N]: the load the coefficients multiply."""
        return 2.0 * self.rollers * (inputs["F_upper"] + inputs["F_lower"])

    @abstractmethod
    def force(self, state, inputs) -> float:
        """F_friction [N] at the state and inputs."""

    def outputs(self, t, state, inputs, wanted=None):
        return {"F_friction": float(self.force(state, inputs))}


class StribeckModel(EffectModel):
    """:func:`stribeck_friction`, static level static_coefficient 2 N (F_upper + F_lower)."""

    def __init__(self, static_coefficient, stribeck_velocity, stribeck_exponent, viscous,
                 viscous_exponent, **coulomb):
        for name, value in (("stribeck_velocity", stribeck_velocity),
                            ("stribeck_exponent", stribeck_exponent),
                            ("viscous_exponent", viscous_exponent)):
            checks.positive(name, value)
        self.static_coefficient = checks.non_negative("static_coefficient", static_coefficient)
        self.shape = (stribeck_velocity, checks.finite("viscous", viscous), stribeck_exponent,
                      viscous_exponent)
        super().__init__(**coulomb)

    def force(self, state, inputs):
        load = self.total_load(inputs)
        v_s, c_v, d, b = self.shape
        return stribeck_friction(inputs["u"], self.coefficient * load,
                                 self.static_coefficient * load, v_s, c_v,
                                 self.velocity_tolerance, d, b)


class DahlModel(EffectModel):
    """Three Dahl elements in parallel (:func:`dahl_friction`), shares of the Coulomb level
    1 - s_2 - s_3, s_2, s_3; states z_1..z_3 [-], dz/dt = (u - |u| z) / delta."""

    states = ("z_1", "z_2", "z_3")

    def __init__(self, presliding_distance, second_distance, third_distance, second_share,
                 third_share, z_start, **coulomb):
        self.distances = np.array([checks.positive("presliding_distance", presliding_distance),
                                   checks.positive("second_distance", second_distance),
                                   checks.positive("third_distance", third_distance)])
        checks.in_range("second_share", second_share, 0.0, 1.0)
        checks.in_range("third_share", third_share, 0.0, 1.0 - second_share)
        self.shares = np.array([1.0 - second_share - third_share, second_share, third_share])
        self.z_start = checks.in_range("z_start", z_start, -1.0, 1.0)
        super().__init__(**coulomb)

    def state_scales(self):
        return (1.0, 1.0, 1.0)

    def initial_state(self, t, inputs):
        return (float(self.z_start),) * 3

    def derivatives(self, t, state, inputs):
        u = inputs["u"]
        return tuple((u - abs(u) * np.asarray(state)) / self.distances)

    def update(self, z, dx) -> np.ndarray:
        """The states after a monotone displacement dx [m] (:func:`dahl_update`)."""
        return dahl_update(z, dx, self.distances)

    def force(self, state, inputs):
        level = self.coefficient * self.total_load(inputs)
        return np.sum(dahl_friction(state, level * self.shares))


class _TableModel(EffectModel):
    """A level factor interpolated in a table over equally spaced nodes from start to end."""

    def __init__(self, table_start, table_end, factors, **coulomb):
        self.factors = parse_factors(factors)
        self.start = checks.finite("table_start", table_start)
        if not table_end > table_start:
            raise ValueError(f"parameter table_end must be > table_start, got {table_end}")
        self.end = table_end
        super().__init__(**coulomb)


class PositionTableModel(_TableModel):
    """:func:`position_dependent_friction` over the feed position input x [m]."""

    inputs = EffectModel.inputs + ("x",)

    def force(self, state, inputs):
        return position_dependent_friction(inputs["u"], inputs["x"],
                                           self.coefficient * self.total_load(inputs), self.start,
                                           self.end, self.factors, self.velocity_tolerance)


class _RunningDistanceModel(EffectModel):
    """The running distance D [m] as the state, dD/dt = |u|, D = 0 at the start."""

    states = ("distance",)
    distance_scale = 1.0  # m, set by subclasses

    def state_scales(self):
        return (self.distance_scale,)

    def initial_state(self, t, inputs):
        return (0.0,)

    def derivatives(self, t, state, inputs):
        return (abs(inputs["u"]),)


class PreloadLossModel(_RunningDistanceModel):
    """:func:`preload_loss_friction` over the running distance."""

    def __init__(self, loss, wear_distance, law="exponential", load_exponent=1.5,
                 profile="0 1", **coulomb):
        self.loss = checks.in_range("loss", loss, -10.0, 1.0)
        self.distance_scale = checks.positive("wear_distance", wear_distance)
        if law not in PRELOAD_LAWS:
            raise ValueError(f"law must be one of {PRELOAD_LAWS}, got {law!r}")
        self.law, self.exponent = law, float(checks.positive("load_exponent", load_exponent))
        self.profile = monotone_profile(profile)
        super().__init__(**coulomb)

    def force(self, state, inputs):
        return preload_loss_friction(inputs["u"], state[0],
                                     self.coefficient * self.total_load(inputs), self.loss,
                                     self.distance_scale, self.velocity_tolerance, self.law,
                                     self.exponent, self.profile)


class BallToBallModel(_RunningDistanceModel, _TableModel):
    """:func:`ball_to_ball_friction`: the table over the running distance."""

    def __init__(self, **parameters):
        _TableModel.__init__(self, **parameters)
        self.distance_scale = (self.end - self.start) / (self.factors.size - 1)

    def force(self, state, inputs):
        return ball_to_ball_friction(inputs["u"], state[0],
                                     self.coefficient * self.total_load(inputs), self.start,
                                     self.end, self.factors, self.velocity_tolerance)
