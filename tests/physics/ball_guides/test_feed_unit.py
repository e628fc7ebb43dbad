"""The four-slider ball-guide feed unit (Zhang, Wang and Le 2019) against hand calculations,
numerical derivatives, symmetry and the paper's stated trends."""
import numpy as np
import pytest

from guideway_fmu.physics.ball_guides import feed_unit as fu
from guideway_fmu.physics.ball_guides import hertz_point as hp

BALL = hp.BallGroove(4.7625e-3, 0.52)
PRELOAD = 20.0
N = 12


def layout(angle_deg=45.0, **changes):
    values = dict(half_span_x=0.1, half_span_y=0.15, row_spacing_y=0.023, row_spacing_z=0.010,
                  contact_angle=np.radians(angle_deg), balls_per_row=N, pitch=4.8e-3)
    values.update(changes)
    return fu.Layout(**values)


def unit(angle_change=True, angle_deg=45.0):
    return fu.FeedUnit(layout(angle_deg), BALL, PRELOAD, angle_change)


@pytest.mark.parametrize("angle_change", [True, False])
def test_zero_load_gives_zero_errors_limiting_case(angle_change):
    state = unit(angle_change).equilibrium(np.zeros(5))
    assert np.all(state.q == 0.0)
    np.testing.assert_allclose(state.loads, PRELOAD, rtol=1e-12)
    np.testing.assert_allclose(np.degrees(state.angles), 45.0, rtol=1e-12)


@pytest.mark.parametrize("angle_deg", [30.0, 45.0, 60.0])
def test_rest_stiffness_hand_calculation(angle_deg):
    # every ball at rest: k0 = 1.5 K delta_p^0.5 along its contact line; with the angle change
    # the preloaded line also turns, adding Q0 / L0 across it. 16 n balls, all at +-alpha.
    a = np.radians(angle_deg)
    k_h = hp.ball_constant(BALL)
    rest = (PRELOAD / k_h) ** (2 / 3)
    k0 = 1.5 * k_h * rest**0.5
    turn = PRELOAD / ((2 * BALL.conformity - 1) * BALL.diameter + rest)
    x = np.concatenate([s * 0.1 + (np.arange(N) - (N - 1) / 2) * 4.8e-3 for s in (1, -1)])
    sum_x2 = 8 * np.sum(x**2)  # each x position carries 8 balls (2 rails x 4 rows)
    for change, extra in ((False, 0.0), (True, turn)):
        k = unit(change, angle_deg).tangent(np.zeros(5))
        k_lat = k0 * np.cos(a) ** 2 + extra * np.sin(a) ** 2  # one ball, along y
        k_ver = k0 * np.sin(a) ** 2 + extra * np.cos(a) ** 2  # one ball, along z
        np.testing.assert_allclose(k[0, 0], 16 * N * k_lat, rtol=1e-12)
        np.testing.assert_allclose(k[1, 1], 16 * N * k_ver, rtol=1e-12)
        np.testing.assert_allclose(k[3, 3], sum_x2 * k_ver, rtol=1e-12)  # pitch: z springs at x
        np.testing.assert_allclose(k[4, 4], sum_x2 * k_lat, rtol=1e-12)  # yaw: y springs at x


@pytest.mark.parametrize("angle_change", [True, False])
def test_tangent_stiffness_matches_central_numerical_derivative(angle_change):
    u = unit(angle_change)
    load = fu.generalized_load((800.0, 1500.0, -4000.0), (0.06, -0.09, 0.12))
    q = u.equilibrium(load).q
    steps = np.array([1e-9, 1e-9, 1e-8, 1e-8, 1e-8])
    numeric = np.column_stack([(u.restoring(q + h * e) - u.restoring(q - h * e)) / (2 * h)
                               for h, e in zip(steps, np.eye(5))])
    np.testing.assert_allclose(-numeric, u.tangent(q), rtol=1e-5, atol=1e-6 * np.abs(numeric).max())


