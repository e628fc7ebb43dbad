"""The 5-DOF ball carriage (physics/ball_guides/carriage_5dof.py) against Wu et al. (2012): Table 3's 1-D
point-to-point frequencies from Tables 1 and 2, the paper's closed forms, its Table 2 from the
Hertz route, numerical derivatives of the ball forces, and the time-domain model's small
oscillations against the eigenvalues."""
from __future__ import annotations

import numpy as np
import pytest

from guideway_fmu.physics.ball_guides import carriage_5dof as bc
from guideway_fmu.physics.dynamics import rk4_step

BODY = bc.CarriageBody(mass=0.313, inertia=(9.938e-5, 6.136e-5, 1.394e-4),
                       contact_angle=np.radians(45.0), d=7.37e-3, e=10.3e-3)  # Table 1
#: the layout that reproduces Table 3: 9 balls per row over the 43 mm load zone (Table 2 lists 9)
PER_ROW, PITCH = 9, 43e-3 / 9
TABLE2 = {  # K_n1..K_n9 [N/m] at M_y [N m]
    0.0: [17.8e6] * 9,
    1.45: [15.7e6, 16.3e6, 16.8e6, 17.3e6, 17.8e6, 18.2e6, 18.6e6, 19.0e6, 19.4e6],
    2.90: [12.9e6, 14.5e6, 15.7e6, 16.8e6, 17.8e6, 18.6e6, 19.4e6, 20.2e6, 20.8e6],
    4.35: [7.6e6, 12.0e6, 14.5e6, 16.3e6, 17.8e6, 19.0e6, 20.2e6, 21.2e6, 22.1e6],
}
TABLE3 = {0.0: (2.10e3, 3.16e3, 3.60e3, 5.08e3), 1.45: (2.08e3, 3.12e3, 3.61e3, 5.06e3),
          2.90: (2.03e3, 2.99e3, 3.66e3, 5.03e3)}  # 1-D point-to-point column [Hz]


def table2_modes(moment):
    positions = bc.ball_positions(PER_ROW, PITCH)
    k = np.concatenate([TABLE2[moment], TABLE2[moment]])
    stiffness = bc.stiffness_matrix(bc.contact_directions(BODY, positions), k)
    return bc.modes(stiffness, BODY.mass_matrix())


@pytest.mark.parametrize("moment", sorted(TABLE3))
def test_table3_one_d_frequencies_from_tables_1_and_2_published_numbers(moment):
    found = table2_modes(moment)
    assert found.frequencies[0] == 0.0  # the rigid lateral-roll motion of two rows (eq. A13)
    np.testing.assert_allclose(found.frequencies[1:], TABLE3[moment], rtol=0.01)


@pytest.mark.parametrize("moment", sorted(TABLE2))
def test_eigenproblem_equals_the_papers_closed_forms_cross_check(moment):
    positions = bc.ball_positions(PER_ROW, PITCH)
    closed = bc.paper_frequencies(BODY, positions, TABLE2[moment])
    np.testing.assert_allclose(table2_modes(moment).frequencies[1:],
                               [closed[k] for k in ("f_RYL", "f_PVL", "f_PVH", "f_RYH")], rtol=1e-9)


def test_symmetric_load_gives_uncoupled_modes_and_a_moment_couples_them():
    free = table2_modes(0.0)
    assert [free.label(i) for i in range(5)] == ["rigid", "yawing", "pitching", "vertical", "rolling"]
    assert free.participation[2, bc.DOF.index("v")] < 1e-12  # pitching alone
    loaded = table2_modes(2.90)
    # Wu et al., Fig. 13: under M_y the pitching and vertical modes each move both theta and v
    for mode in (2, 3):
        share = loaded.participation[mode]
        assert min(share[bc.DOF.index("v")], share[bc.DOF.index("theta")]) > 0.1


def hertz_balls(preload_approach=3.926e-6):
    """The Hertz route with the preload whose Table 2 row at 1.45 N m fits best (least squares
    over the 9 balls, rest stiffness 17.8e6 N/m): delta_0 = 3.93 um, Q_0 = 46.6 N."""
    k_h = 17.8e6 / (1.5 * np.sqrt(preload_approach))
    return bc.HertzBalls(BODY, bc.ball_positions(PER_ROW, PITCH), k_h, k_h * preload_approach**1.5)


@pytest.mark.parametrize("moment, tolerance", [(1.45, 0.01), (2.90, 0.04)])
def test_hertz_route_reproduces_table2_fitted_at_one_moment_published_numbers(moment, tolerance):
    # fitted at 1.45 N m, reported at 2.90 N m (held out); at 4.35 N m the most unloaded ball
    # nears contact loss and differs by 32 % (10.0 against 7.6 MN/m), the others within 2.4 MN/m
    balls = hertz_balls()
    k = np.sort(balls.ball_stiffness(balls.equilibrium([0, 0, 0, moment, 0]))[:PER_ROW])
    np.testing.assert_allclose(k, TABLE2[moment], rtol=tolerance)


def test_hertz_route_frequencies_under_moment_match_table3_published_numbers():
    balls = hertz_balls()
    q = balls.equilibrium([0, 0, 0, 2.90, 0])
    found = bc.modes(balls.tangent(q), BODY.mass_matrix())
    np.testing.assert_allclose(found.frequencies[1:], TABLE3[2.90], rtol=0.015)


