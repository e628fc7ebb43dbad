"""Patir-Cheng average flow model of a rough line contact (Patir and Cheng, J. Lubr. Technol.
100 (1978) 12-17), for Gaussian roughness of RMS sigma [m] and Peklenik number gamma.

The average Reynolds equation replaces the smooth film of Soleimanian et al. (2020) eq. 18 by
  d/dx(phi_x rho h^3 / (12 mu) dp/dx) = u_m d(rho h_T)/dx + d(rho h_T)/dt,
with h the separation of the mean planes [m], phi_x the pressure flow factor and h_T the mean
gap (fluid volume per area, asperity contacts excluded). The shear flow factor term is left
out: it is proportional to the sliding velocity times the difference of the two surfaces'
roughness, zero for equally rough surfaces. Both factors tend to the smooth film for h >> sigma.

gamma is the ratio of the roughness correlation lengths along and across the rolling direction:
1 isotropic, > 1 ridges along the motion (ground raceways and rollers), < 1 across it.
"""
from __future__ import annotations

import math

import numpy as np
from scipy import special

# Patir and Cheng (1978), Table 1: gamma -> (C, r, smallest h / sigma of the fit);
# phi_x = 1 - C exp(-r h/sigma) for gamma <= 1, 1 + C (h/sigma)^-r for gamma > 1.
PRESSURE_FLOW = {1 / 9: (1.48, 0.42, 1.0), 1 / 6: (1.38, 0.42, 1.0), 1 / 3: (1.18, 0.42, 0.75),
                 1.0: (0.90, 0.56, 0.5), 3.0: (0.225, 1.5, 0.5), 6.0: (0.520, 1.5, 0.5),
                 9.0: (0.870, 1.5, 0.5)}


def check_peklenik(name: str, gamma) -> float:
    """The table key equal to gamma (to 1e-6 relative); ValueError starting with ``name`` and
    listing the choices for anything else (including non-numbers)."""
    try:
        value = float(gamma)
    except (TypeError, ValueError):
        value = math.nan
    for key in PRESSURE_FLOW:
        if math.isclose(value, key, rel_tol=1e-6):
            return key
    raise ValueError(f"{name} must be one of Patir and Cheng's 1/9, 1/6, 1/3, 1, 3, 6, 9, "
                     f"got {gamma!r}")


def pressure_flow_factor(ratio, gamma: float = 1.0):
    """(phi_x, d phi_x / d(h/sigma)) at ratio = h / sigma [-]; below the fit's range
    (h / sigma < 0.5 to 1, see PRESSURE_FLOW) phi_x is held at its value on the bound."""
    key = check_peklenik("peklenik", gamma)
    c, r, lowest = PRESSURE_FLOW[key]
    ratio = np.asarray(ratio, dtype=float)
    held = np.maximum(ratio, lowest)
    if key <= 1.0:
        term = c * np.exp(-r * held)
        phi, slope = 1.0 - term, r * term
    else:
        term = c * held**-r
        phi, slope = 1.0 + term, -r * term / held
    return phi, np.where(ratio > lowest, slope, 0.0)


def mean_gap(ratio):
    """(h_T / sigma, d(h_T / sigma) / d(h / sigma)) at ratio = h / sigma [-].

    h_T = E[max(h + delta, 0)] over Gaussian delta ~ N(0, sigma^2):
    h_T / sigma = H Phi(H) + phi(H) with H = h / sigma, Phi and phi the standard normal
    distribution and density; its derivative is Phi(H)."""
    ratio = np.asarray(ratio, dtype=float)
    density = np.exp(-0.5 * ratio * ratio) / math.sqrt(2.0 * math.pi)
    cdf = special.ndtr(ratio)
    return ratio * cdf + density, cdf
