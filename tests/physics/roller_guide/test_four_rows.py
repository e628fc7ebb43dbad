"""Checks of the four-row guideway contact mechanics (Soleimanian et al. 2020, eqs. 1b, 2, 3, 6-14)."""
import dataclasses
import math

import numpy as np
import pytest

from guideway_fmu.physics.roller_guide import carriage, film
from guideway_fmu.physics.roller_guide import four_rows as gw
from guideway_fmu.physics.roller_guide.roller_law import contact_force
from support import returns

# Soleimanian et al. (2020) Table 2, INA RUE45-E, with its 9200 N shared by all 80 rollers (the
# light `carriage` reading, whose rows unload within a few micrometres; the default shares it per
# groove, test_default_guideway_is_the_groove_reading below)
GUIDEWAY = gw.Guideway(preload=9200.0)
SPEED = 0.29  # m/s, feed velocity amplitude of the paper (A_1 = 0.2919)
# Palmgren k for l = 8 mm (see test_roller_contact.py), Q0 = 9200 / (4 * 20) = 115 N,
# delta0 = (115 / 5.10388e8)^0.9 = (2.253189e-7)^0.9 = 1.041160e-6 m.
K_HAND = (1e3 * 8.0**0.8 / (2 * 3.84e-5)) ** (1 / 0.9)
DELTA0_HAND = 1.041160e-6
# The lower row loses contact at y = delta0 / sin 45 = 1.4724e-6 m dry; lubricated, its steady
# film keeps a load that falls without end (about 1e-16 N once the gap is five films).
Y_GRID = np.linspace(-5e-6, 5e-6, 41)  # step 2.5e-7 m, both rows loaded and either row unloaded
Y_BOTH_LOADED = [-1.5e-6, -1e-6, -2.5e-7, 0.0, 3e-7, 1e-6, 1.5e-6]  # lubricated at u = 0.29 m/s
LUBRICATION = [pytest.param(False, 0.0, id="dry"), pytest.param(True, SPEED, id="lubricated")]



def film_cases(speeds, ys=(-3e-6, -1.5e-6, -1e-6, -2.5e-7, 0.0, 3e-7, 1e-6, 1.5e-6, 2.5e-6, 5e-6)):
    """(u, y) pairs, including ones where a row's geometry has parted (a vanishing load)."""
    return [(u, y) for u in speeds for y in ys]


def net_contact_force(g, y, u, lubricated):
    f_upper, f_lower, _, _ = gw.quasi_static_state(g, y, u, lubricated)
    return gw.net_force(g, f_upper, f_lower)


def central_difference_stiffness(g, y, u, lubricated, dy=1e-10):
    return (net_contact_force(g, y + dy, u, lubricated)
            - net_contact_force(g, y - dy, u, lubricated)) / (2 * dy)


def eq14_stiffness(g, y):
    """Soleimanian et al. (2020) eq. 14 (dry, theta = 45 deg): K = (10/9) N k (delta_U^(1/9) + delta_L^(1/9))."""
    d_upper = max(g.delta0 + y / (2 * math.sin(g.contact_angle)), 0.0)  # eq. 3 without film
    d_lower = max(g.delta0 - y / (2 * math.sin(g.contact_angle)), 0.0)
    return 10 / 9 * g.rollers_per_groove * g.k * (d_upper ** (1 / 9) + d_lower ** (1 / 9))


def test_preload_approach_hand_calculation():
    assert GUIDEWAY.preload_per_roller == pytest.approx(115.0, rel=1e-15)
    assert GUIDEWAY.k == pytest.approx(K_HAND, rel=1e-12)
    assert (115.0 / K_HAND) ** 0.9 == pytest.approx(DELTA0_HAND, rel=1e-6)
    assert GUIDEWAY.delta0 == pytest.approx(DELTA0_HAND, rel=1e-6)
    # and the preload approach carries the preload: k delta0^(10/9) = Q0
    assert contact_force(GUIDEWAY.delta0, GUIDEWAY.k) == pytest.approx(115.0, rel=1e-12)


