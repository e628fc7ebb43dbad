"""Ball-to-ball contact friction (Lin, Duan and Okwudire 2019) against the paper's published
numbers, direct integration of its appendix and limiting cases."""
import numpy as np
import pytest
from scipy.integrate import dblquad
from scipy.special import ellipe

from guideway_fmu.physics.ball_guides import ball_to_ball as bb

TABLE_1 = bb.Bearing(5e-3, 0.56, 2.1e11, 0.28, 0.1, np.radians(45.0), 0.01)


def case(theta_deg, rho, top=(0.0, 0.0)):
    t = np.radians(theta_deg)
    deviation = (-t, t, np.radians(top[0]), np.radians(top[1]))
    return bb.TwoBallCase(TABLE_1, (deviation, deviation), 100.0, rho)


def test_semi_axis_constant_psi_matches_table_1_published_number():
    assert TABLE_1.psi == pytest.approx(5.307e-4, rel=2e-4)


@pytest.mark.parametrize("ratio", [-0.8, 0.3, 1.5])
def test_friction_maps_match_direct_integration_of_eqs_a4_to_a6(ratio):
    aspect = TABLE_1.aspect

    def integral(kind):
        def integrand(s, t):
            pressure = np.sqrt(max(1 - t * t - s * s, 0.0))
            speed = np.hypot(t - ratio, aspect * s)
            return pressure * {"force": (t - ratio) / speed,
                               "moment": (t * t - ratio * t + aspect**2 * s * s) / speed,
                               "loss": speed}[kind]
        # split where the velocity centre sits (the integrand's kink): quadpack then converges
        cuts = [-1.0, *([ratio] if abs(ratio) < 1 else []), 1.0]
        value = sum(dblquad(integrand, lo, hi, lambda t: -np.sqrt(1 - t * t),
                            lambda t: np.sqrt(1 - t * t), epsabs=1e-8, epsrel=1e-8)[0]
                    for lo, hi in zip(cuts[:-1], cuts[1:]))
        return 3 / (2 * np.pi) * value

    force, moment, loss = TABLE_1.maps.at(ratio)
    assert force == pytest.approx(integral("force"), abs=2e-3)
    assert moment == pytest.approx(integral("moment"), abs=2e-3)
    assert loss == pytest.approx(integral("loss"), abs=2e-3)


def test_pure_spin_moment_equals_eq_11_and_sliding_limits_eq_12():
    aspect = TABLE_1.aspect
    force, moment, _ = TABLE_1.maps.at(0.0)
    assert force == pytest.approx(0.0, abs=1e-12)
    assert moment == pytest.approx(3 / 8 * ellipe(1 - aspect**2), rel=1e-4)
    far = TABLE_1.maps.at([-40.0, 40.0, -1e3, 1e3])
    np.testing.assert_allclose(far[0], [1, -1, 1, -1], atol=1e-3)
    np.testing.assert_allclose(far[1], 0.0, atol=1e-3)


def test_linear_friction_slope_is_near_the_papers_1_38():
    assert TABLE_1.maps.slope == pytest.approx(1.38, rel=0.01)


def test_case_a_reproduces_table_2_and_table_3_published_numbers():
    # Table 3: contact force 3.74 N (analytical) and 4.01 N (numerical); Table 2: numerical
    # epsilon_1 0.87 %; the analytical eq. 33 gives +-0.754 % by hand
    a, n = bb.analytical(case(2.0, -0.6)), bb.numerical(case(2.0, -0.6))
    assert a["contact_force"] == pytest.approx(3.74, rel=0.03)
    assert n["contact_force"] == pytest.approx(4.01, rel=0.03)
    assert n["epsilon"][0] == pytest.approx(0.0087, abs=0.0002)
    w = (0.4 / 1.6) ** (2 / 3)
    hand = (1 - w) / (1 + w) * np.radians(2.0) / 2
    np.testing.assert_allclose(a["epsilon"], [hand, -hand], rtol=1e-12)
    assert a["friction_loss"] == pytest.approx(0.1 * a["contact_force"] * 0.01 / np.cos(np.pi / 4))


