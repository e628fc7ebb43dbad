"""Checks of the line-contact film laws and the squeeze bracket of Soleimanian et al. (2020) eqs. 4-5."""
import dataclasses
import math

import numpy as np
import pytest

from guideway_fmu.physics.roller_guide import film

EXTRAPOLATED = film.LineContact()  # Soleimanian et al. (2020) Tables 2-3
PAN_HAMROCK = film.LineContact(model="pan_hamrock")
LOAD = 115.0  # N, preload per roller of the default guideway
SPEED = 0.29  # m/s, amplitude of the paper's feed velocity (A_1 = 0.2919)
# Velocity exponent of each law and its load exponent.
EXPONENTS = [(EXTRAPOLATED, 0.647, -0.045), (PAN_HAMROCK, 0.694, -0.128)]


def test_extrapolated_steady_film_hand_calculation():
    # Eq. 5 with R = 2.5e-3 m, l = 8e-3 m, E' = 2e11 Pa, mu0 = 0.195 Pa s, alpha = 2.2e-8 1/Pa:
    fbar = 115.0 / (2e11 * 2.5e-3 * 8e-3)  # = 115 / 4e6 = 2.875e-5
    u_dimless = 0.195 * 0.29 / (2e11 * 2.5e-3)  # = 0.05655 / 5e8 = 1.131e-10
    g = 2.2e-8 * 2e11  # = 4400
    assert (fbar, u_dimless, g) == pytest.approx((2.875e-5, 1.131e-10, 4400.0), rel=1e-12)
    # Fbar^-0.045 = 1.600889, U^0.647 = 3.669360e-7, G^0.46 = 47.42291; with the steady bracket 0.25:
    # h = 0.25 * 2.5e-3 * 13.924 * 1.600889 * 3.669360e-7 * 47.42291 = 2.424286e-7 m
    h_hand = 0.25 * 2.5e-3 * 13.924 * fbar**-0.045 * u_dimless**0.647 * g**0.46
    assert h_hand == pytest.approx(0.25 * 2.5e-3 * 13.924 * 1.600889 * 3.669360e-7 * 47.42291, rel=1e-6)
    assert h_hand == pytest.approx(2.424286e-7, rel=1e-6)
    assert film.steady_film(EXTRAPOLATED, LOAD, SPEED) == pytest.approx(h_hand, rel=1e-12)
    assert film.unsqueezed_film(EXTRAPOLATED, LOAD, SPEED) == pytest.approx(4 * h_hand, rel=1e-12)


def test_pan_hamrock_film_hand_calculation():
    # Hamrock's groups: W = F / (l E' R), U = mu0 (u/2) / (E' R), G = alpha E'.
    w = 115.0 / (8e-3 * 2e11 * 2.5e-3)  # = 2.875e-5
    u_dimless = 0.195 * (0.29 / 2) / (2e11 * 2.5e-3)  # = 0.028275 / 5e8 = 5.655e-11
    g = 2.2e-8 * 2e11  # = 4400
    # W^-0.128 = 3.813242, U^0.694 = 7.730156e-8, G^0.568 = 117.3495:
    # H_min = 1.714 * 3.813242 * 7.730156e-8 * 117.3495 = 5.928905e-5, h = R H_min = 1.482226e-7 m
    h_hand = 2.5e-3 * 1.714 * w**-0.128 * u_dimless**0.694 * g**0.568
    assert h_hand == pytest.approx(2.5e-3 * 1.714 * 3.813242 * 7.730156e-8 * 117.3495, rel=1e-6)
    assert h_hand == pytest.approx(1.482226e-7, rel=1e-6)
    assert film.steady_film(PAN_HAMROCK, LOAD, SPEED) == pytest.approx(h_hand, rel=1e-12)


@pytest.mark.parametrize("contact", [EXTRAPOLATED, PAN_HAMROCK], ids=["extrapolated", "pan_hamrock"])
def test_film_limiting_case_zero_speed_gives_zero_film(contact):
    loads = np.array([0.0, 1.0, LOAD, 1e4])
    assert np.array_equal(film.steady_film(contact, loads, 0.0), np.zeros(4))


