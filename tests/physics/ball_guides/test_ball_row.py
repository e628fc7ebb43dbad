"""A row of balls over time (physics/ball_guides/ball_row.py) against hand calculations, the two-ball closed
form of eq. 30, limiting cases and conservation of the row's clearance."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from guideway_fmu.physics.ball_guides import ball_row
from guideway_fmu.physics.ball_guides import ball_to_ball as bb
from guideway_fmu.physics.dynamics import rk4_step
from support import returns

THETA = np.radians(2.0)
RADIUS = 5e-3


def row(balls=2, zone=None, deviations=(-THETA, THETA, 0.0, 0.0), amplitude=0.0, **extra):
    zone = zone or balls * 2 * RADIUS + 1e-3
    return ball_row.from_parameters(
        RADIUS, 0.56, 2.1e11, 0.28, 0.1, np.radians(45.0), balls, zone, *deviations,
        amplitude, extra.get("wavelength", 0.02), extra.get("velocity_tolerance", 1e-4))


def loads(model, rho=-0.6, normal=100.0, u=0.01, x=0.0):
    """Inputs giving a pair of balls at -p, p N_x = rho N_y and -rho N_y (p = D/2)."""
    # N_x = M p / (N L^2 / 12) at p = -D/2 of two balls
    moment = -rho * normal * model.zone_length ** 2 / (3 * model.diameter)
    return {"u": u, "x": x, "F_normal": 2 * normal, "F_side": 0.0, "M_yaw": moment}


def touching(model):
    """Ball 1 at -D/2, ball 2 against it in front."""
    return np.array([-0.5, 0.5]) * model.diameter


def test_touching_pair_pushes_with_the_two_ball_closed_form_of_eq_30():
    model = row()
    inputs = loads(model)
    state = touching(model)
    expected = bb.analytical(bb.TwoBallCase(bb.Bearing(RADIUS, 0.56, 2.1e11, 0.28, 0.1,
                                                       np.radians(45.0), 0.01),
                                            ((-THETA, THETA, 0, 0),) * 2, 100.0, -0.6))
    out = model.outputs(0.0, state, inputs)
    assert out["contact_force"] == pytest.approx(expected["contact_force"], rel=1e-9)
    assert out["groups"] == 1
    # power balance: the carriage's friction work is the contacts' loss (eq. 32)
    assert -out["F_friction"] * inputs["u"] == pytest.approx(out["friction_loss"], rel=1e-6)
    assert out["friction_loss"] == pytest.approx(expected["friction_loss"], rel=1e-6)


def test_gap_closes_at_the_hand_calculated_time_then_the_pair_pushes():
    model = row()
    inputs = loads(model)
    gap = 1e-7  # the balls travel gap / (eps1 - eps2) = 20 um meanwhile: loads stay put
    state = touching(model) + [-gap / 2, gap / 2]
    eps1, eps2 = model.row(state, inputs).epsilon
    assert eps1 > eps2  # ball 1 behind and faster
    t_close = gap / ((eps1 - eps2) * inputs["u"] / 2)  # hand calculation
    sol = solve_ivp(lambda t, y: model.derivatives(t, y, inputs), (0, 1.5 * t_close), state,
                    dense_output=True, rtol=1e-10, atol=1e-14, max_step=t_close / 200)
    assert model.gaps(sol.sol(0.98 * t_close))[0] == pytest.approx(0.02 * gap, abs=2e-3 * gap)
    after = sol.sol(1.2 * t_close)
    assert abs(model.gaps(after)[0]) < 1e-3 * gap
    assert model.outputs(0.0, after, inputs)["contact_force"] > 0


def test_reversed_motion_parts_the_pair_limiting_case():
    model = row()
    inputs = loads(model, u=-0.01)
    out = model.outputs(0.0, touching(model), inputs)
    assert out["contact_force"] == 0.0 and out["groups"] == 2
    rates = np.diff(model.derivatives(0.0, touching(model), inputs))
    assert rates[0] > 0  # the gap opens


def test_ideal_grooves_roll_every_ball_at_half_speed_without_contact_force_limiting_case():
    model = row(balls=6, deviations=(0.0, 0.0, 0.0, 0.0))
    inputs = {"u": 0.2, "x": 0.3, "F_normal": 600.0, "F_side": 30.0, "M_yaw": 1.0}
    state = np.array(model.initial_state(0.0, inputs))
    assert np.allclose(model.derivatives(0.0, state, inputs), -0.1, rtol=0, atol=1e-15)
    assert model.outputs(0.0, state, inputs)["F_friction"] == 0.0


def test_unloaded_row_keeps_its_spacing_limiting_case():
    model = row(balls=4, amplitude=np.radians(1.0))
    inputs = {"u": 0.2, "x": 0.0, "F_normal": 0.0, "F_side": 0.0, "M_yaw": 0.0}
    state = model.initial_state(0.0, inputs)
    assert np.ptp(model.derivatives(0.0, state, inputs)) == 0.0
    assert model.outputs(0.0, state, inputs)["contact_force"] == 0.0


@pytest.mark.slow
def test_groove_wave_makes_contacts_form_and_break_and_conserves_the_clearance():
    model = row(balls=12, zone=12 * 2 * RADIUS + 0.6e-3, amplitude=np.radians(1.0))
    inputs = {"u": 0.1, "x": 0.0, "F_normal": 1200.0, "F_side": 0.0, "M_yaw": -2.0}

    def rates(t, y):
        return model.derivatives(t, y, dict(inputs, x=0.1 * t))

    y0 = model.initial_state(0.0, inputs)
    sol = solve_ivp(rates, (0, 0.6), y0, max_step=1e-3, rtol=1e-8, atol=1e-12, dense_output=True)
    times = np.linspace(0, 0.6, 121)
    forces = np.array([model.outputs(t, sol.sol(t), dict(inputs, x=0.1 * t))["contact_force"]
                       for t in times])
    clearance = [model.gaps(sol.sol(t)).sum() for t in times]
    assert np.allclose(clearance, model.zone_length - 12 * model.diameter, rtol=0, atol=1e-12)
    assert forces.max() > 1.0
    contact = forces > 0
    assert np.any(np.diff(contact.astype(int)) == 1) and np.any(np.diff(contact.astype(int)) == -1)


def test_side_load_beyond_four_point_contact_is_refused_naming_the_inputs():
    model = row()
    inputs = loads(model, rho=-1.5)
    with pytest.raises(ValueError, match="F_side, M_yaw"):
        model.outputs(0.0, touching(model), inputs)


@pytest.mark.parametrize("changes, name", [({"zone": 0.019}, "zone_length"),
                                           ({"balls": 1}, "balls"),
                                           ({"wavelength": 0.0}, "wavelength")])
def test_bad_row_parameters_are_refused_by_name(changes, name):
    with pytest.raises(ValueError, match=name):
        row(**changes)


def closing_gap(model, inputs, gap=1e-7):
    """A state of touching balls with one gap [m] between the first two, and the time [s] that
    gap takes to close (by hand: gap over the relative speed of their contact points)."""
    state = touching(model) + [-gap / 2, gap / 2]
    eps1, eps2 = model.row(state, inputs).epsilon
    return state, gap / ((eps1 - eps2) * inputs["u"] / 2)


@pytest.mark.slow
def test_advance_across_a_closing_gap_matches_a_tight_adaptive_integration():
    # one call of advance over 3 t_c (the hand-calculated closing time) against RK45 at
    # rtol 1e-12 with steps of t_c / 1000: the event-located substeps land on it to well below
    # the error of one plain RK4 step across the jump
    model = row()
    inputs = loads(model)
    state, t_c = closing_gap(model, inputs)
    h = 3 * t_c
    exact = solve_ivp(lambda t, y: model.derivatives(t, y, inputs), (0, h), state, rtol=1e-12,
                      atol=1e-18, max_step=t_c / 1000).y[:, -1]
    plain = np.abs(rk4_step(model, 0.0, state, inputs, h) - exact).max()
    located = np.abs(model.advance(0.0, state, inputs, h) - exact).max()
    assert plain > 1e-9  # the jump costs a plain step a share of the gap
    assert located < 1e-3 * plain
    assert model.gaps(model.advance(0.0, state, inputs, h))[0] <= ball_row.CLOSED


def test_limiting_case_a_feed_speed_beyond_the_substep_bound_is_refused_naming_it():
    # 1e6 m/s over 1 ms: 1e3 m of travel in substeps of 0.05 D = 5e-4 m, 2e6 substeps (more than
    # MAX_SUBSTEPS); 1e300 m/s took substeps of 5e-304 s without end
    model = row()
    inputs = loads(model, u=1e6)
    with returns(), pytest.raises(ValueError, match="substeps"):
        model.advance(0.0, touching(model), inputs, 1e-3)


def test_limiting_case_group_changes_beyond_the_substep_bound_are_refused(monkeypatch):
    # the gap of the hand calculation above closes within the step, which ends the first
    # substep there: a second one is needed, and one is allowed here
    monkeypatch.setattr(ball_row, "MAX_SUBSTEPS", 1)
    model = row()
    inputs = loads(model)
    gap = 1e-7
    state, t_close = closing_gap(model, inputs, gap)
    with pytest.raises(ValueError, match="groups change too often"):
        model.advance(0.0, state, inputs, 1.5 * t_close)
    monkeypatch.undo()  # allowed two, the same step passes the gap's closing
    assert abs(model.gaps(model.advance(0.0, state, inputs, 1.5 * t_close))[0]) < 1e-3 * gap
