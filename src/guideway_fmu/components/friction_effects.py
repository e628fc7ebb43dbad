"""Friction FMUs that extend FrictionCoulomb by one effect each, with its interface.

Inputs F_upper, F_lower [N] (per-roller loads) and u [m/s], output F_friction [N] on the moving
body, parameters coefficient, rollers_per_groove and velocity_tolerance as FrictionCoulomb: the
Coulomb level is F_c = coefficient * 2 N (F_upper + F_lower). Effects that depend on the path
also take the feed position x [m]. The laws are in physics/friction_effects.py.

Path-dependent states (Dahl state z, running distance D) are kept at the last accepted step;
the output evaluates the law from that state to the current x, and ``doStep`` accepts it. In a
Gauss-Seidel loop where the feed steps first, the state therefore advances exactly by the
feed's displacement over each step.
"""
from __future__ import annotations

import numpy as np

from ..physics import checks, friction_effects
from .roller_friction import _Friction

_LOADS = ("F_upper", "F_lower", "u")


class _Extension(_Friction):
    """FrictionCoulomb's interface plus the position input where ``uses_position``."""

    uses_position = False
    role = "diagnosis"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("coefficient", 0.005, "1", "friction coefficient mu of the Coulomb level")
        if self.uses_position:
            self.input("x", 0.0, "m", "feed position of the moving body")
        depends = _LOADS + (("x",) if self.uses_position else ())
        self.output("F_friction", "N", "friction force on the moving body", depends)

    def total_load(self) -> float:
        """2 N (F_upper + F_lower) [N]: the load the coefficients multiply."""
        checks.positive_integer("rollers_per_groove", self.rollers_per_groove)
        return 2.0 * self.rollers_per_groove * (self.F_upper + self.F_lower)

    def coulomb_level(self) -> float:
        """F_c [N] from the current loads."""
        checks.non_negative("coefficient", self.coefficient)
        return self.coefficient * self.total_load()

    def build_model(self):
        checks.non_negative("velocity_tolerance", self.velocity_tolerance)
        return self.parameter_values()


class _RunningDistance(_Extension):
    """The running distance D [m] as a state: accumulated |dx| of the position input."""

    uses_position = True
    internal_state = ("distance", "x_last")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.distance, self.x_last = 0.0, 0.0

    def initialise(self):
        self.distance, self.x_last = 0.0, float(self.x)

    def distance_now(self) -> float:
        return self.distance + abs(self.x - self.x_last)

    def advance(self, t, h):
        self.distance, self.x_last = self.distance_now(), float(self.x)


class _FactorTable(_Extension):
    """A table of friction-level factors at equally spaced nodes from table_start to table_end."""

    table_of = "position"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("table_start", 0.0, "m", f"{self.table_of} of the first factor")
        self.parameter("table_end", 1.0, "m", f"{self.table_of} of the last factor (> table_start)")
        self.parameter("factors", "1 1", None,
                       f"friction-level factors at equally spaced {self.table_of}s from "
                       "table_start to table_end, space separated (at least 2)")

    def build_model(self):
        try:
            factors = np.array([float(v) for v in self.factors.split()])
        except ValueError:
            raise ValueError(f"parameter factors must be numbers separated by spaces, "
                             f"got {self.factors!r}") from None
        if factors.size < 2 or not np.all(np.isfinite(factors)):
            raise ValueError(f"parameter factors needs at least 2 finite numbers, got {self.factors!r}")
        checks.finite("table_start", self.table_start)
        if not self.table_end > self.table_start:
            raise ValueError(f"parameter table_end must be > table_start, got {self.table_end}")
        super().build_model()
        return factors


class FrictionStribeck(_Extension):
    """Stribeck + viscous friction (lubrication): the level falls from static to Coulomb with speed."""

    description = __doc__.splitlines()[0]

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("static_coefficient", 0.005, "1",
                       "friction coefficient at rest: static level F_s = static_coefficient * 2 N "
                       "(F_upper + F_lower)")
        self.parameter("stribeck_velocity", 0.01, "m/s", "Stribeck velocity v_s (> 0)")
        self.parameter("stribeck_exponent", 2.0, "1", "shape exponent d of exp(-(|u|/v_s)^d) (> 0)")
        self.parameter("viscous", 0.0, "N.s/m", "viscous coefficient c_v (unit for b = 1)")
        self.parameter("viscous_exponent", 1.0, "1", "exponent b of the viscous term c_v |u|^b (> 0)")

    def build_model(self):
        for name in ("stribeck_velocity", "stribeck_exponent", "viscous_exponent"):
            checks.positive(name, getattr(self, name))
        checks.non_negative("static_coefficient", self.static_coefficient)
        checks.finite("viscous", self.viscous)
        return super().build_model()

    def evaluate(self):
        force = friction_effects.stribeck_friction(
            self.u, self.coulomb_level(), self.static_coefficient * self.total_load(),
            self.stribeck_velocity, self.viscous, self.velocity_tolerance,
            self.stribeck_exponent, self.viscous_exponent)
        return {"F_friction": float(force)}