@pytest.mark.parametrize("contact", [EXTRAPOLATED, PAN_HAMROCK], ids=["extrapolated", "pan_hamrock"])
def test_film_limiting_case_direction_of_feed_does_not_matter(contact):
    assert film.steady_film(contact, LOAD, -SPEED) == film.steady_film(contact, LOAD, SPEED)


@pytest.mark.parametrize("contact, speed_exponent, load_exponent", EXPONENTS,
                         ids=["extrapolated", "pan_hamrock"])
@pytest.mark.parametrize("speed", [1e-4, 0.01, SPEED, 2.0])
def test_film_exponents_log_log_numerical_derivative(contact, speed_exponent, load_exponent, speed):
    eps = 1e-4

    def log_slope(h_of):
        return (math.log(h_of(1 + eps)) - math.log(h_of(1 - eps))) / (
            math.log(1 + eps) - math.log(1 - eps))

    assert log_slope(lambda f: film.steady_film(contact, LOAD, speed * f)) == pytest.approx(
        speed_exponent, rel=1e-8)
    assert log_slope(lambda f: film.steady_film(contact, LOAD * f, speed)) == pytest.approx(
        load_exponent, rel=1e-8)


def test_film_limiting_case_unloaded_roller_steady_film_is_infinite_and_none_without_motion():
    # h = C F^-m: no floor, the law's own limit; no entrainment (u = 0): no film
    films = film.steady_film(EXTRAPOLATED, [0.0, -1.0, 1e-30, LOAD], SPEED)
    assert np.isinf(films[0]) and np.isinf(films[1])
    assert films[2] == pytest.approx(films[3] * (LOAD / 1e-30) ** 0.045, rel=1e-9)
    assert np.array_equal(film.steady_film(EXTRAPOLATED, [0.0, LOAD], 0.0), [0.0, 0.0])


@pytest.mark.parametrize("load", [0.0, 1e-300, 1e-100])
def test_unloaded_roller_film_grows_at_the_squeeze_relations_limit_hand_value(load):
    # h / h_s -> 0: 0.75 exp(132 h_dot / u) -> 1, h_dot = |u| ln(4/3) / 132, clipped at
    # S_MAX = ln(0.99 / 0.75): 0.29 m/s * 0.27763 / 132 = 6.0996e-4 m/s. A roller under
    # 1e-100 N (h F^m / C = 3e-5 of the ratio at 1 N) is within 1e-3 of it.
    from guideway_fmu.physics.roller_guide.four_rows import Guideway, RowKernel
    kernel = RowKernel(Guideway())
    limit = SPEED * math.log(0.99 / 0.75) / 132.0
    assert limit == pytest.approx(6.0996e-4, rel=1e-4)
    h = float(film.steady_film(EXTRAPOLATED, 100.0, SPEED))  # a loaded film, then unloaded
    rate = kernel.film_rate(h, load, SPEED)
    assert rate == pytest.approx(limit, rel=1e-3 if load else 1e-12)
    assert rate <= limit * (1 + 1e-12)


def test_unsqueezed_film_refuses_pan_hamrock():
    with pytest.raises(ValueError, match="extrapolated"):
        film.unsqueezed_film(PAN_HAMROCK, LOAD, SPEED)


# --- the squeeze bracket 1 - 0.75 exp(132 h_dot / u): published form and its regularisation ----

H_DOTS = np.concatenate([-np.geomspace(1.0, 1e-12, 13), [0.0], np.geomspace(1e-12, 1.0, 13)])
SPEEDS = np.concatenate([-np.geomspace(1.0, 1e-12, 7), [-0.0, 0.0], np.geomspace(1e-12, 1.0, 7)])


def test_squeeze_factor_show_effect_published_form_turns_negative_for_growing_film_at_small_speed():
    # 132 h_dot / u = 132 * 1e-6 / 1e-5 = 13.2: 1 - 0.75 e^13.2 = 1 - 0.75 * 5.40e5 = -4.05e5.
    published = film.squeeze_factor(1e-6, 1e-5, regularised=False)
    assert published == pytest.approx(1 - 0.75 * math.exp(13.2), rel=1e-12)
    assert published < -4e5
    # The regularised bracket clips the exponent at S_MAX: the film keeps 1 % of its unsqueezed value.
    assert film.squeeze_factor(1e-6, 1e-5) == pytest.approx(film.FACTOR_MIN, rel=1e-12)