@pytest.mark.parametrize("lubricated, u", LUBRICATION + [pytest.param(True, -0.1, id="reversed")])
def test_net_force_limiting_case_zero_at_centre_with_symmetric_preload(lubricated, u):
    f_upper, f_lower, h_upper, h_lower = gw.quasi_static_state(GUIDEWAY, 0.0, u, lubricated)
    assert f_upper == f_lower > 0.0 and h_upper == h_lower
    assert gw.net_force(GUIDEWAY, f_upper, f_lower) == 0.0


@pytest.mark.parametrize("y", Y_GRID[::4])
def test_limiting_case_zero_film_equals_dry(y):
    dry = gw.quasi_static_state(GUIDEWAY, y, SPEED, lubricated=False)
    assert np.array_equal(dry[2:], [0.0, 0.0])
    assert np.array_equal(gw.row_loads(GUIDEWAY, y, 0.0, 0.0), dry[:2])
    # At u = 0 the film vanishes (h ~ u^0.647), so the lubricated loads and stiffness are the dry
    # ones (the films themselves: test_quasi_static_film_is_steady_film_of_its_load with u = 0).
    lubricated = gw.quasi_static_state(GUIDEWAY, y, 0.0, lubricated=True)
    np.testing.assert_allclose(lubricated[:2], dry[:2], rtol=1e-12, atol=0.0)
    assert gw.quasi_static_stiffness(GUIDEWAY, y, 0.0, True) == pytest.approx(
        gw.quasi_static_stiffness(GUIDEWAY, y, SPEED, False), rel=1e-12)


@pytest.mark.parametrize("lubricated, u", LUBRICATION)
@pytest.mark.parametrize("y", Y_GRID)
def test_quasi_static_stiffness_numerical_derivative(lubricated, u, y):
    assert gw.quasi_static_stiffness(GUIDEWAY, y, u, lubricated) == pytest.approx(
        central_difference_stiffness(GUIDEWAY, y, u, lubricated), rel=1e-6)


@pytest.mark.parametrize("angle_deg, lubricated, u, y", [
    (angle, *dry_or_lub.values, y)
    for angle in (20.0, 30.0, 60.0, 75.0) for dry_or_lub in LUBRICATION
    for y in (-3e-6, -1e-6, 0.0, 5e-7, 2e-6)])
def test_other_contact_angle_stiffness_numerical_derivative(angle_deg, lubricated, u, y):
    g = gw.Guideway(contact_angle=math.radians(angle_deg))
    assert gw.quasi_static_stiffness(g, y, u, lubricated) == pytest.approx(
        central_difference_stiffness(g, y, u, lubricated), rel=1e-6)


@pytest.mark.parametrize("y", [-4e-6, -1.4e-6, -5e-7, 0.0, 2e-7, 1e-6, 1.4e-6, 3e-6])
def test_dry_stiffness_published_formula_eq14_at_45_degrees(y):
    assert gw.frozen_film_stiffness(GUIDEWAY, y) == pytest.approx(eq14_stiffness(GUIDEWAY, y), rel=1e-12)
    assert gw.quasi_static_stiffness(GUIDEWAY, y, SPEED, lubricated=False) == pytest.approx(
        eq14_stiffness(GUIDEWAY, y), rel=1e-12)


@pytest.mark.parametrize("y", [-1e-6, 0.0, 5e-7])
def test_row_approach_published_formula_eq3_at_45_degrees(y):
    h_upper, h_lower = 2.0e-7, 3.0e-7
    two_sin = 2 * math.sin(GUIDEWAY.contact_angle)
    eq3_upper = (y + two_sin * h_upper) / two_sin + GUIDEWAY.delta0
    eq3_lower = GUIDEWAY.delta0 - (y - two_sin * h_lower) / two_sin
    assert gw.row_approach(GUIDEWAY, y, h_upper, h_lower) == pytest.approx(
        (eq3_upper, eq3_lower), rel=1e-12)