def test_preload_release_hand_calculation():
    # constant angle, central vertical load: the table sinks w, upper balls approach delta_p +
    # w sin(alpha), lower ones delta_p - w sin(alpha). The lower rows go slack at w = delta_p /
    # sin(alpha), where each upper ball carries (2 delta_p)^1.5 K = 2^1.5 Q0: the 96 upper balls
    # then hold F = 96 2^1.5 Q0 sin(alpha) (the "2.83 times the preload" of four-row guides).
    u = unit(False)
    a = np.radians(45.0)
    release = 8 * N * 2**1.5 * PRELOAD * np.sin(a)
    state = u.equilibrium((0.0, -release, 0.0, 0.0, 0.0))
    upper = u.z > 0
    np.testing.assert_allclose(state.q[1], -u.rest / np.sin(a), rtol=1e-9)
    np.testing.assert_allclose(state.approaches[~upper], 0.0, atol=1e-9 * u.rest)
    np.testing.assert_allclose(state.loads[upper], 2**1.5 * PRELOAD, rtol=1e-9)
    before = u.equilibrium((0.0, -0.99 * release, 0.0, 0.0, 0.0))
    assert before.loads[~upper].min() > 0.0


@pytest.mark.parametrize("angle_change", [True, False])
def test_small_load_matches_the_linear_compliance_limiting_case(angle_change):
    u = unit(angle_change)
    load = fu.generalized_load((0.0, 2.0, -3.0), (0.04, 0.05, 0.1))
    linear = np.linalg.solve(u.tangent(np.zeros(5)), load)
    np.testing.assert_allclose(u.equilibrium(load).q, linear, rtol=2e-3)


def test_contact_angle_follows_eqs_9_and_10_hand_calculation():
    # eq. 9: |O's O'g| = ((L0 sin a + dz)^2 + (L0 cos a + dy)^2)^0.5, eq. 10: sin a_s =
    # (L0 sin a + dz) / |O's O'g|, for an upper row ball whose slider moves down by 3 um
    u = unit(True)
    q = np.array([0.0, -3e-6, 0.0, 0.0, 0.0])
    approach, normal, length = u.contact(q)
    ball = np.argmax((u.y > 0.15) & (u.z > 0))  # slider 1, row 1
    a, L0 = np.radians(45.0), u.distance
    expected_length = np.hypot(L0 * np.sin(a) + 3e-6, L0 * np.cos(a))
    np.testing.assert_allclose(length[ball], expected_length, rtol=1e-12)
    np.testing.assert_allclose(abs(normal[1][ball]), (L0 * np.sin(a) + 3e-6) / expected_length,
                               rtol=1e-12)
    np.testing.assert_allclose(approach[ball], u.rest + expected_length - L0, rtol=1e-12)


@pytest.mark.parametrize("angle_change", [True, False])
def test_reversed_load_point_reverses_the_angle_errors_symmetry(angle_change):
    # Fig. 16: the unit is symmetric under a half turn about z, so a vertical force at
    # (-x, -y) gives the same delta_z and the opposite delta_y, epsilon_x, epsilon_y
    u = unit(angle_change)
    force = (0.0, 0.0, -5000.0)
    here = u.equilibrium(fu.generalized_load(force, (0.07, 0.11, 0.2))).q
    there = u.equilibrium(fu.generalized_load(force, (-0.07, -0.11, 0.2))).q
    np.testing.assert_allclose(there, here * np.array([-1, 1, -1, -1, 1]),
                               rtol=1e-9, atol=1e-12 * np.abs(here).max())
    assert abs(here[2]) > 1e-7 and abs(here[3]) > 1e-7  # the angle errors are there to reverse


def test_vertical_and_lateral_stiffness_equal_at_45_deg_and_diverge_fig_12():
    stiffness = {}
    for angle in (30.0, 40.0, 45.0, 50.0, 60.0):
        u = unit(True, angle)
        stiffness[angle] = u.slider_stiffness(u.equilibrium(np.zeros(5)))[0]
    lateral, vertical = stiffness[45.0]
    np.testing.assert_allclose(lateral, vertical, rtol=1e-12)
    lat = [stiffness[a][0] for a in sorted(stiffness)]
    ver = [stiffness[a][1] for a in sorted(stiffness)]
    assert np.all(np.diff(lat) < 0) and np.all(np.diff(ver) > 0)