@pytest.mark.parametrize("h_dot", [1e-6, 0.0])
def test_squeeze_factor_show_effect_published_form_undefined_at_zero_speed(h_dot):
    assert not np.isfinite(film.squeeze_factor(h_dot, 0.0, regularised=False))
    assert np.isfinite(film.squeeze_factor(h_dot, 0.0))


def test_squeeze_factor_show_effect_regularised_bounded_on_grid():
    h_dot, u = np.meshgrid(H_DOTS, SPEEDS)
    factor = film.squeeze_factor(h_dot, u)
    assert np.all(np.isfinite(factor))
    assert np.all(factor >= film.FACTOR_MIN) and np.all(factor < 1.0)
    # Limiting cases: no squeeze gives the steady 0.25; the frozen film at u = 0 too.
    assert film.squeeze_factor(0.0, 0.0) == 0.25 and film.squeeze_factor(0.0, -SPEED) == 0.25


def test_squeeze_factor_limiting_case_regularised_equals_published_where_well_behaved():
    u = np.array([1e-4, 0.01, SPEED, 1.0])[:, None]
    s = np.array([-4.5, -1.0, -0.1, 0.0, 0.1, 0.25])[None, :]  # inside (S_MIN, S_MAX) = (-4.61, 0.2776)
    h_dot = s * u / film.SQUEEZE_GAIN
    np.testing.assert_allclose(film.squeeze_factor(h_dot, u),
                               film.squeeze_factor(h_dot, u, regularised=False), rtol=1e-14)


@pytest.mark.parametrize("u", [1e-6, 0.01, SPEED, -SPEED, 3.0])
def test_film_rate_inverts_squeeze_factor(u):
    h_s = 1e-6  # m, unsqueezed film
    # Inside the unclipped range (S_MIN, S_MAX) = (ln 0.01, ln(0.99 / 0.75)).
    s = np.linspace(film.S_MIN * 0.99, film.S_MAX * 0.99, 41)
    h_dot = s * abs(u) / film.SQUEEZE_GAIN
    h = h_s * film.squeeze_factor(h_dot, u)
    np.testing.assert_allclose(film.film_rate(h, h_s, u), h_dot, rtol=1e-9, atol=1e-14 * abs(u))


@pytest.mark.parametrize("h_over_hs", [0.0, 0.01, 0.25, 0.5, 0.99, 2.0])
def test_film_rate_limiting_case_zero_speed_freezes_film(h_over_hs):
    assert film.film_rate(h_over_hs * 1e-6, 1e-6, 0.0) == 0.0


@pytest.mark.parametrize("u", [0.01, SPEED, -SPEED])
def test_film_rate_limiting_case_steady_film_is_equilibrium(u):
    h_s = np.array([1e-8, 9.7e-7, 1e-6])
    assert np.array_equal(film.film_rate(h_s / 4, h_s, u), np.zeros(3))


@pytest.mark.parametrize("h_over_hs", [1.0, 1.5])
def test_film_rate_limiting_case_film_above_unsqueezed_drains_at_clipped_rate(h_over_hs):
    # 1 - h / h_s <= 0 has no logarithm: the exponent is clipped to S_MIN, h_dot = S_MIN |u| / 132.
    rate = film.film_rate(h_over_hs * 1e-6, 1e-6, -SPEED)
    assert rate == pytest.approx(film.S_MIN * SPEED / film.SQUEEZE_GAIN, rel=1e-14)


def test_film_rate_limiting_case_relaxes_towards_steady_film():
    h_s = 1e-6
    below, above = film.film_rate(np.array([0.1, 0.4]) * h_s, h_s, SPEED)
    assert below > 0.0 > above


def test_line_contact_defaults_validate():
    EXTRAPOLATED.validate()
    PAN_HAMROCK.validate()


@pytest.mark.parametrize("field, value", [
    ("radius", 0.0), ("radius", -1e-3), ("length", -8e-3), ("e_reduced", math.nan),
    ("viscosity", 0.0), ("viscosity", math.inf), ("pressure_viscosity", -1e-8), ("model", "dry"),
])
def test_line_contact_validate_refuses_bad_field_naming_it(field, value):
    contact = dataclasses.replace(EXTRAPOLATED, **{field: value})
    with pytest.raises(ValueError, match=f"LineContact.{field}"):
        contact.validate()
