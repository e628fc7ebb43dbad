"""Friction FMUs that extend FrictionCoulomb by one effect each, with its interface.

Inputs F_upper, F_lower [N] (per-roller loads) and u [m/s], output F_friction [N] on the moving
body, parameters coefficient, rollers_per_groove and velocity_tolerance as FrictionCoulomb: the
Coulomb level is F_c = coefficient * 2 N (F_upper + F_lower). Effects that depend on the path
also take the feed position x [m]. The laws and their continuous-time models are in
physics/rigs/friction_laws.py.

Path-dependent states (Dahl state z, running distance D) are kept at the last accepted step;
the output evaluates the law from that state advanced to the current x, and ``doStep`` accepts
it. In a Gauss-Seidel loop where the feed steps first, the state therefore advances exactly by
the feed's displacement over each step.
"""
from __future__ import annotations

import numpy as np

from ...physics.rigs import friction_laws as effects
from ..roller_guide.friction import _Friction

_LOADS = ("F_upper", "F_lower", "u")


class _Extension(_Friction):
    """FrictionCoulomb's interface plus the position input where ``uses_position``."""

    uses_position = False
    role = "diagnosis"
    model_class = effects.EffectModel

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("coefficient", 0.005, "1", "friction coefficient mu of the Coulomb level")
        if self.uses_position:
            self.input("x", 0.0, "m", "feed position of the moving body")
        depends = _LOADS + (("x",) if self.uses_position else ())
        self.output("F_friction", "N", "friction force on the moving body", depends)

    @classmethod
    def continuous_model(cls, parameters):
        return cls.model_class(**parameters)

    def state_now(self) -> tuple:
        """The model's state at the current inputs (none for a stateless law)."""
        return ()

    def evaluate(self):
        return self.model().outputs(0.0, self.state_now(), self.model_inputs())


class _RunningDistance(_Extension):
    """The running distance D [m] as a state: accumulated |dx| of the position input."""

    uses_position = True
    internal_state = ("distance", "x_last")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.distance, self.x_last = 0.0, 0.0

    def initialise(self):
        self.distance, self.x_last = 0.0, float(self.x)

    def state_now(self):
        return (self.distance + abs(self.x - self.x_last),)

    def advance(self, t, h):
        (self.distance,), self.x_last = self.state_now(), float(self.x)


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


class FrictionStribeck(_Extension):
    """Stribeck + viscous friction (lubrication): the level falls from static to Coulomb with speed."""

    description = __doc__.splitlines()[0]
    model_class = effects.StribeckModel

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("static_coefficient", 0.005, "1",
                       "friction coefficient at rest: static level F_s = static_coefficient * 2 N "
                       "(F_upper + F_lower)")
        self.parameter("stribeck_velocity", 0.01, "m/s", "Stribeck velocity v_s (> 0)")
        self.parameter("stribeck_exponent", 2.0, "1", "shape exponent d of exp(-(|u|/v_s)^d) (> 0)")
        self.parameter("viscous", 0.0, "N.s/m", "viscous coefficient c_v (unit for b = 1)")
        self.parameter("viscous_exponent", 1.0, "1", "exponent b of the viscous term c_v |u|^b (> 0)")


class FrictionDahl(_Extension):
    """Dahl pre-sliding friction, up to three elements in parallel; force builds up after reversals.

    A Maxwell-slip of Dahl elements: the shares left at 0 give one or two elements."""

    description = __doc__.splitlines()[0]
    uses_position = True
    model_class = effects.DahlModel
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

    def initialise(self):
        self.z, self.x_last = np.array(self.model().initial_state(0.0, {})), float(self.x)

    def state_now(self) -> np.ndarray:
        return self.model().update(self.z, self.x - self.x_last)

    def advance(self, t, h):
        self.z, self.x_last = self.state_now(), float(self.x)


class FrictionPositionDependent(_FactorTable):
    """Coulomb friction whose level varies along the rail (a table of factors over position)."""

    description = __doc__.splitlines()[0]
    uses_position = True
    model_class = effects.PositionTableModel


class FrictionPreloadLoss(_RunningDistance):
    """Coulomb friction whose level drifts down with the running distance (preload loss, wear)."""

    description = __doc__.splitlines()[0]
    model_class = effects.PreloadLossModel

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("loss", 0.0, "1", "fraction of the level finally lost (< 1; < 0: a gain); "
                       "law wear: the share the preload carries")
        self.parameter("wear_distance", 1.0, "m", "running distance of the loss (> 0): the decay "
                       "distance, or for law wear the distance at which the preload is gone")
        self.parameter("law", "exponential", None, "exponential: the level decays as "
                       "exp(-D/wear_distance); wear: the preload's share follows "
                       "(1 - D/wear_distance)^load_exponent (raceways wearing steadily); table: "
                       "the loss follows profile up to wear_distance (any monotone loss)",
                       choices=effects.PRELOAD_LAWS)
        self.parameter("load_exponent", 1.5, "1", "law wear: n of the preload Q0 ~ delta0^n "
                       "(1.5 Hertz balls, 10/9 rollers)")
        self.parameter("profile", "0 1", None, "law table: the share of loss lost at equally "
                       "spaced distances from 0 to wear_distance, rising from 0 to 1, space "
                       "separated")


class FrictionBallToBall(_RunningDistance, _FactorTable):
    """Ball-guide friction raised and varied by ball-to-ball sliding along the running distance."""

    description = __doc__.splitlines()[0]
    table_of = "running distance"
    model_class = effects.BallToBallModel
