"""Hertz theory of a line contact (cylinder on a flat), SI units.

E' is the reduced modulus in Hamrock's convention, 2 / E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
as listed in Soleimanian et al. (2020) Table 3 (E' = 2e11 Pa).
"""
from __future__ import annotations

import numpy as np


def half_width(load: np.ndarray | float, length: float, radius: float, e_reduced: float):
    """Contact half-width b [m] = sqrt(8 w' R / (pi E')) for the load [N] over ``length`` [m]."""
    w = np.maximum(np.asarray(load, dtype=float), 0.0) / length
    return np.sqrt(8.0 * w * radius / (np.pi * e_reduced))


def contact_area(load, length: float, radius: float, e_reduced: float):
    """Apparent (nominal) contact area 2 b l [m^2]."""
    return 2.0 * half_width(load, length, radius, e_reduced) * length

