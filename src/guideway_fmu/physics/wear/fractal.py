"""Fractal rough surfaces and their contact (Zhang, Wang and Jiang, fractal-creep wear of linear
ball guides, eqs. 38-53; after Majumdar and Tien 1990, Majumdar and Bhushan 1991, Yan and
Komvopoulos 1998), SI units.

* **Profile** (eq. 38): the Weierstrass-Mandelbrot function
  z(x) = G^(D'-1) sum_n gamma^((D'-2) n) cos(2 pi gamma^n x) of profile dimension 1 < D' < 2 and
  scale G [m], frequencies gamma^n [1/m] from the lowest one up; gamma = 1.5 as in the paper.
* **Structure function** (eq. 39): E(tau) = <(z(x + tau) - z(x))^2> over x. For the W-M profile
  E(tau) = sum_n G^(2(D'-1)) gamma^(2(D'-2)n) (1 - cos(2 pi gamma^n tau)), which with the sum
  taken as an integral over ln(omega) / ln(gamma) is E(tau) = C G^(2(D'-1)) tau^(4-2D'),
  C = (2 pi)^(4-2D') Gamma(2D'-3) sin((2D'-3) pi/2) / ((4-2D') ln gamma) (Majumdar and Tien 1990
  quote C without the (2 pi)^(4-2D'), which belongs to eq. 38's cos(2 pi gamma^n x)). A
  least-squares line through log E against log tau gives D' from its slope 4 - 2D' and G from
  its intercept (:func:`fit_structure_function`).
* **Contact** of a fractal surface (dimension D = D' + 1) with a rigid flat over a patch of
  nominal area A_alpha, the largest truncated asperity area A_L: asperities smaller than the
  critical area A_c (eq. 41) deform plastically at the hardness H, larger ones elastically. Eqs.
  42-44 give the elastic load F_e, the plastic load F_p and the real area S for A_L > A_c; for
  A_L <= A_c every asperity is plastic, S = (D-1)/(3-D) A_L and F = H S (the two meet at
  A_L = A_c). At D = 2.5 eq. 42's 1 - (A_c/A_L)^((5-2D)/2) over 5 - 2D takes its limit
  ln(A_L/A_c) / 2.
* **A_L** (eqs. 46-47): the lubricant carries the yield strength sigma_s on the patch's area
  not in contact and the asperities the rest of the mean pressure P: sigma_s (A_alpha - S) +
  F_e + F_p = P A_alpha. The paper takes the constants of eq. 47 from another reference; they
  follow from eqs. 42-44 by collecting the powers A_L, A_L^((4-D)/2), A_L^((D-1)/2):
  K_1 = -sigma_s (D-1)/(6-2D), K_2 = c_e G^(D-2) E*, K_3 = A_c^((3-D)/2) (D-1) (H/(3-D) -
  sigma_s/(6-2D)) - c_e G^(D-2) E* A_c^((5-2D)/2) and K = (P - sigma_s) A_alpha, with c_e the
  coefficient of eq. 42. Where P <= sigma_s the film carries the patch and A_L = 0; otherwise
  A_L is the smallest root, on the branch where the carried load grows with A_L, below the A_L
  at which the real area would exceed the patch.
* **Wear volume** (eqs. 49-53): a slip area S_s of such patches sheds
  Delta V = S_s/A_alpha (pi-2) 2^(3-D) G^(D-2) A_L^((D-1)/2) A_c^(3-D) (D-1) /
  ((3-D) pi^((7-D)/2)) (eq. 52) over the mean asperity size
  l_a = 2 (D-1) A_c^(1/2) / (sqrt(pi) (D-2)) (eq. 51), so V_0 = Delta V / l_a [m^2] per unit
  sliding distance (eq. 53).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import gamma as gamma_function

from .. import checks
from ..papers import zhang_wang_jiang as paper
from ..roots import bracketed_root


def wm_profile(x, dimension: float, scale: float, lowest: float, highest: float,
               gamma: float = paper.FREQUENCY_RATIO) -> np.ndarray:
    """z(x) [m] of eq. 38 at the positions x [m] for the profile dimension D' (1, 2), G [m],
    with frequencies gamma^n from ``lowest`` up to ``highest`` [1/m]."""
    checks.in_range("dimension", dimension, 1.0 + 1e-9, 2.0 - 1e-9)
    checks.positive("scale", scale)
    if not 0 < lowest < highest:
        raise ValueError(f"lowest and highest frequency must satisfy 0 < lowest < highest, got "
                         f"{lowest!r}, {highest!r}")
    x = np.asarray(x, dtype=float)
    first = np.ceil(np.log(lowest) / np.log(gamma))
    orders = np.arange(first, np.floor(np.log(highest) / np.log(gamma)) + 1)
    frequencies = gamma ** orders
    amplitudes = scale ** (dimension - 1) * frequencies ** (dimension - 2)
    return np.cos(2 * np.pi * np.outer(x, frequencies)) @ amplitudes


def structure_function(z, spacing: float, lags) -> np.ndarray:
    """E(tau) = <(z(x + tau) - z(x))^2> [m^2] (eq. 39) of the equally spaced profile z [m] at the
    lags given in samples (each >= 1 and shorter than the profile)."""
    z = checks.finite("profile", z)
    checks.positive("spacing", spacing)
    lags = np.asarray(lags, dtype=int)
    if z.ndim != 1 or lags.size == 0 or lags.min() < 1 or lags.max() >= z.size:
        raise ValueError(f"lags must lie in [1, {z.size - 1}] samples of a 1-D profile")
    return np.array([np.mean((z[k:] - z[:-k]) ** 2) for k in lags])


def wm_constant(dimension: float, gamma: float = paper.FREQUENCY_RATIO) -> float:
    """C of E(tau) = C G^(2(D'-1)) tau^(4-2D'); Gamma(e) sin(pi e/2) at e = 2D'-3 is written
    Gamma(1+e) (pi/2) sinc(e/2), finite through D' = 1.5."""
    e = 2 * dimension - 3
    return float((2 * np.pi) ** (4 - 2 * dimension) * gamma_function(1 + e) * np.pi / 2
                 * np.sinc(e / 2) / ((4 - 2 * dimension) * np.log(gamma)))


@dataclass(frozen=True)
class StructureFit:
    """D' and G [m] of a profile, the lags [m] and E(tau) [m^2] fitted, and the fit's r^2."""

    dimension: float
    scale: float
    lags: np.ndarray
    values: np.ndarray
    r_squared: float


def fit_structure_function(z, spacing: float, shortest: int = 1, longest: int | None = None,
                           points: int = 40, gamma: float = paper.FREQUENCY_RATIO) -> StructureFit:
    """D' and G of the profile z [m] sampled every ``spacing`` [m]: least squares on the log-log
    structure function over lags from ``shortest`` to ``longest`` samples (default a tenth of
    the profile), geometrically spaced."""
    z = checks.finite("profile", z)
    longest = longest or max(z.size // 10, shortest + 2)
    lags = np.unique(np.geomspace(shortest, longest, points).astype(int))
    if lags.size < 3:
        raise ValueError(f"the profile of {z.size} samples is too short for a structure-function "
                         f"fit: at least 3 distinct lags are needed")
    values = structure_function(z - z.mean(), spacing, lags)
    if np.any(values <= 0):
        raise ValueError("the profile is flat at some lag: its structure function has no slope")
    x, y = np.log(lags * spacing), np.log(values)
    slope, intercept = np.polyfit(x, y, 1)
    residual = y - (slope * x + intercept)
    r2 = 1 - np.sum(residual ** 2) / np.sum((y - y.mean()) ** 2)
    dimension = (4 - slope) / 2
    if not 1 < dimension < 2:
        raise ValueError(f"the profile's structure function has slope {slope:.3g}: D' = "
                         f"{dimension:.3g} lies outside (1, 2), not a fractal profile")
    scale = (np.exp(intercept) / wm_constant(dimension, gamma)) ** (1 / (2 * (dimension - 1)))
    return StructureFit(float(dimension), float(scale), lags * spacing, values, float(r2))


@dataclass(frozen=True)
class FractalSurface:
    """A fractal surface of dimension D (2, 3) and scale G [m] against a rigid flat: reduced
    modulus E* [Pa] (1/E* = sum (1 - nu^2)/E), yield strength sigma_s [Pa], hardness H [Pa]."""

    dimension: float
    scale: float
    e_star: float
    yield_strength: float
    hardness: float
    gamma: float = paper.FREQUENCY_RATIO
    patch_area: float = paper.PATCH_AREA

    def __post_init__(self):
        checks.in_range("fractal dimension D", self.dimension, 2.0 + 1e-6, 3.0 - 1e-6)
        for name in ("scale", "e_star", "yield_strength", "hardness", "patch_area"):
            checks.positive(name, getattr(self, name))
        if not self.gamma > 1:
            raise ValueError(f"gamma must be > 1, got {self.gamma!r}")
        if not self.hardness > self.yield_strength:
            raise ValueError(f"hardness {self.hardness!r} Pa must exceed the yield strength "
                             f"{self.yield_strength!r} Pa")

    @property
    def critical_area(self) -> float:
        """A_c [m^2] (eq. 41): asperities smaller than this deform plastically."""
        d, g = self.dimension, self.scale
        inner = (2 ** (11 - 2 * d) * g ** (2 * d - 4) * self.e_star * np.log(self.gamma)
                 / (9 * np.pi ** (4 - d) * self.hardness))
        return float(inner ** (1 / (d - 2)))

    def _elastic_coefficient(self) -> float:
        """c_e G^(D-2) E* of eq. 42 without the (5-2D) factor [Pa m^(D-2)]."""
        d = self.dimension
        return (2 ** ((11 - 2 * d) / 2) / (3 * np.pi ** ((4 - d) / 2)) * (d - 1)
                * np.sqrt(np.log(self.gamma)) * self.scale ** (d - 2) * self.e_star)

    def contact(self, largest):
        """(load [N], real area [m^2]) of the patch at the largest asperity area A_L [m^2]
        (a number or an array)."""
        d, a_c = self.dimension, self.critical_area
        a_l = np.asarray(largest, dtype=float)
        ratio = a_c / np.maximum(a_l, a_c)
        exponent = (5 - 2 * d) / 2
        shape = (-np.log(ratio) / 2 if abs(exponent) < 1e-9
                 else (1 - ratio ** exponent) / (5 - 2 * d))
        elastic = self._elastic_coefficient() * a_l ** ((4 - d) / 2) * shape
        plastic = (d - 1) * self.hardness / (3 - d) * ratio ** ((3 - d) / 2) * a_l
        area = (d - 1) / (6 - 2 * d) * (1 + ratio ** ((3 - d) / 2)) * a_l
        plastic_only = a_l <= a_c  # every asperity plastic: S = (D-1)/(3-D) A_L, F = H S
        area = np.where(plastic_only, (d - 1) / (3 - d) * a_l, area)
        load = np.where(plastic_only, self.hardness * area, elastic + plastic)
        return load[()], area[()]

    @property
    def full_contact(self) -> float:
        """A_L [m^2] at which the real area S reaches the patch's nominal area."""
        top = self.patch_area * max(1.0, (3 - self.dimension) / (self.dimension - 1))
        return bracketed_root(lambda a: self.contact(a)[1] - self.patch_area,
                              self.critical_area * 1e-12, top,
                              f"largest asperity area of full contact (patch {self.patch_area:.6g} "
                              f"m^2)", xtol=top * 1e-14, rtol=1e-12)

    def carried(self, largest):
        """Mean pressure [Pa] the patch carries at A_L [m^2]: sigma_s on the free area plus the
        asperities' load (eq. 46's left side over A_alpha)."""
        load, area = self.contact(largest)
        return (self.yield_strength * (self.patch_area - area) + load) / self.patch_area

    def largest_area(self, pressure: float) -> float:
        """A_L [m^2] under the mean pressure P [Pa] (eqs. 46-47); 0 where P <= sigma_s, and the
        full contact (S = A_alpha) where P exceeds what the asperities can bear."""
        p = float(checks.non_negative("pressure", pressure))
        if p <= self.yield_strength:
            return 0.0
        grid = np.geomspace(self.critical_area * 1e-12, self.full_contact, 400)
        excess = self.carried(grid) - p
        up = np.flatnonzero((excess[:-1] < 0) & (excess[1:] >= 0))
        if up.size == 0:
            return self.full_contact
        i = int(up[0])
        return bracketed_root(lambda a: self.carried(a) - p, grid[i], grid[i + 1],
                              f"largest asperity area under the mean pressure {p:.6g} Pa",
                              xtol=grid[i] * 1e-13, rtol=1e-12)

    def wear_per_length(self, slip_area: float, pressure: float) -> float:
        """V_0 [m^2]: volume worn per metre of sliding by the slip area S_s [m^2] under the mean
        pressure P [Pa] (eqs. 51-53); 0 where the film carries the load."""
        s_s = float(checks.non_negative("slip_area", slip_area))
        a_l = self.largest_area(pressure)
        if s_s == 0.0 or a_l == 0.0:
            return 0.0
        d, a_c = self.dimension, self.critical_area
        volume = (s_s / self.patch_area * (np.pi - 2) * 2 ** (3 - d) * self.scale ** (d - 2)
                  * a_l ** ((d - 1) / 2) * a_c ** (3 - d) * (d - 1)
                  / ((3 - d) * np.pi ** ((7 - d) / 2)))
        size = 2 * (d - 1) * np.sqrt(a_c) / (np.sqrt(np.pi) * (d - 2))
        return float(volume / size)
