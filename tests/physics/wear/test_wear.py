"""Fractal surfaces, Carter creep and the wear of a ball guide (physics/wear/fractal.py, creep.py,
wear.py) against synthetic profiles, hand calculations, limiting cases and the paper's trends."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from guideway_fmu.physics.wear import creep, fractal, raceway_wear
from guideway_fmu.physics.ball_guides import hertz_point
from support import returns

STEEL = dict(e_star=1.143e11, yield_strength=518.4e6, hardness=2.8 * 518.4e6)


# -- the structure function ---------------------------------------------------------------
@pytest.mark.parametrize("dimension, scale", [(1.5, 2.38e-8), (1.65, 3e-11), (1.8, 2.38e-8)])
def test_structure_function_fit_recovers_d_and_g_of_a_synthetic_wm_profile(dimension, scale):
    # a W-M profile 10 mm long sampled every 0.1 um, its frequencies from 1/(10 mm) to 1000
    # times the sampling rate (the structure function at whole lags sees them all), fitted over
    # lags of 0.4 to 10 um: eight periods ln(1.5) of the sum's log-periodic ripple
    spacing = 1e-7
    x = np.arange(0.0, 1e-2, spacing)
    z = fractal.wm_profile(x, dimension, scale, lowest=1 / 1e-2, highest=1e3 / spacing)
    fit = fractal.fit_structure_function(z, spacing, shortest=4, longest=103, points=200)
    assert fit.dimension == pytest.approx(dimension, rel=0.05)
    assert fit.scale == pytest.approx(scale, rel=0.05)
    assert fit.r_squared > 0.9


def test_structure_function_fit_of_a_low_dimension_profile_recovers_d():
    # at D' = 1.3 G = (E / C)^(1 / (2 (D'-1))) magnifies the intercept's error: the lags'
    # ln(tau) of about -14 turn a 0.3 % error of D' into 11 % of G, so only D' is held to 5 %
    spacing = 1e-7
    x = np.arange(0.0, 1e-2, spacing)
    z = fractal.wm_profile(x, 1.3, 1e-9, lowest=1 / 1e-2, highest=1e3 / spacing)
    fit = fractal.fit_structure_function(z, spacing, shortest=4, longest=103, points=200)
    assert fit.dimension == pytest.approx(1.3, rel=0.05)


def test_wm_constant_is_continuous_through_d_1_5_limiting_case():
    # Gamma(e) sin(pi e / 2) -> pi / 2 as e = 2D' - 3 -> 0; (2 pi)^(4-2D') = 2 pi there
    assert fractal.wm_constant(1.5) == pytest.approx(2 * np.pi * np.pi / 2 / np.log(1.5),
                                                     rel=1e-12)
    assert fractal.wm_constant(1.5 + 1e-7) == pytest.approx(fractal.wm_constant(1.5), rel=1e-6)


def test_structure_function_of_a_sine_is_the_hand_value():
    # z = A cos(2 pi x / L): <(z(x + tau) - z(x))^2> = A^2 (1 - cos(2 pi tau / L))
    spacing, period, amplitude = 1e-6, 1e-4, 2e-7
    x = np.arange(0, 100 * period, spacing)
    z = amplitude * np.cos(2 * np.pi * x / period)
    lags = np.array([5, 25, 50])
    expected = amplitude**2 * (1 - np.cos(2 * np.pi * lags * spacing / period))
    assert np.allclose(fractal.structure_function(z, spacing, lags), expected, rtol=1e-3)


def test_a_flat_or_white_profile_is_refused_with_a_reason():
    with pytest.raises(ValueError, match="flat"):
        fractal.fit_structure_function(np.zeros(1000), 1e-6)
    with pytest.raises(ValueError, match="outside"):  # a ramp: E = tau^2, D' = 1
        fractal.fit_structure_function(np.linspace(0, 1e-6, 5000), 1e-6)


# -- fractal contact ----------------------------------------------------------------------
def surface(dimension=2.8):
    return fractal.FractalSurface(dimension, 2.38e-8, **STEEL)


def test_critical_area_is_eq_41_by_hand():
    d, g, e, h = 2.4, 2.38e-8, 1.143e11, 2.8 * 518.4e6
    hand = (2 ** (11 - 2 * d) * g ** (2 * d - 4) * e * math.log(1.5)
            / (9 * math.pi ** (4 - d) * h)) ** (1 / (d - 2))
    assert surface(d).critical_area == pytest.approx(hand, rel=1e-12)


@pytest.mark.parametrize("dimension", [2.3, 2.5, 2.8])
def test_contact_load_and_area_are_continuous_at_the_critical_area_limiting_case(dimension):
    s = surface(dimension)
    below = s.contact(s.critical_area * (1 - 1e-9))
    above = s.contact(s.critical_area * (1 + 1e-9))
    assert above[0] == pytest.approx(below[0], rel=1e-6)
    assert above[1] == pytest.approx(below[1], rel=1e-6)


def test_contact_at_d_2_5_is_the_limit_of_its_neighbours():
    area = 5 * surface(2.5).critical_area
    at = surface(2.5).contact(area)[0]
    near = [fractal.FractalSurface(2.5 + e, 2.38e-8, **STEEL).contact(area)[0]
            for e in (-1e-6, 1e-6)]
    assert at == pytest.approx(np.mean(near), rel=1e-4)


def test_real_area_is_the_integral_of_the_island_distribution_hand_calculation():
    # S = integral of A n(A) dA over (0, A_L] of eq. 40, the truncated areas being twice the
    # real ones above A_c (Yan and Komvopoulos) and equal below: eq. 44
    s = surface(2.6)
    d, a_c, a_l = s.dimension, s.critical_area, 50 * s.critical_area

    def density(a):
        return (d - 1) / 2 * a_l ** ((d - 1) / 2) * a ** (-(d + 1) / 2)

    elastic = quad(lambda a: a / 2 * density(a), a_c, a_l, epsrel=1e-12)[0]
    plastic = quad(lambda a: (d - 1) / 2 * a_l ** ((d - 1) / 2), 0, a_c, weight="alg",
                   wvar=((1 - d) / 2, 0.0), epsrel=1e-12)[0]  # a n(a) = c a^((1-D)/2)
    assert s.contact(a_l)[1] == pytest.approx(elastic + plastic, rel=1e-6)


def test_film_carries_a_pressure_below_the_yield_strength_limiting_case():
    s = surface()
    assert s.largest_area(0.9 * s.yield_strength) == 0.0
    assert s.wear_per_length(1e-8, 0.9 * s.yield_strength) == 0.0
    above = s.largest_area(1.5e9)
    assert s.carried(above) == pytest.approx(1.5e9, rel=1e-9)


def test_largest_area_grows_with_pressure_and_saturates_at_full_contact():
    s = surface(2.2)  # plastic-dominated: carries at most about H
    areas = [s.largest_area(p) for p in (0.6e9, 0.9e9, 1.2e9)]
    assert areas == sorted(areas) and areas[0] > 0
    assert s.largest_area(5e9) == pytest.approx(s.full_contact)
    assert s.contact(s.full_contact)[1] == pytest.approx(s.patch_area)


# -- creep --------------------------------------------------------------------------------
def test_zero_tangential_force_gives_full_adhesion_and_no_creep_limiting_case():
    c = creep.creep(1e-4, 1e-3, 4e-3, 0.1, 0.0, 0.0)
    assert c.adhesion_along == 1.0 and c.slip_area == 0.0 and c.creep_along == 0.0
    assert c.adhesion_area == pytest.approx(np.pi * 1e-4 * 1e-3)


def test_carter_creep_rate_and_areas_by_hand():
    a, b, d, mu, r = 1e-4, 1e-3, 4e-3, 0.1, 0.36
    c = creep.creep(a, b, d, mu, r)
    assert c.adhesion_along == pytest.approx(0.8)  # sqrt(1 - 0.36)
    assert c.creep_along == pytest.approx(2 * a * mu / d * (0.8 - 1))
    assert c.slip_area == pytest.approx(np.pi * a * b * 0.2)
    assert c.slip_area + c.adhesion_area == pytest.approx(np.pi * a * b)


def test_full_sliding_is_refused_by_name():
    with pytest.raises(ValueError, match="ratio_along"):
        creep.creep(1e-4, 1e-3, 4e-3, 0.1, 1.0)


def test_rolling_friction_is_eq_37_by_hand():
    assert creep.rolling_friction(6e-5, 2e-3, 2e-6, 0.9) == pytest.approx(
        3 * 0.9 * 2 * 6e-5 / 16 / (2e-3 - 1e-6))


# -- the guide ----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def lg20():
    return raceway_wear.Guide()


def test_lg20_reduced_modulus_is_the_papers_e_star(lg20):
    assert lg20.surface.e_star == pytest.approx(1.143e11, rel=1e-3)


def test_preload_ball_load_is_hertz_of_the_initial_deformation(lg20):
    assert lg20.state(0.0, (0.0, 0.0))["preload"] == pytest.approx(
        lg20.ball_constant * 4e-6 ** 1.5, rel=1e-12)


def test_settle_balances_the_load_and_the_rows_by_statics(lg20):
    z, q_u, q_l = lg20.settle(2000.0, 4e-6, 3e-6)
    c = math.cos(lg20.contact_angle)
    assert 2 * 12 * c * (q_u - q_l) == pytest.approx(2000.0, rel=1e-9)
    assert q_u == pytest.approx(hertz_point.load(lg20.ball_constant, 4e-6 + z * c), rel=1e-12)
    z0, *_ = lg20.settle(0.0, 4e-6, 4e-6)
    assert z0 == pytest.approx(0.0, abs=1e-15)  # symmetric rows: no sinking


def test_heavy_load_unloads_the_lower_rows_and_the_upper_ones_carry_it_alone(lg20):
    _, q_u, q_l = lg20.settle(20000.0, 4e-6, 4e-6)
    assert q_l == 0.0
    assert q_u == pytest.approx(20000.0 / (2 * 12 * math.cos(lg20.contact_angle)))


def test_rate_table_matches_direct_evaluation(lg20):
    for q in (5.0, 30.0, 77.7, 140.0, 600.0, 3000.0):
        assert lg20.wear_rate(q) == pytest.approx(lg20.contact(q).wear_rate, rel=1e-4)
    assert lg20.wear_rate(0.99 * lg20.threshold_load) == 0.0


@pytest.mark.slow
def test_wear_grows_with_load_and_with_creep_rate_figs_14_to_16():
    loads = [500.0, 2000.0, 5000.0]
    depth = [raceway_wear.simulate(raceway_wear.Guide(), f, 5000.0, 3).columns["wear_upper"][-1]
             for f in loads]
    assert depth == sorted(depth) and depth[0] > 0
    ratios = [0.1, 0.3, 0.6]
    by_creep = [raceway_wear.simulate(raceway_wear.Guide(tangential_ratio=r), 2000.0, 5000.0, 3)
                .columns["wear_upper"][-1] for r in ratios]
    assert by_creep == sorted(by_creep)


def test_wear_growth_slows_with_distance_fig_15():
    # the upper rows' interference wears away, the lower rows take less, the balls unload
    run = raceway_wear.simulate(raceway_wear.Guide(wear_coefficient=0.5), 2000.0, 2e6, 41)
    rate = np.diff(run.columns["wear_upper"])
    assert rate[-1] < 0.9 * rate[0]
    assert np.all(np.diff(rate) <= 1e-12 * rate[0])


def test_no_tangential_force_means_no_wear_limiting_case():
    run = raceway_wear.simulate(raceway_wear.Guide(tangential_ratio=0.0), 2000.0, 5000.0, 5)
    assert np.all(run.columns["wear_depth"] == 0.0) and run.preload_lost_at is None


def test_preload_is_lost_exactly_when_the_wear_depth_reaches_the_initial_deformation():
    guide = raceway_wear.Guide(wear_coefficient=0.5)
    run = raceway_wear.simulate(guide, 2000.0, 5e6, 51)
    at = run.preload_lost_at
    assert at is not None and 0 < at < 5e6
    depth = np.interp(at, run.distance, run.columns["wear_depth"])
    assert depth == pytest.approx(guide.preload_deformation, rel=2e-3)  # the grid's interpolation
    before = run.distance < at
    assert np.all(run.columns["preload_deformation"][before] > 0)
    assert np.all(run.columns["preload_deformation"][~before] <= 0)
    assert np.all(run.columns["preload"][~before] == 0.0)
    # the event itself, integrated to it: the depth equals delta_0 to the solver's tolerance
    h = guide.advance(2000.0, (0.0, 0.0), at)
    assert (h[0] + h[1]) / 4 == pytest.approx(guide.preload_deformation, rel=1e-6)


def test_advance_in_pieces_equals_one_run():
    guide = raceway_wear.Guide(wear_coefficient=0.5)
    whole = guide.advance(2000.0, (0.0, 0.0), 1e6)
    pieces = np.zeros(2)
    for _ in range(10):
        pieces = guide.advance(2000.0, pieces, 1e5)
    assert np.allclose(pieces, whole, rtol=1e-6)


@pytest.mark.parametrize("changes, name", [({"balls_per_row": 0}, "balls_per_row"),
                                           ({"contact_angle": 2.0}, "contact_angle"),
                                           ({"fractal_dimension": 3.2}, "fractal dimension"),
                                           ({"tangential_ratio": 1.5}, "tangential_ratio"),
                                           ({"spacing_ratio": 0.8}, "spacing_ratio"),
                                           ({"conformity": 0.4}, "conformity")])
def test_bad_guide_parameters_are_refused_by_name(changes, name):
    with pytest.raises(ValueError, match=name):
        raceway_wear.Guide(**changes)


def test_wear_volume_per_sliding_length_is_eqs_51_to_53_by_hand():
    # eq. 52 over eq. 51 with the numbers written out for D = 2.6, a slip area of 100 patches
    s = surface(2.6)
    pressure = 1.2e9
    a_l, a_c, g = s.largest_area(pressure), s.critical_area, 2.38e-8
    slip = 100 * 64e-12
    volume = (100 * (math.pi - 2) * 2 ** 0.4 * g ** 0.6 * a_l ** 0.8 * a_c ** 0.4 * 1.6
              / (0.4 * math.pi ** 2.2))
    size = 2 * 1.6 * math.sqrt(a_c) / (math.sqrt(math.pi) * 0.6)
    assert s.wear_per_length(slip, pressure) == pytest.approx(volume / size, rel=1e-12)
    assert s.wear_per_length(2 * slip, pressure) == pytest.approx(
        2 * s.wear_per_length(slip, pressure), rel=1e-12)  # patches add up


def test_row_wear_rate_is_eqs_54_to_58_by_hand(lg20):
    # n_s K_f V_0 |zeta_x| over the strip 2 l_r b, l_r = (D_w (n_s - 1) + 1) D_b
    c = lg20.contact(140.0)
    v0 = lg20.surface.wear_per_length(c.creep.slip_area, c.pressure)
    strip = (1.0 * 11 + 1) * 3.969e-3
    assert c.wear_rate == pytest.approx(12 * 5e-4 * v0 * abs(c.creep.creep_along)
                                        / (2 * strip * c.across), rel=1e-12)
    assert c.pressure == pytest.approx(140.0 / (math.pi * c.along * c.across))  # eq. 21


def test_limiting_case_a_load_beyond_the_balls_stops_the_slider_solve_naming_it(lg20):
    # 1e300 N: the Hertz loads of the bracket's ends overflow, no sign change is left
    with pytest.raises(ValueError, match=r"sinking.*1e\+300 N"):
        lg20.settle(1e300, 1e-6, 1e-6)


@pytest.mark.parametrize("run", [
    lambda g: g.advance(2000.0, (0.0, 0.0), 1e300),
    lambda g: raceway_wear.simulate(g, 2000.0, 1e300, 3),
], ids=["advance", "simulate"])
def test_limiting_case_a_running_distance_beyond_any_wear_stops_the_integration_naming_it(
        lg20, run):
    # past the preload's loss the upper rows wear on at a rate that grows with their depth
    # (7e6 m deep after 1e20 m): over 1e300 m the integration took steps without end
    with returns(), pytest.raises(RuntimeError, match=r"1e\+300 m under 2000 N"):
        run(lg20)
