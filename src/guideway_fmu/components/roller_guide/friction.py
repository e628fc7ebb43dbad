"""Friction FMUs of the four-row roller guideway: FrictionMixedEHL and FrictionCoulomb."""
from __future__ import annotations

from ...physics.roller_guide import greenwood_tripp
from ...physics.roller_guide import friction
from ...physics.papers import soleimanian2020
from ..base import GuidewaySlave


class _Friction(GuidewaySlave):
    """Shared interface: per-roller loads and feed velocity in, friction on the moving body out."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("rollers_per_groove", soleimanian2020.ROLLERS_PER_GROOVE, None,
                       "rollers N in each of the 4 grooves")
        self.parameter("velocity_tolerance", 1e-4, "m/s",
                       "velocity scale of the regularised sign, tanh(u / v); 0 gives sign(u)")
        self.input("F_upper", 0.0, "N", "load of one roller in an upper groove (>= 0)", True)
        self.input("F_lower", 0.0, "N", "load of one roller in a lower groove (>= 0)", True)
        self.input("u", 0.0, "m/s", "feed velocity of the moving body")


class FrictionMixedEHL(_Friction):
    """Greenwood-Tripp boundary friction plus viscous shear of the film (Soleimanian et al. 2020, eqs. 24-31).

    F_friction acts on the moving body, opposite to u. Algebraic, no state.
    """

    description = __doc__.splitlines()[0]
    _PARTS = ("F_upper", "F_lower", "h_upper", "h_lower", "u")

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        s, p = greenwood_tripp.Surface(), friction.MixedFrictionParams()
        self.parameter("asperity_density", s.asperity_density, "1/m2", "asperity density n")
        self.parameter("asperity_radius", s.asperity_radius, "m", "asperity tip radius beta")
        self.parameter("roughness", s.roughness, "m", "composite RMS roughness sigma")
        self.parameter("e_reduced", s.e_reduced, "Pa", "reduced modulus E'")
        self.parameter("roller_radius", p.roller_radius, "m", "roller radius R")
        self.parameter("roller_length", p.roller_length, "m", "roller length l")
        self.parameter("viscosity", p.viscosity, "Pa.s", "lubricant viscosity mu0")
        self.parameter("limiting_shear_stress", p.limiting_shear_stress, "Pa", "tau_l0 of eq. 28")
        self.parameter("limiting_shear_slope", p.limiting_shear_slope, "1", "beta_m of eq. 28")
        self.input("h_upper", 0.0, "m", "film thickness of an upper roller contact (>= 0)", True)
        self.input("h_lower", 0.0, "m", "film thickness of a lower roller contact (>= 0)", True)
        self.output("F_friction", "N", "friction force on the moving body (boundary + viscous)", self._PARTS)
        self.output("F_boundary", "N", "boundary (asperity) part of F_friction", self._PARTS)
        self.output("F_viscous", "N", "viscous (film shear) part of F_friction", self._PARTS)

    @classmethod
    def continuous_model(cls, parameters):
        return friction.mixed_from_parameters(**parameters)


class FrictionCoulomb(_Friction):
    """Coulomb friction mu * (total roller load) opposing the feed velocity. Algebraic, no state."""

    description = __doc__.splitlines()[0]

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.parameter("coefficient", friction.CoulombParams().coefficient, "1",
                       "friction coefficient mu")
        self.output("F_friction", "N", "friction force on the moving body",
                    ("F_upper", "F_lower", "u"))

    @classmethod
    def continuous_model(cls, parameters):
        return friction.coulomb_from_parameters(**parameters)
