"""Creep of a ball rolling on its raceway under a tangential force: Carter's adhesion and
micro-slip areas, creep rates and the rolling friction (Zhang, Wang and Jiang, fractal-creep wear
of linear ball guides, eqs. 12-22 and 32-37), SI units.

The contact ellipse (physics/ball_guides/hertz_point.py) has the semi-axis a along the rolling direction
and b across it; the paper's notation, hertz_point's b and a. Under the normal load P_z and the
tangential forces P_x along and P_y across the rolling direction, with the sliding friction
coefficient mu:

* adhesion: a_e / a = lambda_a = sqrt(1 - P_x / (mu P_z)) (eq. 13), b_e / b = lambda_b =
  sqrt(1 - P_y / (mu P_z)) (eq. 14); the adhesion area pi a b lambda_a lambda_b (eqs. 32, 34)
  sits at the leading edge, the rest pi a b (1 - lambda_a lambda_b) slips (eq. 35);
* creep rates zeta_x = (2 a mu / D_b)(lambda_a - 1), zeta_y = (2 b mu / D_b)(lambda_b - 1)
  (eqs. 17, 18): the ball's surface lags the raceway's by |zeta| of the distance rolled;
* rolling friction mu_b = e / (R_b - delta / 2) with the rolling-resistance arm
  e = 3 tau (2 a) / 16 and tau the elastic hysteresis coefficient (eqs. 36-37; the paper takes
  tau = 3 x 0.3 for a slender ellipse), delta the ball's approach.

P_x = P_y = 0 gives full adhesion: no slip area and no creep. A tangential force reaching
mu P_z is full sliding, where Carter's creep no longer applies. The paper's eq. 22 (a mean
pressure of the slip area) is not used: it grows without bound as the adhesion area vanishes;
the wear model takes the Hertz mean pressure (eq. 21) instead (physics/wear/raceway_wear.py).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import checks
from ..papers import zhang_wang_jiang as paper


@dataclass(frozen=True)
class Creep:
    """Adhesion ratios lambda_a, lambda_b [-], creep rates zeta_x, zeta_y [-] and the adhesion
    and micro-slip areas [m^2] of one contact."""

    adhesion_along: float
    adhesion_across: float
    creep_along: float
    creep_across: float
    adhesion_area: float
    slip_area: float


def adhesion_ratio(name: str, tangential_ratio: float) -> float:
    """lambda = sqrt(1 - P_t / (mu P_z)) (eqs. 13, 14) of the ratio P_t / (mu P_z) in [0, 1)."""
    r = float(checks.finite(name, tangential_ratio))
    if not 0.0 <= r < 1.0:
        raise ValueError(f"{name} (tangential force over mu times the normal load) must lie in "
                         f"[0, 1), got {r!r}: at 1 the ball slides and creep no longer applies")
    return float(np.sqrt(1.0 - r))


def creep(along: float, across: float, diameter: float, friction: float,
          ratio_along: float, ratio_across: float = 0.0) -> Creep:
    """Carter's creep of a contact with semi-axes a (``along`` the rolling) and b (``across``)
    [m] on a ball of ``diameter`` D_b [m], friction mu [-], and the tangential forces over
    mu P_z along and across the rolling direction."""
    a, b = checks.non_negative("along", along), checks.non_negative("across", across)
    checks.positive("diameter", diameter)
    mu = checks.positive("friction", friction)
    la = adhesion_ratio("ratio_along", ratio_along)
    lb = adhesion_ratio("ratio_across", ratio_across)
    ellipse = np.pi * a * b
    return Creep(la, lb, float(2 * a * mu / diameter * (la - 1)),
                 float(2 * b * mu / diameter * (lb - 1)), float(ellipse * la * lb),
                 float(ellipse * (1 - la * lb)))


def rolling_friction(along: float, radius: float, approach: float,
                     hysteresis: float = paper.HYSTERESIS) -> float:
    """mu_b [-] (eqs. 36-37) of a ball of ``radius`` R_b [m] with the contact semi-axis a
    ``along`` the rolling [m] and the approach delta [m]."""
    a = checks.non_negative("along", along)
    r = checks.positive("radius", radius)
    delta = checks.non_negative("approach", approach)
    tau = checks.non_negative("hysteresis", hysteresis)
    if not delta < 2 * r:
        raise ValueError(f"approach {delta!r} m must stay below the ball diameter {2 * r!r} m")
    return float(3 * tau * 2 * a / 16 / (r - delta / 2))
