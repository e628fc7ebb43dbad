"""Hertz point contact of a ball in a groove (physics/ball_guides/hertz_point.py) against hand calculations,
a second published form of the ellipse equation, numerical derivatives and the Hamrock-Brewe
fits."""
from __future__ import annotations

import pytest
from scipy.special import ellipe, ellipk

from guideway_fmu.physics.ball_guides import hertz_point as hp

D = 4.763e-3  # ball of Wu et al. (2012), Table 1


def test_nearly_flat_groove_gives_sphere_on_flat_hand_calculation():
    # f -> infinity: a ball on a flat, Hertz's circle: delta = (9 Q^2 / (16 E*^2 R_b))^(1/3),
    # a = (3 Q R_b / (4 E*))^(1/3), E* = E'/2, R_b = D/2
    contact = hp.BallGroove(D, 1e7)
    q, e_star, r_b = 50.0, contact.e_reduced / 2.0, D / 2.0
    delta = (9 * q**2 / (16 * e_star**2 * r_b)) ** (1 / 3)
    assert hp.approach(hp.constant(contact), q) == pytest.approx(delta, rel=1e-6)
    a, b = hp.semi_axes(contact, q)
    assert a == pytest.approx((3 * q * r_b / (4 * e_star)) ** (1 / 3), rel=1e-6)
    assert b == pytest.approx(a, rel=1e-5)


@pytest.mark.parametrize("conformity", [0.505, 0.52, 0.55, 0.6, 1.0])
def test_ellipticity_satisfies_johnsons_form_of_the_curvature_ratio(conformity):
    # Johnson (Contact Mechanics, eq. 4.39 form): B/A = (kappa^2 E - K) / (K - E), B/A the
    # radius ratio R_y / R_x; the module solves Harris's curvature-difference form instead
    contact = hp.BallGroove(D, conformity)
    el = hp.ellipse(contact)
    m = 1.0 - 1.0 / el.kappa**2
    ratio = (el.kappa**2 * ellipe(m) - ellipk(m)) / (ellipk(m) - ellipe(m))
    assert ratio == pytest.approx(contact.radius_ratio, rel=1e-9)
    a, b = hp.semi_axes(contact, 80.0)
    assert a / b == pytest.approx(el.kappa, rel=1e-12)


@pytest.mark.parametrize("conformity", [0.51, 0.52, 0.53, 0.55, 0.6, 0.75, 1.0])
def test_hamrock_brewe_fits_stay_within_their_error_of_the_exact_solution(conformity):
    # measured: kappa within 3.2 %, K_h within 3.2 %, a within 2.2 %, b within 1.1 % for
    # radius ratios 2..51 (f 0.51..1); at f = 0.505 (ratio 101) kappa errs by 6.4 %
    contact = hp.BallGroove(D, conformity)
    exact, fit = hp.ellipse(contact), hp.ellipse(contact, "hamrock-brewe")
    assert abs(fit.kappa / exact.kappa - 1) < 0.035
    assert abs(hp.constant(contact, "hamrock-brewe") / hp.constant(contact) - 1) < 0.035
    (a, b), (a_fit, b_fit) = hp.semi_axes(contact, 100.0), hp.semi_axes(contact, 100.0, "hamrock-brewe")
    assert abs(a_fit / a - 1) < 0.025 and abs(b_fit / b - 1) < 0.012


def test_stiffness_is_the_derivative_of_the_load_numerical_derivative():
    k_h = hp.ball_constant(hp.BallGroove(D, 0.52))
    delta, step = 3e-6, 1e-10
    numerical = (hp.load(k_h, delta + step) - hp.load(k_h, delta - step)) / (2 * step)
    assert hp.stiffness(k_h, delta) == pytest.approx(numerical, rel=1e-7)
    assert hp.approach(k_h, hp.load(k_h, delta)) == pytest.approx(delta, rel=1e-12)
    assert hp.load(k_h, -1e-6) == 0.0 and hp.stiffness(k_h, -1e-6) == 0.0  # contact lost


def test_two_grooves_in_series_double_the_approach_hand_calculation():
    contact = hp.BallGroove(D, 0.52)
    q = 40.0
    assert hp.approach(hp.ball_constant(contact), q) == pytest.approx(
        2 * hp.approach(hp.constant(contact), q), rel=1e-12)


@pytest.mark.parametrize("kwargs, name", [
    ({"diameter": -1e-3, "conformity": 0.52}, "diameter"),
    ({"diameter": D, "conformity": 0.5}, "conformity"),
    ({"diameter": D, "conformity": 0.52, "nu_ball": 0.7}, "nu_ball"),
    ({"diameter": D, "conformity": 0.52, "e_groove": 0.0}, "e_groove"),
])
def test_bad_geometry_is_refused_naming_the_field(kwargs, name):
    with pytest.raises(ValueError, match=name):
        hp.BallGroove(**kwargs)
    with pytest.raises(ValueError, match="method"):
        hp.ellipse(hp.BallGroove(D, 0.52), "approximate")


def test_limiting_case_a_conformity_next_to_a_half_stops_the_ellipse_solve_naming_it():
    # f -> 1/2: the groove's radius nears the ball's, F -> 1 and kappa -> infinity, beyond the
    # bracket [1, 1e4] of the exact solve: a named error instead of SciPy's bare one
    with pytest.raises(ValueError, match="ellipticity.*conformity 0.5"):
        hp.ellipse(hp.BallGroove(0.01, 0.5 + 1e-10))