def test_tangent_stiffness_is_the_derivative_of_the_ball_forces_numerical_derivative():
    balls = hertz_balls()
    q = np.array([1e-7, -2e-7, 3e-6, 1e-5, -2e-5])  # any displacement with every ball in contact
    assert np.all(balls.approaches(q) > 0.0)
    step = 1e-10
    numerical = np.column_stack([(balls.restoring(q + step * e) - balls.restoring(q - step * e))
                                 / (2 * step) for e in np.eye(5)])
    np.testing.assert_allclose(-numerical, balls.tangent(q), rtol=1e-5, atol=1e-3)


def test_equilibrium_balances_the_load_and_refuses_the_unresisted_motion():
    balls = hertz_balls()
    load = np.array([0.0, -30.0, 0.0, 1.0, 0.4])
    q = balls.equilibrium(load)
    np.testing.assert_allclose(balls.restoring(q), -load, atol=1e-8)
    with pytest.raises(ValueError, match="no ball resists"):
        balls.equilibrium([10.0, 0, 0, 0, 0])  # a bare lateral force drives the rigid mode
    with pytest.raises(ValueError, match="more than the balls can carry"):
        balls.equilibrium([0, 0, 0, 200.0, 0])


def test_time_domain_small_oscillation_has_the_eigenfrequency_limiting_case():
    model = bc.BallCarriageModel(BODY, PER_ROW, PITCH, ball_stiffness=TABLE2[0.0])
    inputs = dict.fromkeys(bc.LOADS, 0.0) | {"u_feed": 0.0, "preload": 0.0}
    state = np.array(model.initial_state(0.0, inputs))
    state[1] = 1e-8  # vertical offset: the vertical mode alone (uncoupled at M_y = 0)
    h, v = 2e-6, []
    for n in range(2000):
        v.append(state[1])
        state = rk4_step(model, n * h, state, inputs, h)
    v = np.array(v)
    crossings = np.flatnonzero(np.sign(v[:-1]) != np.sign(v[1:]))
    t = crossings * h - v[crossings] * h / (v[crossings + 1] - v[crossings])
    frequency = (len(t) - 1) / (2 * (t[-1] - t[0]))
    assert frequency == pytest.approx(table2_modes(0.0).frequencies[3], rel=2e-3)


def test_feed_motion_moves_the_balls_by_half_the_travel_hand_calculation():
    model = bc.BallCarriageModel(BODY, PER_ROW, PITCH, ball_stiffness=TABLE2[0.0])
    rates = model.derivatives(0.0, np.zeros(11),
                              dict.fromkeys(bc.LOADS, 0.0) | {"u_feed": 0.3, "preload": 0.0})
    assert rates[10] == 0.15
    np.testing.assert_allclose(bc.ball_positions(PER_ROW, PITCH, PITCH),
                               bc.ball_positions(PER_ROW, PITCH)[[-1, *range(PER_ROW - 1)]],
                               atol=1e-15)


@pytest.mark.parametrize("make, name", [
    (lambda: bc.CarriageBody(0.0, (1, 1, 1), 0.7, 0.01, 0.01), "mass"),
    (lambda: bc.CarriageBody(1.0, (1, 1), 0.7, 0.01, 0.01), "inertia"),
    (lambda: bc.CarriageBody(1.0, (1, 1, 1), 2.0, 0.01, 0.01), "contact_angle"),
    (lambda: bc.ball_positions(0, 1e-3), "per_row"),
    (lambda: bc.BallCarriageModel(BODY, 9, PITCH, ball_stiffness=[1e7] * 8), "ball_stiffness"),
    (lambda: bc.BallCarriageModel(BODY, 9, PITCH), "either"),
])
def test_bad_carriage_input_is_refused_naming_it(make, name):
    with pytest.raises(ValueError, match=name):
        make()


@pytest.mark.parametrize("load, message", [
    ([0.0, float("nan"), 0.0, 0.0, 0.0], "load"),  # returned q = NaN before: NaN passed the check
    ([0.0, 1e300, 0.0, 0.0, 0.0], "more than the balls can carry"),  # lifts every lower ball
])
def test_limiting_case_a_load_without_equilibrium_is_refused_naming_it(load, message):
    with pytest.raises(ValueError, match=message):
        hertz_balls().equilibrium(load)


def test_rigid_direction_stretches_no_ball_and_is_the_stiffness_null_space_hand_calculation():
    positions = bc.ball_positions(PER_ROW, PITCH)
    directions = bc.contact_directions(BODY, positions)
    rigid = bc.rigid_direction(BODY)
    np.testing.assert_allclose(bc.approach_change(directions, rigid), 0.0, atol=1e-18)
    stiffness = bc.stiffness_matrix(directions, np.concatenate([TABLE2[2.90], TABLE2[2.90]]))
    values, vectors = np.linalg.eigh(stiffness)
    assert values[0] < 1e-9 * values[-1]  # one rigid mode, and it is this direction
    np.testing.assert_allclose(abs(vectors[:, 0] @ rigid), 1.0, rtol=1e-9)


def test_linear_springs_balance_a_load_as_the_linear_solve_limiting_case():
    model = bc.BallCarriageModel(BODY, PER_ROW, PITCH, ball_stiffness=TABLE2[1.45])
    inputs = dict(F_y=0.0, F_z=-40.0, M_x=0.0, M_y=1.2, M_z=-0.3, u_feed=0.0, preload=0.0)
    q = np.array(model.initial_state(0.0, inputs)[:5])
    stiffness = bc.stiffness_matrix(bc.contact_directions(BODY, bc.ball_positions(PER_ROW, PITCH)),
                                    model.linear)
    expected = np.linalg.lstsq(stiffness, model.load(inputs), rcond=None)[0]  # minimum norm
    np.testing.assert_allclose(q, expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())
