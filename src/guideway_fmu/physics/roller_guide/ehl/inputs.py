"""Inputs of the mixed-EHL line contact: geometry, lubricant laws and surface (SI units).

Hamrock's dimensionless groups: W = w' / (E' R), U = mu0 u_m / (E' R), G = alpha E', with w'
the load per unit length, u_m = (u1 + u2) / 2 the mean (entrainment) velocity and E' the
reduced modulus 2 / E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Soleimanian et al. 2020, Table 3: E' = 2e11 Pa).
Hertz scales: half-width b = R sqrt(8 W / pi), peak pressure p_H = E' sqrt(W / (2 pi)).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ... import checks
from ...papers import soleimanian2020 as paper
from .. import greenwood_tripp as gt
from . import flow_factors

# Roelands (Soleimanian et al. 2020, eq. 20): mu = mu0 exp{(ln mu0 + 9.67) [(1 + p / ROELANDS_PRESSURE)^Z - 1]}
ROELANDS_PRESSURE = 1.0 / 5.1e-9  # Pa
ROELANDS_LN_VISCOSITY = 9.67  # -ln(6.31e-5 Pa s), mu0 in Pa s
# Dowson-Higginson (eq. 19): rho / rho0 = 1 + A p / (1 + B p), p in Pa
DH_A = 0.6e-9  # 1/Pa
DH_B = 1.7e-9  # 1/Pa


def roelands_exponent(viscosity: float, pressure_viscosity: float) -> float:
    """Z = alpha / (5.1e-9 (ln mu0 + 9.67)) [-]: Roelands' d ln(mu)/dp is then alpha at p = 0."""
    return pressure_viscosity * ROELANDS_PRESSURE / (math.log(viscosity) + ROELANDS_LN_VISCOSITY)


def lubricant_state(p, viscosity: float, pressure_viscosity: float):
    """(mu / mu0, d ln(mu) / dp [1/Pa], rho / rho0, d(rho / rho0) / dp [1/Pa]) at pressure p [Pa].

    Roelands viscosity (eq. 20) and Dowson-Higginson density (eq. 19). The paper prints eq. 19
    as 1 + 0.6 p / (1 + 1.7 p), which holds for p in GPa; in Pa the coefficients are 0.6e-9 and
    1.7e-9. Eq. 20 is garbled in the paper's text; the consistent Roelands form is used.
    For p < 0, which only Newton iterates reach, both laws continue along their tangent at p = 0
    (ln mu linear, rho linear) so that the discrete equations stay continuously differentiable.
    """
    p = np.asarray(p, dtype=float)
    pos, neg = np.maximum(p, 0.0), np.minimum(p, 0.0)
    s = math.log(viscosity) + ROELANDS_LN_VISCOSITY
    z = roelands_exponent(viscosity, pressure_viscosity)
    base = 1.0 + pos / ROELANDS_PRESSURE
    ln_mu = s * (base**z - 1.0) + pressure_viscosity * neg
    dln_mu = pressure_viscosity * base ** (z - 1.0)
    den = 1.0 + DH_B * pos
    rho = 1.0 + DH_A * pos / den + DH_A * neg
    return np.exp(ln_mu), dln_mu, rho, DH_A / den**2


def pan_hamrock(W, U, G):
    """(H_c, H_min) = (h_c / R, h_min / R) of Pan & Hamrock's smooth line-contact fit.

    H_min = 1.714 W^-0.128 U^0.694 G^0.568, H_c = 2.922 W^-0.166 U^0.692 G^0.470
    (Pan and Hamrock 1989, fitted over W 2e-5..3e-4, U 1e-12..1e-10, G 3500..5000).
    """
    return (2.922 * W**-0.166 * U**0.692 * G**0.470, 1.714 * W**-0.128 * U**0.694 * G**0.568)


def martin(W, U):
    """H_min = h_min / R = 4.9 U / W of a rigid cylinder in an isoviscous fluid (Martin 1916)."""
    return 4.9 * U / W