def test_case_b_matched_top_deviations_give_no_contact_force():
    a, n = bb.analytical(case(2.0, -0.6, top=(-2.0, 2.0))), bb.numerical(case(2.0, -0.6, top=(-2.0, 2.0)))
    assert a["contact_force"] == 0.0 and n["contact_force"] == 0.0
    np.testing.assert_allclose(n["epsilon"], 0.0, atol=1e-9)


def test_models_agree_at_small_deviation_and_side_load_and_diverge_at_large_fig_8():
    def gap(theta, rho):
        a, n = bb.analytical(case(theta, rho)), bb.numerical(case(theta, rho))
        return ((n["epsilon"][0] - n["epsilon"][1]) / (a["epsilon"][0] - a["epsilon"][1])) - 1

    assert abs(gap(0.5, -0.1)) < 0.02
    assert gap(3.0, -0.8) > 0.2


def test_no_deviation_rolls_at_half_the_groove_velocity_limiting_case():
    for rho in (-0.5, 0.0, 0.3):
        n = bb.numerical(case(0.0, rho))
        np.testing.assert_allclose(n["epsilon"], 0.0, atol=1e-9)
        assert n["contact_force"] == 0.0


def test_contact_loads_balance_the_load_and_match_the_nominal_split_statics():
    angles = bb.contact_angles(TABLE_1, np.zeros(4))
    loads = bb.contact_loads(TABLE_1, angles, -60.0, 100.0)
    upper, lower = bb.diagonal_loads(TABLE_1, -60.0, 100.0)
    np.testing.assert_allclose(loads, [upper, lower, upper, lower], rtol=1e-9)
    t = np.radians(2.0)
    angles = bb.contact_angles(TABLE_1, (-t, t, 0.0, 0.0))
    loads = bb.contact_loads(TABLE_1, angles, -60.0, 100.0)
    sx, sy = np.array([-1, 1, 1, -1]), np.array([-1, -1, 1, 1])
    normals = np.column_stack([sx * np.sin(angles), sy * np.cos(angles)])
    np.testing.assert_allclose(loads @ normals, 0.0, atol=1e-8)  # the ball is in equilibrium
    top = loads[2:, None] * normals[2:]
    np.testing.assert_allclose(top.sum(axis=0), (60.0, 100.0), rtol=1e-9)  # and the top groove


def test_analytical_group_of_two_reproduces_eq_30_and_splits_a_pulling_pair():
    upper, lower = bb.diagonal_loads(TABLE_1, -60.0, 100.0)
    g = [bb.drag(TABLE_1, upper, lower), bb.drag(TABLE_1, lower, upper)]
    eps = [0.0075, -0.0075]
    common, forces = bb.group_forces(eps, g)
    assert forces[0] == pytest.approx(g[0] * g[1] / (g[0] + g[1]) * 0.015, rel=1e-12)
    assert bb.split_groups(eps, g, [True]) == [[0, 1]]
    assert bb.split_groups(eps[::-1], g, [True]) == [[0], [1]]  # the rear ball is slower
    assert bb.split_groups([0.01, -0.01, 0.02], [1.0, 1.0, 1.0], [True, True]) == [[0, 1], [2]]


def test_two_point_contact_is_refused_naming_the_contact():
    with pytest.raises(ValueError, match="two-point contact"):
        bb.analytical(case(2.0, -1.2))
    with pytest.raises(ValueError, match="contact BR"):
        bb.numerical(case(3.0, -0.9))


def test_limiting_case_contact_loads_beyond_any_motion_are_refused_not_answered():
    # 1e300 N per contact: the residual is NaN, which passed the convergence check; the
    # group's velocity came back as pure rolling (v / 2) after the continuation's ten steps
    angles = bb.contact_angles(TABLE_1, np.radians([-2.0, 2.0, 0.0, 0.0]))
    ball = bb.Ball(angles, np.full(4, 1e300))
    with pytest.raises(ValueError, match="no quasi-static ball motion"):
        bb.solve_group(TABLE_1, [ball, ball])
