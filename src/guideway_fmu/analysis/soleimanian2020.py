"""Soleimanian et al. (2020) as published: the readings of what the paper leaves open, and the
numbers and trends it states about its own results, computed under each reading
(benchmarks/soleimanian2020_reproduced.py writes docs/soleimanian2020-reproduced.md).

The preload. Table 2 gives "preload 9200 N" (class V3) for four grooves of 20 rollers and does
not say over what it is shared. Three readings, each a parameter set of the shipped scenarios
(the contact FMUs share their ``preload`` F0 among all 4 N rollers):

* ``carriage``: 9200 N over the carriage's 80 rollers, Q0 = 115 N (V3 is 10 % of the
  carriage's dynamic load rating in the maker's catalogue);
* ``side``: 9200 N per pair of grooves on one side, Q0 = 230 N;
* ``groove``: 9200 N per groove, Q0 = 460 N: the FMUs' default (Guideway.preload = 36800 N,
  Carriage.mass = 3.302 kg), the reading that reproduces the most of the paper's statements.

The paper gives no mass of the moving rail; each reading's mass is the one, to the gram, that
puts the linearised unloaded natural frequency (lubricated, at the rig's feed speed amplitude)
at the published 6590 Hz, so that statement cannot tell the readings apart.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..numerics.spectrum import power_spectrum, spectrum
from ..physics import checks
from ..physics.papers import soleimanian2020 as paper
from ..physics.papers.soleimanian2020 import RIG_SPEED
from ..physics.roller_guide import carriage, four_rows, friction, greenwood_tripp
from ..physics.rigs.feed_motion import Oscillating
from ..physics.roller_guide.film import LineContact, film_law, steady_film
from ..physics.roller_guide.roller_law import approach_for_load

PAPER_NATURAL_FREQUENCY = paper.NATURAL_FREQUENCY  # Hz, the unloaded rig
SHARES = {"carriage": 1, "side": 2, "groove": 4}  # the 9200 N over 4 / n of the grooves
# Table 1: the surface and lubricant of the Hess and Soom comparison (Fig. 11)
HESS_SOOM = friction.MixedFrictionParams(
    surface=greenwood_tripp.Surface(asperity_density=paper.HESS_SOOM_ASPERITY_DENSITY,
                                    asperity_radius=paper.HESS_SOOM_ASPERITY_RADIUS,
                                    roughness=paper.ROUGHNESS, e_reduced=paper.E_REDUCED),
    limiting_shear_stress=paper.HESS_SOOM_LIMITING_SHEAR_STRESS,
    limiting_shear_slope=paper.LIMITING_SHEAR_SLOPE)


@dataclass(frozen=True)
class Reading:
    """One reading of the paper's preload: its name, F0 [N] of the contact FMUs (shared by all
    4 N rollers) and the rail mass [kg] that gives 6590 Hz with it."""

    name: str
    preload: float
    mass: float

    @property
    def preload_per_roller(self) -> float:
        return self.guideway().preload_per_roller

    def parameters(self) -> dict[str, dict]:
        """The scenario parameters of this reading (instance -> {parameter: value}): the
        contact's F0 and the carriage's mass."""
        return {"Contact": {"preload": self.preload}, "Carriage": {"mass": self.mass}}

    def guideway(self) -> four_rows.Guideway:
        return four_rows.Guideway(preload=self.preload)


def _stiffness(g: four_rows.Guideway) -> float:
    """Quasi-static stiffness [N/m] at rest, lubricated, at the rig's feed speed."""
    return float(four_rows.quasi_static_stiffness(g, 0.0, RIG_SPEED))


def natural_frequency(g: four_rows.Guideway, mass: float) -> float:
    """Linearised unloaded natural frequency [Hz] at the rig's feed speed."""
    return math.sqrt(_stiffness(g) / mass) / (2 * math.pi)


def readings() -> list[Reading]:
    """The three readings, the mass of each fitted to the published natural frequency (to the
    gram: a scenario states it in a few digits)."""
    omega = 2 * math.pi * PAPER_NATURAL_FREQUENCY
    preloads = {name: paper.PRELOAD * share for name, share in SHARES.items()}
    return [Reading(name, f0, round(_stiffness(four_rows.Guideway(preload=f0)) / omega**2, 3))
            for name, f0 in preloads.items()]