def test_natural_frequency_published_number():
    # Soleimanian et al. (2020): f_n = sqrt(K / M) / (2 pi) = 6590 Hz for the unloaded, lubricated guideway.
    stiffness = gw.quasi_static_stiffness(gw.Guideway(), 0.0, SPEED, lubricated=True)
    f_n = math.sqrt(stiffness / carriage.Carriage().mass) / (2 * math.pi)
    assert f_n == pytest.approx(6590.0, rel=0.01)


def test_default_guideway_is_the_groove_reading_hand_calculation():
    # 9200 N per groove of 20 rollers: Q0 = 460 N, delta0 = (460 / 5.10388e8)^0.9 = 3.62553e-6 m
    g = gw.Guideway()
    assert g.preload_per_roller == pytest.approx(460.0, rel=1e-15)
    assert g.delta0 == pytest.approx(3.62553e-6, rel=1e-5)


@pytest.mark.parametrize("lubricated, u", LUBRICATION)
@pytest.mark.parametrize("y", [3e-6, 1e-5, 1e-4, -1e-4])
def test_contact_loss_limiting_case_parted_row_carries_nothing_dry_and_a_vanishing_load_lubricated(
        lubricated, u, y):
    # dry: exactly 0; lubricated: the steady film h = C F^-m closes the gap |delta_geom| (to
    # 1e-9 of it) under a load below 1e-12 of Q0 (115 N): F = (C / |delta_geom|)^(1/m)
    state = gw.quasi_static_state(GUIDEWAY, y, u, lubricated)
    f_upper, f_lower, h_upper, h_lower = state
    parted, film_of_parted = (f_lower, h_lower) if y > 0 else (f_upper, h_upper)
    if lubricated:
        gap = -min(gw.row_approach(GUIDEWAY, y))
        assert 0.0 < parted < 1e-12 * GUIDEWAY.preload_per_roller
        assert film_of_parted == pytest.approx(gap, rel=1e-9)
    else:
        assert parted == 0.0 and film_of_parted == 0.0
    outputs = [*state, gw.net_force(GUIDEWAY, f_upper, f_lower),
               gw.quasi_static_stiffness(GUIDEWAY, y, u, lubricated),
               gw.frozen_film_stiffness(GUIDEWAY, y, h_upper, h_lower),
               *gw.film_rates(GUIDEWAY, y, h_upper, h_lower, u)]
    assert np.all(np.isfinite(outputs))


def assert_quasi_static_equation(g, y, u):
    """(F / k)^(9/10) = delta_geom + h(F) for both rows, h(F) the steady film of the film
    module, to 1e-9 of |delta_geom| + h: the approach form, well conditioned also for a parted
    row, whose vanishing load the difference of two near-equal lengths cannot resolve."""
    f_upper, f_lower, _, _ = gw.quasi_static_state(g, y, u)
    d_upper, d_lower = gw.row_approach(g, y)
    for force, d_geom in ((f_upper, d_upper), (f_lower, d_lower)):
        h = film.steady_film(g.contact, force, u)
        approach = (np.asarray(force) / g.k) ** 0.9
        np.testing.assert_allclose(approach - d_geom - h, 0.0,
                                   atol=1e-9 * float(np.max(np.abs(d_geom) + h)))


@pytest.mark.parametrize("u", [SPEED, 0.01, -0.2])
@pytest.mark.parametrize("y", Y_GRID[::2])
def test_quasi_static_state_satisfies_its_own_equation(u, y):
    assert_quasi_static_equation(GUIDEWAY, y, u)


