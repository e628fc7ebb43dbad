"""Greenwood-Tripp contact of two nominally flat rough surfaces, SI units.

Asperity heights are Gaussian with composite RMS roughness sigma; lambda = h / sigma is
the film ratio. Soleimanian et al. (2020), eqs. 16-17 (asperity pressure) and 24-26 (asperity load and area).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import gamma, pbdv

from .. import checks
from ..papers import soleimanian2020 as paper

# F_n(lambda) < exp(-lambda^2 / 2) underflows to 0 in double precision beyond lambda ~ 38.6;
# above this cut-off scipy's D_v would also return NaN, so the result is set to 0 directly.
_LAMBDA_UNDERFLOW = 40.0


def gt_function(n: float, lam):
    """Statistical function F_n(lambda) = 1/sqrt(2 pi) * int_lambda^inf (s - lambda)^n exp(-s^2/2) ds.

    Evaluated in closed form, F_n = Gamma(n+1)/sqrt(2 pi) * exp(-lambda^2/4) * D_-(n+1)(lambda),
    with D_v the parabolic cylinder function (scipy pbdv). Within 5e-9 relative of quadrature
    for lambda in [-5, 10]; 0 (not NaN) where it underflows (lambda > 40). Requires n > -1.
    lambda < 0 (mean planes overlapping) is valid mathematically down to lambda ~ -35,
    where D_v overflows; the asperity functions below never pass lambda < 0.
    """
    lam = np.asarray(lam, dtype=float)
    clipped = np.minimum(lam, _LAMBDA_UNDERFLOW)
    d, _ = pbdv(-(n + 1.0), clipped)
    value = gamma(n + 1.0) / np.sqrt(2.0 * np.pi) * np.exp(-0.25 * clipped**2) * d
    return np.where(lam > _LAMBDA_UNDERFLOW, 0.0, value)


def f52(lam):
    """F_5/2(lambda), the asperity-load function (exact)."""
    return gt_function(2.5, lam)


def f2(lam):
    """F_2(lambda), the asperity-area function (exact)."""
    return gt_function(2.0, lam)


def _fit(coefficients, lam):
    lam = np.asarray(lam, dtype=float)
    return np.where(lam <= 3.0, np.polyval(coefficients, lam), 0.0)


def f52_polynomial(lam):
    """Published fifth-order fit of F_5/2 (Soleimanian et al. 2020, eq. 17), 0 for lambda > 3.

    Kept only to reproduce and compare the published results. Within 0.01 of the exact
    function for lambda <= 2, but with these 3-digit coefficients it has a minimum at
    lambda ~ 1.91 and rises to 0.092 at lambda = 3 (exact: 1.7e-4) before dropping to 0;
    the 4-digit version of the fit (-0.0046, 0.0574, -0.2958, 0.7844, -1.0776, 0.6167)
    turns negative above lambda ~ 2.22. The project therefore uses :func:`f52`.
    """
    return _fit([-0.004, 0.057, -0.296, 0.784, -1.078, 0.617], lam)


def f2_polynomial(lam):
    """Published fifth-order fit of F_2 (Soleimanian et al. 2020, eq. 26), 0 for lambda > 3.

    Kept only to reproduce and compare the published results. Within 0.01 of the exact
    function for lambda <= 2, but with these 3-digit coefficients it is negative (a negative
    asperity area) for 1.90 < lambda <= 3; the 4-digit version (-0.0018, 0.0281, -0.1728,
    0.5258, -0.8043, 0.5) is negative above lambda ~ 2.27.
    The project therefore uses :func:`f2`.
    """
    return _fit([-0.002, 0.028, -0.173, 0.526, -0.804, 0.5], lam)


@dataclass(frozen=True)
class Surface:
    """Rough-surface parameters; defaults from Soleimanian et al. (2020) Table 3."""

    asperity_density: float = paper.ASPERITY_DENSITY  # n [1/m^2]
    asperity_radius: float = paper.ASPERITY_RADIUS  # beta [m]
    roughness: float = paper.ROUGHNESS  # sigma, composite RMS [m]
    e_reduced: float = paper.E_REDUCED  # E' [Pa]

    def validate(self) -> None:
        """Raise ValueError naming the first field that is not finite and > 0."""
        checks.check_fields(
            self,
            {
                "asperity_density": checks.positive,
                "asperity_radius": checks.positive,
                "roughness": checks.positive,
                "e_reduced": checks.positive,
            },
        )


def _film_ratio(h, surface: Surface):
    """lambda = h / sigma with h < 0 taken as 0 (full asperity contact, the Greenwood-Tripp limit)."""
    return np.maximum(np.asarray(h, dtype=float), 0.0) / surface.roughness


def asperity_pressure(h, surface: Surface):
    """Asperity pressure p_a [Pa] at film thickness h [m] (eq. 16).

    p_a = 16 sqrt(2)/15 * pi * (n beta sigma)^2 * sqrt(sigma / beta) * E' * F_5/2(h / sigma);
    h < 0 is treated as h = 0.
    """
    s = surface
    nbs = s.asperity_density * s.asperity_radius * s.roughness
    k = 16.0 * np.sqrt(2.0) / 15.0 * np.pi * nbs**2 * np.sqrt(s.roughness / s.asperity_radius)
    return k * s.e_reduced * f52(_film_ratio(h, s))


def asperity_load(h, area, surface: Surface):
    """Load carried by the asperities W_a = p_a A [N] over the apparent area A [m^2] (eq. 24)."""
    return asperity_pressure(h, surface) * np.asarray(area, dtype=float)


def asperity_area(h, area, surface: Surface):
    """Real asperity contact area A_a = pi^2 (n beta sigma)^2 A F_2(h / sigma) [m^2] (eq. 25).

    h [m] < 0 is treated as h = 0; A [m^2] is the apparent contact area.
    """
    s = surface
    nbs = s.asperity_density * s.asperity_radius * s.roughness
    return np.pi**2 * nbs**2 * np.asarray(area, dtype=float) * f2(_film_ratio(h, s))