@dataclass(frozen=True)
class LineContactEHL:
    """One roller-raceway line contact; defaults from Soleimanian et al. (2020) Tables 2-4.

    ``roughness`` = 0 gives smooth surfaces; otherwise the Greenwood-Tripp asperity pressure of
    :mod:`..greenwood_tripp` acts with the Table 4 asperity density and radius.
    ``sliding_velocity`` u_s = u1 - u2 only enters the friction (eq. 29), not the film.
    ``average_flow`` (rough surfaces only) solves Patir and Cheng's average Reynolds equation
    (:mod:`.flow_factors`, roughness orientation ``peklenik``) instead of eq. 18: the fluid
    fills only the mean gap between the rough surfaces, and ridges along the motion
    (``peklenik`` > 1) let the pressure drive more flow, so the film falls with roughness.
    """

    load: float  # w', load per unit length [N/m]
    radius: float  # R, reduced radius [m]
    entrainment_velocity: float  # u_m = (u1 + u2) / 2 [m/s]
    e_reduced: float = paper.E_REDUCED  # E' [Pa]
    viscosity: float = paper.VISCOSITY  # mu0 at ambient pressure [Pa s]
    pressure_viscosity: float = paper.PRESSURE_VISCOSITY  # alpha [1/Pa]
    sliding_velocity: float = 0.0  # u_s [m/s]
    roughness: float = 0.0  # sigma, composite RMS [m]
    asperity_density: float = paper.ASPERITY_DENSITY  # n [1/m^2]
    asperity_radius: float = paper.ASPERITY_RADIUS  # beta [m]
    limiting_shear_stress: float = paper.LIMITING_SHEAR_STRESS  # tau_l0 [Pa]
    limiting_shear_slope: float = paper.LIMITING_SHEAR_SLOPE  # beta_m [-]
    average_flow: bool = False  # Patir-Cheng flow factors (True) or Soleimanian et al. (2020) eq. 18 (False)
    peklenik: float = 1.0  # gamma of the average flow model: 1 isotropic, 9 ground along motion

    @classmethod
    def from_dimensionless(cls, W: float, U: float, G: float, *,
                           radius: float = paper.ROLLER_RADIUS,
                           e_reduced: float = paper.E_REDUCED,
                           viscosity: float = paper.VISCOSITY, **fields):
        """The contact with Hamrock's W, U, G at the given R [m], E' [Pa] and mu0 [Pa s].

        R, E' and mu0 do not change a smooth solution's W, U, G scaling, except through the
        Roelands law (which needs mu0 and p in Pa) and, for rough surfaces, sigma / R.
        """
        checks.positive("W", W)
        checks.non_negative("U", U)
        checks.non_negative("G", G)
        checks.positive("radius", radius)
        checks.positive("e_reduced", e_reduced)
        checks.positive("viscosity", viscosity)
        er = e_reduced * radius
        return cls(load=W * er, radius=radius, entrainment_velocity=U * er / viscosity,
                   e_reduced=e_reduced, viscosity=viscosity,
                   pressure_viscosity=G / e_reduced, **fields)

    def validate(self) -> None:
        """Raise ValueError naming the first invalid field."""
        checks.check_fields(self, {
            "load": checks.positive, "radius": checks.positive,
            "entrainment_velocity": checks.non_negative, "e_reduced": checks.positive,
            "pressure_viscosity": checks.non_negative, "sliding_velocity": checks.finite,
            "roughness": checks.non_negative, "asperity_density": checks.positive,
            "asperity_radius": checks.positive, "limiting_shear_stress": checks.non_negative,
            "limiting_shear_slope": checks.non_negative})
        if not isinstance(self.average_flow, bool):
            raise ValueError(f"LineContactEHL.average_flow must be True or False, "
                             f"got {self.average_flow!r}")
        flow_factors.check_peklenik("LineContactEHL.peklenik", self.peklenik)
        # Roelands needs ln(mu0) + 9.67 > 0.
        checks.in_range("LineContactEHL.viscosity", self.viscosity,
                        math.exp(-ROELANDS_LN_VISCOSITY), math.inf)

    @property
    def W(self) -> float:
        return self.load / (self.e_reduced * self.radius)

    @property
    def U(self) -> float:
        return self.viscosity * self.entrainment_velocity / (self.e_reduced * self.radius)

    @property
    def G(self) -> float:
        return self.pressure_viscosity * self.e_reduced

    @property
    def half_width(self) -> float:
        """Hertz half-width b [m]."""
        return self.radius * math.sqrt(8.0 * self.W / math.pi)

    @property
    def hertz_pressure(self) -> float:
        """Hertz peak pressure p_H [Pa]."""
        return self.e_reduced * math.sqrt(self.W / (2.0 * math.pi))

    def surface(self) -> gt.Surface | None:
        """The Greenwood-Tripp surface, None if smooth.

        The asperity law uses E* = E' / 2 (1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2), not E':
        Greenwood and Tripp build it from Hertz's sphere-on-flat asperity contact
        P = 4/3 E* beta^0.5 delta^1.5, whose modulus is E*. Soleimanian et al. (2020) (eq. 16) writes E', as
        much of the mixed-EHL literature does; that doubles the asperity pressure.
        """
        if self.roughness == 0.0:
            return None
        return gt.Surface(asperity_density=self.asperity_density,
                          asperity_radius=self.asperity_radius, roughness=self.roughness,
                          e_reduced=0.5 * self.e_reduced)

    def film_estimate(self) -> float:
        """h_c / R from Pan-Hamrock or, if larger (light load, low G), Martin's rigid film."""
        return max(pan_hamrock(self.W, self.U, self.G)[0], martin(self.W, self.U))
