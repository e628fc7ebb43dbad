"""The readings of Soleimanian et al. (2020) and the measures its statements are computed with
(analysis/soleimanian2020.py), against hand calculations."""
from __future__ import annotations


import numpy as np
import pytest

from guideway_fmu import scenarios
from guideway_fmu.analysis import soleimanian2020 as paper
from guideway_fmu.cosim import system
from guideway_fmu.physics.roller_guide import carriage, four_rows


def test_readings_share_9200_n_over_80_40_and_20_rollers_hand_values():
    q0 = {r.name: r.preload_per_roller for r in paper.readings()}
    assert q0 == pytest.approx({"carriage": 115.0, "side": 230.0, "groove": 460.0}, rel=1e-12)


@pytest.mark.parametrize("reading", paper.readings(), ids=lambda r: r.name)
def test_each_readings_mass_gives_the_published_natural_frequency(reading):
    # to the gram: a gram in 3 kg moves the frequency by 1.5e-4 of it
    assert paper.natural_frequency(reading.guideway(), reading.mass) == pytest.approx(6590.0,
                                                                                     rel=1e-4)
    assert reading.guideway().preload_per_roller == pytest.approx(reading.preload_per_roller)


def test_the_groove_reading_is_the_fmus_default():
    # the default reading is the one that reproduces the most statements (docs/physics.md)
    groove = paper.readings()[2]
    assert four_rows.Guideway().preload == groove.preload
    assert carriage.Carriage().mass == groove.mass


def test_film_to_solid_stiffness_is_the_numerical_derivative_ratio():
    # d delta / dF of the solids against dh / dF of the steady film, by central differences
    g = four_rows.Guideway()
    f_u, _, _, _ = four_rows.quasi_static_state(g, 0.0, paper.RIG_SPEED)
    f = float(f_u)
    step = 1e-4 * f
    from guideway_fmu.physics.roller_guide import film
    dh = (film.steady_film(g.contact, f + step, paper.RIG_SPEED)
          - film.steady_film(g.contact, f - step, paper.RIG_SPEED)) / (2 * step)
    ddelta = (((f + step) / g.k) ** 0.9 - ((f - step) / g.k) ** 0.9) / (2 * step)
    assert paper.film_to_solid_stiffness(g) == pytest.approx(ddelta / abs(float(dh)), rel=1e-6)


def test_band_share_and_spectrum_peak_of_two_sines_hand_values():
    t = np.arange(200000) / 1e6  # 0.2 s at 1 MHz
    x = 3.0 * np.sin(2 * np.pi * 5 * t) + 1.0 * np.sin(2 * np.pi * 4500 * t)
    assert paper.band_share(t, x, 0.0, 100.0) == pytest.approx(0.9, abs=1e-3)  # 9 / (9 + 1)
    f, a = paper.spectrum_peak(t, x, 1000.0, 10000.0)
    assert f == pytest.approx(4500.0, abs=5.0) and a == pytest.approx(1.0, rel=0.02)


def test_a_reading_is_a_parameter_set_of_the_shipped_scenarios(fmu_dir):
    groove = paper.readings()[2]
    s = system.load(scenarios.find("soleimanian2020_9000N_4500Hz"), fmu_dir).with_changes(
        parameters=groove.parameters())
    assert s.components["Contact"].parameters["preload"] == 36800.0
    assert s.components["Carriage"].parameters["mass"] == pytest.approx(groove.mass)
    with pytest.raises(system.ScenarioError, match="no component 'Rail'"):
        s.with_changes(parameters={"Rail": {"mass": 1.0}})


def test_hess_soom_test_follows_eq33_and_falls_along_stribecks_mixed_branch():
    # eq. 33 with Table 1: u = 0.2375 - 0.25 sin(2 pi 5 t): 0.2375 at t = 0, -0.0125 at 50 ms
    u, mu = paper.hess_soom_friction(np.array([0.0, 0.05]))
    assert u == pytest.approx([0.2375, -0.0125], abs=1e-12)
    # the film grows as |u|^0.647 and carries more of the 250 N: the coefficient falls with
    # the speed over the cycle's positive half (the mixed branch of a Stribeck curve)
    u, mu = paper.hess_soom_friction(np.linspace(0.1, 0.15, 201))  # u rises from 0.2375 to 0.4875
    assert np.all(np.diff(u) > 0) and np.all(np.diff(mu) < 0)