def film_to_solid_stiffness(g: four_rows.Guideway) -> float:
    """Ratio of a roller's film stiffness dF/dh to its solids' dF/d delta at rest, unloaded, at
    the rig's feed speed: (F / (m h)) / ((10/9) F / delta) = 9 delta / (10 m h), from the steady
    film h = C F^-m in series with Palmgren's contact."""
    f_u, _, h_u, _ = four_rows.quasi_static_state(g, 0.0, RIG_SPEED)
    delta = float(approach_for_load(f_u, g.k))
    _, m = film_law(g.contact, RIG_SPEED)
    return 9.0 * delta / (10.0 * m * float(h_u))


def band_share(time, values, low: float, high: float) -> float:
    """Share of the variance of ``values`` (on an even grid of ``time``) between ``low`` and
    ``high`` [Hz]: the band's part of their power spectrum (numerics.spectrum)."""
    f, power = power_spectrum(time, values)
    inside = (f >= low) & (f <= high)
    return float(power[inside].sum() / max(power[1:].sum(), 1e-300))


def spectrum_peak(time, values, low: float, high: float) -> tuple[float, float]:
    """(frequency [Hz], amplitude) of the largest line of ``values`` between ``low`` and ``high``
    [Hz] in their amplitude spectrum (numerics.spectrum)."""
    f, amplitude = spectrum(time, values)
    inside = np.flatnonzero((f >= low) & (f <= high))
    best = inside[np.argmax(amplitude[inside])]
    return float(f[best]), float(amplitude[best])


def hess_soom_friction(time):
    """(sliding velocity u [m/s], friction coefficient [-]) of one roller in the test the paper
    sets beside Hess and Soom's measurement (Fig. 11) at the times ``time`` [s].

    Load 250 N; u of eq. 33 with Table 1's mean 0.2375 m/s, amplitude 0.25 m/s and 5 Hz; Table
    1's surface and limiting shear (HESS_SOOM); Table 3's viscosity and Table 2's roller (the
    paper gives no other geometry); the steady film of eq. 4 at each instant, whose relaxation
    time 99 h_s / |u| (under a millisecond) is short against the 200 ms cycle.
    """
    _, u, _ = Oscillating().evaluate(np.asarray(time, dtype=float))
    load = paper.HESS_SOOM_LOAD
    film = steady_film(LineContact(), load, u)
    boundary, viscous = friction.contact_friction(load, film, u, HESS_SOOM)
    return u, (boundary + viscous) / load


def rig_facts(u: float = RIG_SPEED) -> dict:
    """k, preload approach, films and natural frequencies of Soleimanian et al. 2020's rig at
    y = 0, feed speed u [m/s]; ValueError naming 'u' unless it is finite."""
    checks.finite("'u'", u)
    g, body = four_rows.Guideway(), carriage.Carriage()
    state = four_rows.quasi_static_state(g, 0.0, u)
    f_u, h_u = float(state[0]), float(state[2])
    k_lub = float(four_rows.quasi_static_stiffness(g, 0.0, u, state=state))
    k_dry = float(four_rows.quasi_static_stiffness(g, 0.0, lubricated=False))
    pan_hamrock = LineContact(model="pan_hamrock")

    def hz(k):
        return float(np.sqrt(k / body.mass) / (2 * np.pi))

    return {
        "roller_stiffness_k_N_per_m^(10/9)": g.k,
        "preload_per_roller_N": g.preload_per_roller,
        "preload_approach_delta0_m": g.delta0,
        "feed_speed_m_per_s": u,
        "film_extrapolated_at_y0_m": h_u,
        "film_pan_hamrock_at_y0_m": float(steady_film(pan_hamrock, f_u, u)),
        "roller_load_at_y0_N": f_u,
        "rail_mass_kg": body.mass,
        "stiffness_y0_lubricated_N_per_m": k_lub,
        "stiffness_y0_dry_N_per_m": k_dry,
        "natural_frequency_lubricated_Hz": hz(k_lub),
        "natural_frequency_dry_Hz": hz(k_dry),
        "paper_natural_frequency_Hz": PAPER_NATURAL_FREQUENCY,
    }