class FrictionDahl(_Extension):
    """Dahl pre-sliding friction, up to three elements in parallel; force builds up after reversals.

    A Maxwell-slip of Dahl elements: the shares left at 0 give one or two elements."""

    description = __doc__.splitlines()[0]
    uses_position = True
    internal_state = ("z", "x_last")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("presliding_distance", 1e-5, "m", "pre-sliding distance of element 1 (> 0)")
        self.parameter("second_distance", 1e-4, "m", "pre-sliding distance of element 2 (> 0)")
        self.parameter("second_share", 0.0, "1", "share of the Coulomb level in element 2, [0, 1]")
        self.parameter("third_distance", 1e-3, "m", "pre-sliding distance of element 3 (> 0)")
        self.parameter("third_share", 0.0, "1",
                       "share of the Coulomb level in element 3, [0, 1 - second_share]")
        self.parameter("z_start", 0.0, "1", "Dahl state z of all elements at the start, [-1, 1]")
        self.z, self.x_last = np.zeros(3), 0.0

    def build_model(self):
        checks.positive("presliding_distance", self.presliding_distance)
        checks.positive("second_distance", self.second_distance)
        checks.positive("third_distance", self.third_distance)
        checks.in_range("second_share", self.second_share, 0.0, 1.0)
        checks.in_range("third_share", self.third_share, 0.0, 1.0 - self.second_share)
        checks.in_range("z_start", self.z_start, -1.0, 1.0)
        super().build_model()
        return np.array([self.presliding_distance, self.second_distance, self.third_distance])

    def initialise(self):
        self.z, self.x_last = np.full(3, float(self.z_start)), float(self.x)

    def state_now(self) -> np.ndarray:
        return friction_effects.dahl_update(self.z, self.x - self.x_last, self.model())

    def advance(self, t, h):
        self.z, self.x_last = self.state_now(), float(self.x)

    def evaluate(self):
        share = np.array([1.0 - self.second_share - self.third_share, self.second_share,
                          self.third_share])
        force = friction_effects.dahl_friction(self.state_now(), self.coulomb_level() * share)
        return {"F_friction": float(np.sum(force))}


class FrictionPositionDependent(_FactorTable):
    """Coulomb friction whose level varies along the rail (a table of factors over position)."""

    description = __doc__.splitlines()[0]
    uses_position = True

    def evaluate(self):
        force = friction_effects.position_dependent_friction(
            self.u, self.x, self.coulomb_level(), self.table_start, self.table_end, self.model(),
            self.velocity_tolerance)
        return {"F_friction": float(force)}


class FrictionPreloadLoss(_RunningDistance):
    """Coulomb friction whose level drifts down with the running distance (preload loss, wear)."""

    description = __doc__.splitlines()[0]

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("loss", 0.0, "1", "fraction of the level finally lost (< 1; < 0: a gain)")
        self.parameter("wear_distance", 1.0, "m", "running distance of the loss (> 0)")

    def build_model(self):
        checks.in_range("loss", self.loss, -10.0, 1.0)
        checks.positive("wear_distance", self.wear_distance)
        return super().build_model()

    def evaluate(self):
        force = friction_effects.preload_loss_friction(self.u, self.distance_now(), self.coulomb_level(),
                                                    self.loss, self.wear_distance,
                                                    self.velocity_tolerance)
        return {"F_friction": float(force)}


class FrictionBallToBall(_RunningDistance, _FactorTable):
    """Ball-guide friction raised and varied by ball-to-ball sliding along the running distance."""

    description = __doc__.splitlines()[0]
    table_of = "running distance"

    def evaluate(self):
        force = friction_effects.ball_to_ball_friction(
            self.u, self.distance_now(), self.coulomb_level(), self.table_start, self.table_end,
            self.model(), self.velocity_tolerance)
        return {"F_friction": float(force)}