# Cases an earlier solver returned unconverged (a Newton step landing on the bracket end was
# rejected); "returned" is what it gave, the other load is scipy.optimize.brentq's root.
@pytest.mark.parametrize("angle_deg, u, y", [
    (45.0, -0.2, 1.4e-6),  # F_L = 26.349 N returned, 24.163 N solves the equation (+9 %)
    (45.0, -0.2, 3.7e-6),  # F_U = 494.551 N returned, 489.772 N
    (60.0, SPEED, -1e-6),  # F_L = 261.460 N returned, 256.208 N
    (75.0, SPEED, 8e-7),  # F_L = 56.626 N returned, 53.107 N
])
def test_quasi_static_state_satisfies_its_own_equation_hard_cases(angle_deg, u, y):
    assert_quasi_static_equation(gw.Guideway(contact_angle=math.radians(angle_deg)), y, u)


def test_quasi_static_state_vectorised_satisfies_its_own_equation():
    # y = 1e-6 + 1e-10 alone converges; inside this array F_U = 240.44 N instead of 235.29 N.
    assert_quasi_static_equation(GUIDEWAY, Y_GRID + 1e-10, SPEED)


@pytest.mark.parametrize("u, y", film_cases([SPEED, 0.0]))
def test_quasi_static_film_is_steady_film_of_its_load(u, y):
    state = gw.quasi_static_state(GUIDEWAY, y, u)
    films = film.steady_film(GUIDEWAY.contact, np.array(state[:2]), u)
    np.testing.assert_allclose(state[2:], films, rtol=1e-9)


@pytest.mark.parametrize("y", Y_BOTH_LOADED)
def test_lubricated_approach_exceeds_dry(y):
    f_upper, f_lower, h_upper, h_lower = gw.quasi_static_state(GUIDEWAY, y, SPEED)
    lubricated = gw.row_approach(GUIDEWAY, y, h_upper, h_lower)
    dry = gw.row_approach(GUIDEWAY, y)
    assert h_upper > 0.0 and h_lower > 0.0
    assert lubricated[0] > dry[0] and lubricated[1] > dry[1]
    dry_upper, dry_lower, _, _ = gw.quasi_static_state(GUIDEWAY, y, SPEED, lubricated=False)
    assert f_upper > dry_upper and f_lower > dry_lower


@pytest.mark.parametrize("u, y", film_cases([SPEED, 0.01, -0.2]))
def test_film_rates_limiting_case_zero_at_quasi_static_state(u, y):
    # a row carrying a resolvable load (over 1e-6 of Q0): steady. A parted row's load is the
    # contact law of the gap left between two near-equal lengths (below their float
    # resolution): its film grows, at most at the unloaded roller's rate |u| S_MAX / 132.
    f_upper, f_lower, h_upper, h_lower = gw.quasi_static_state(GUIDEWAY, y, u)
    rates = gw.film_rates(GUIDEWAY, y, h_upper, h_lower, u)
    loaded = np.array([f_upper, f_lower]) > 1e-6 * GUIDEWAY.preload_per_roller
    # 1e-9 |u| m/s is an error of 1.3e-7 in the squeeze exponent 132 h_dot / u.
    np.testing.assert_allclose(rates[loaded], 0.0, atol=1e-9 * abs(u))
    assert np.all(rates[~loaded] <= abs(u) * film.S_MAX / film.SQUEEZE_GAIN * (1 + 1e-12))


@pytest.mark.parametrize("y", Y_BOTH_LOADED)
def test_film_rates_limiting_case_thin_film_grows(y):
    _, _, h_upper, h_lower = gw.quasi_static_state(GUIDEWAY, y, SPEED)
    assert np.all(gw.film_rates(GUIDEWAY, y, 0.5 * h_upper, 0.5 * h_lower, SPEED) > 0.0)


def test_guideway_defaults_validate():
    GUIDEWAY.validate()


