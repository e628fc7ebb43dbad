"""Hertz point contact of a ball in a straight circular-arc groove (ball guides), SI units.

A ball of diameter D touches a groove that is straight along the rolling direction x and
concave across it with radius f D (conformity f > 1/2). The curvatures are 2/D in both
directions for the ball, 0 along x and -1/(f D) across for the groove, so (Harris and Kotzalas,
Rolling Bearing Analysis, ch. 6; Hamrock and Brewe 1983)

    curvature sum      S = 4/D - 1/(f D),      R = 1/S
    curvature difference F = 1/(4 f - 1)
    radius ratio       alpha_r = R_y / R_x = 2 f / (2 f - 1) >= 1 (R_x = D/2 along x)

The contact ellipse has its major semi-axis a across the groove and b along x; its ellipticity
kappa = a/b solves F = ((kappa^2 + 1) E(m) - 2 K(m)) / ((kappa^2 - 1) E(m)) with the complete
elliptic integrals K, E of parameter m = 1 - 1/kappa^2 (scipy.special). Then, with E' the
reduced modulus 2 / E' = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2,

    a = (6 kappa^2 E Q R / (pi E'))^(1/3),   b = (6 E Q R / (pi kappa E'))^(1/3)
    delta = K (9 / (2 E R) (Q / (pi kappa E'))^2)^(1/3)          (normal approach)

so Q = K_h delta^(3/2) (Wu et al. 2012, eq. 1) with K_h fixed by the geometry and materials,
and the normal stiffness dQ/d delta = 3/2 K_h delta^(1/2) (eq. 8). ``method="hamrock-brewe"``
takes Hamrock and Brewe's fits instead of the exact kappa, E and K: kappa = 1.0339
alpha_r^0.6360, E = 1.0003 + 0.5968 / alpha_r, K = 1.5277 + 0.6023 ln(alpha_r).

A ball between carriage and rail touches two grooves; :func:`ball_constant` puts two equal
contacts in series (their approaches add): K_h / 2^(3/2).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import ellipe, ellipk

from .. import checks
from ..papers import wu2012
from ..roots import bracketed_root

METHODS = ("exact", "hamrock-brewe")
STEEL = (wu2012.YOUNGS_MODULUS, wu2012.POISSON_RATIO)  # Young's modulus [Pa], Poisson's ratio [-]


@dataclass(frozen=True)
class BallGroove:
    """A ball of ``diameter`` [m] in a straight groove of radius ``conformity`` * diameter."""

    diameter: float
    conformity: float
    e_ball: float = STEEL[0]
    nu_ball: float = STEEL[1]
    e_groove: float = STEEL[0]
    nu_groove: float = STEEL[1]

    def __post_init__(self):
        checks.positive("diameter", self.diameter)
        if not (np.isfinite(self.conformity) and self.conformity > 0.5):
            raise ValueError(f"conformity must be > 0.5 (groove radius over ball diameter), "
                             f"got {self.conformity!r}")
        for name in ("e_ball", "e_groove"):
            checks.positive(name, getattr(self, name))
        for name in ("nu_ball", "nu_groove"):
            checks.in_range(name, getattr(self, name), 0.0, 0.5)

    @property
    def e_reduced(self) -> float:
        """E' [Pa]: 2 / E' = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2."""
        return 2.0 / ((1 - self.nu_ball**2) / self.e_ball + (1 - self.nu_groove**2) / self.e_groove)

    @property
    def curvature_sum(self) -> float:
        """S [1/m] = 4/D - 1/(f D)."""
        return (4.0 - 1.0 / self.conformity) / self.diameter

    @property
    def curvature_difference(self) -> float:
        """F [-] = 1/(4 f - 1)."""
        return 1.0 / (4.0 * self.conformity - 1.0)

    @property
    def radius_ratio(self) -> float:
        """alpha_r = R_y / R_x [-] = 2 f / (2 f - 1)."""
        return 2.0 * self.conformity / (2.0 * self.conformity - 1.0)


@dataclass(frozen=True)
class Ellipse:
    """Ellipticity kappa = a/b [-] and the complete elliptic integrals E, K of the contact."""

    kappa: float
    second_kind: float
    first_kind: float


def ellipse(contact: BallGroove, method: str = "exact") -> Ellipse:
    """The contact ellipse's kappa, E and K, exactly or by Hamrock and Brewe's fits."""
    if method == "hamrock-brewe":
        ratio = contact.radius_ratio
        return Ellipse(1.0339 * ratio**0.6360, 1.0003 + 0.5968 / ratio,
                       1.5277 + 0.6023 * np.log(ratio))
    if method != "exact":
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    target = contact.curvature_difference

    def mismatch(kappa):
        m = 1.0 - 1.0 / kappa**2
        e, k = ellipe(m), ellipk(m)
        return ((kappa**2 + 1.0) * e - 2.0 * k) / ((kappa**2 - 1.0) * e) - target

    kappa = bracketed_root(mismatch, 1.0 + 1e-9, 1e4,
                           f"ellipticity kappa of the contact of conformity {contact.conformity!r} "
                           f"(curvature difference {target:.6g})", xtol=1e-14, rtol=1e-14)
    m = 1.0 - 1.0 / kappa**2
    return Ellipse(kappa, float(ellipe(m)), float(ellipk(m)))


def semi_axes(contact: BallGroove, load, method: str = "exact") -> tuple[np.ndarray, np.ndarray]:
    """Semi-axes a (across the groove) and b (along x) [m] under the normal load [N] >= 0."""
    el = ellipse(contact, method)
    q = np.maximum(np.asarray(load, dtype=float), 0.0)
    scale = 6.0 * el.second_kind * q / (np.pi * contact.curvature_sum * contact.e_reduced)
    return np.cbrt(el.kappa**2 * scale), np.cbrt(scale / el.kappa)


def constant(contact: BallGroove, method: str = "exact") -> float:
    """K_h [N/m^1.5] of Q = K_h delta^1.5 for one contact."""
    el = ellipse(contact, method)
    r = 1.0 / contact.curvature_sum
    approach_1n = el.first_kind * np.cbrt(9.0 / (2.0 * el.second_kind * r)
                                          / (np.pi * el.kappa * contact.e_reduced) ** 2)
    return float(approach_1n**-1.5)


def ball_constant(contact: BallGroove, method: str = "exact") -> float:
    """K_h [N/m^1.5] of a ball between two equal grooves (carriage and rail) in series."""
    return constant(contact, method) / 2.0**1.5


def load(k_h: float, approach):
    """Normal load Q = K_h max(delta, 0)^1.5 [N] at the approach delta [m] (no tension)."""
    return k_h * np.maximum(np.asarray(approach, dtype=float), 0.0) ** 1.5


def approach(k_h: float, normal_load):
    """Approach delta = (Q / K_h)^(2/3) [m] under the load Q [N] >= 0."""
    return (np.maximum(np.asarray(normal_load, dtype=float), 0.0) / k_h) ** (2.0 / 3.0)


def stiffness(k_h: float, approach_):
    """Normal stiffness dQ/d delta = 1.5 K_h max(delta, 0)^0.5 [N/m] at the approach [m]."""
    return 1.5 * k_h * np.sqrt(np.maximum(np.asarray(approach_, dtype=float), 0.0))