def test_angle_change_raises_vertical_and_lowers_lateral_stiffness_conclusion_1():
    load = (0.0, -10000.0, 0.0, 0.0, 0.0)
    changing, constant = unit(True), unit(False)
    a, c = changing.equilibrium(load), constant.equilibrium(load)
    lateral_a, vertical_a = changing.unit_stiffness(a)
    lateral_c, vertical_c = constant.unit_stiffness(c)
    assert vertical_a > 1.05 * vertical_c and lateral_a < 0.98 * lateral_c
    assert abs(a.q[1]) < abs(c.q[1])  # less vertical deformation under the same load
    upper = changing.z > 0
    assert np.all(np.degrees(a.angles[upper]) > 45.0)  # the loaded rows steepen
    assert np.all(np.degrees(a.angles[~upper]) < 45.0)


def test_point_displacement_hand_calculation():
    q = np.array([1e-6, -2e-6, 3e-6, -4e-6, 5e-6])
    x, y, z = 0.1, -0.2, 0.3
    expected = (q[3] * z - q[4] * y, q[0] + q[4] * x - q[2] * z, q[1] + q[2] * y - q[3] * x)
    np.testing.assert_allclose(fu.point_displacement(q, (x, y, z)), expected, rtol=1e-14)


def test_generalized_load_hand_calculation():
    out = fu.generalized_load((100.0, 200.0, -300.0), (0.1, 0.2, 0.3), (1.0, 2.0, 3.0))
    # M = r x F + M0: (0.2 * -300 - 0.3 * 200, 0.3 * 100 - 0.1 * -300, 0.1 * 200 - 0.2 * 100)
    np.testing.assert_allclose(out, (200.0, -300.0, -120.0 + 1.0, 60.0 + 2.0, 0.0 + 3.0))


def test_model_takes_the_load_point_relative_to_the_travelled_table():
    model = fu.FeedUnitModel(unit(True))
    inputs = dict(F_x=0.0, F_y=0.0, F_z=-1000.0, point_x=0.05, point_y=0.0, point_z=0.1,
                  x_feed=0.08)
    moved = model.outputs(0.0, (), inputs)
    direct = model.outputs(0.0, (), {**inputs, "point_x": -0.03, "x_feed": 0.0})
    for key in moved:
        np.testing.assert_allclose(moved[key], direct[key], rtol=1e-10, atol=1e-18)
    assert moved["epsilon_y"] < 0.0  # load behind the centre tips the table's rear down


@pytest.mark.parametrize("changes, message", [
    (dict(balls_per_row=50), "sliders would overlap"),
    (dict(contact_angle=np.radians(95.0)), "contact_angle"),
    (dict(row_spacing_z=-1.0), "row_spacing_z"),
    (dict(balls_per_row=2.5), "balls_per_row"),
])
def test_bad_layout_is_refused_naming_the_field(changes, message):
    with pytest.raises(ValueError, match=message):
        layout(**changes)


def test_bad_fmu_parameters_are_refused_naming_them():
    base = dict(half_span_x=0.1, half_span_y=0.15, row_spacing_y=0.023, row_spacing_z=0.01,
                contact_angle=0.7, balls_per_row=12, pitch=4.8e-3, ball_diameter=4.7625e-3,
                conformity=0.52, preload=20.0, youngs_modulus=206e9, poisson_ratio=0.3,
                angle_change=True)
    for name, value in (("youngs_modulus", -1.0), ("poisson_ratio", 0.7), ("preload", 0.0),
                        ("conformity", 0.4)):
        with pytest.raises(ValueError, match=name):
            fu.from_parameters(**{**base, name: value})


@pytest.mark.parametrize("angle_change", [True, False])
def test_limiting_case_a_load_beyond_the_balls_stops_the_equilibrium_naming_it(angle_change):
    # 1e300 N: the Hertz loads overflow; the direct solve and the load steps are bounded
    with pytest.raises(ValueError, match=r"no static equilibrium.*1e\+300"):
        unit(angle_change).equilibrium([0.0, -1e300, 0.0, 0.0, 0.0])