@pytest.mark.parametrize("changes, name", [
    ({"rollers_per_groove": 0}, "Guideway.rollers_per_groove"),
    ({"rollers_per_groove": 2.5}, "Guideway.rollers_per_groove"),
    ({"preload": math.nan}, "Guideway.preload"),
    ({"preload": -1.0}, "Guideway.preload"),
    ({"contact_angle": 0.0}, "Guideway.contact_angle"),
    ({"contact_angle": 2.0}, "Guideway.contact_angle"),
    ({"stiffness": -1.0}, "Guideway.stiffness"),
    ({"contact": film.LineContact(radius=0.0)}, "LineContact.radius"),
])
def test_guideway_validate_refuses_bad_field_naming_it(changes, name):
    with pytest.raises(ValueError, match=name):
        dataclasses.replace(GUIDEWAY, **changes).validate()


@pytest.mark.parametrize("model", ["extrapolated", "pan_hamrock"])
def test_row_kernel_matches_array_functions_independent_implementation(model):
    g = gw.Guideway(contact=film.LineContact(model=model))
    kernel = gw.RowKernel(g)
    rng = np.random.default_rng(3)
    # y over +-3 um covers both rows losing contact (delta0 + h ~ 1.3 um)
    for y, hu, hl in zip(rng.uniform(-3e-6, 3e-6, 200), rng.uniform(0.0, 4e-7, 200),
                         rng.uniform(0.0, 4e-7, 200)):
        force, k, fu, fl = kernel.contact(y, hu, hl)
        fu_a, fl_a = gw.row_loads(g, y, hu, hl)
        assert (fu, fl) == pytest.approx((float(fu_a), float(fl_a)), rel=1e-12, abs=1e-12)
        assert kernel.loads(y, hu, hl) == pytest.approx((fu, fl), rel=1e-15)
        assert force == pytest.approx(float(gw.net_force(g, fu_a, fl_a)), rel=1e-12, abs=1e-9)
        assert k == pytest.approx(float(gw.frozen_film_stiffness(g, y, hu, hl)), rel=1e-12)


@pytest.mark.parametrize("u", [0.29, -0.05, 0.0])
def test_row_kernel_film_rates_match_array_functions(u):
    g = gw.Guideway()
    kernel = gw.RowKernel(g)
    rng = np.random.default_rng(4)
    for y, hu, hl in zip(rng.uniform(-3e-6, 3e-6, 100), rng.uniform(1e-9, 1.2e-6, 100),
                         rng.uniform(1e-9, 1.2e-6, 100)):
        expected = gw.film_rates(g, y, hu, hl, u)
        assert kernel.film_rates(y, hu, hl, u) == pytest.approx(
            (float(expected[0]), float(expected[1])), rel=1e-12, abs=1e-30)


@pytest.mark.parametrize("model", ["extrapolated", "pan_hamrock"])
@pytest.mark.parametrize("y, approach", [(1e300, r"7\.07e\+299"), (-1e300, r"7\.07e\+299")])
def test_limiting_case_a_displacement_no_load_can_follow_stops_the_steady_solve_naming_it(
        model, y, approach):
    # |y| = 1e300 m: the row pressed by y sin(45 deg) = 7.07e299 m would carry
    # k (7.07e299)^(10/9) N, beyond the largest double, so ln F has no bracket; its widening
    # looped without end (ContactEHL hung in Initialization Mode) and now stops at its bound
    g = gw.Guideway(contact=film.LineContact(model=model))
    with returns(), pytest.raises(ValueError, match=rf"steady roller load.*{approach} m"):
        gw.quasi_static_state(g, y, SPEED)


@pytest.mark.parametrize("lubricated, u", LUBRICATION)
def test_limiting_case_a_load_no_displacement_can_carry_stops_static_displacement_naming_it(
        lubricated, u):
    # 1e300 N needs a displacement whose roller loads overflow: the bracket's doubling is bounded
    with returns(), pytest.raises(ValueError, match=r"static displacement.*1e\+300 N"):
        gw.static_displacement(gw.Guideway(), 1e300, u, lubricated)
