"""Candidate friction laws and the horizontal rig (physics/rigs/friction_laws.py, horizontal.py)
against hand calculations, limiting cases and a numerical integration."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from guideway_fmu.physics.rigs import friction_laws as fl
from guideway_fmu.physics.rigs import horizontal


def test_stribeck_limits_by_hand():
    # far above v_s: F = -(F_c + c_v u) for u > 0; just above 0: F -> -F_s
    f = fl.stribeck_friction(np.array([1.0, -1.0, 1e-9]), 10.0, 15.0, 0.01, 3.0)
    assert f[0] == pytest.approx(-(10.0 + 3.0 * 1.0), rel=1e-12)
    assert f[1] == pytest.approx(10.0 + 3.0, rel=1e-12)
    assert f[2] == pytest.approx(-15.0, rel=1e-9)


def test_stribeck_at_stribeck_velocity_hand_calculation():
    # u = v_s: level = F_c + (F_s - F_c) e^-1; shear-thinning viscous c_v u^0.5
    f = fl.stribeck_friction(0.04, 10.0, 20.0, 0.04, 2.0, 0.0, 2.0, 0.5)
    assert f == pytest.approx(-(10.0 + 10.0 * math.exp(-1.0) + 2.0 * math.sqrt(0.04)), rel=1e-12)


def test_dahl_update_matches_numerical_integration_of_dahl_ode():
    # dz/dx = (1 - z) / delta for increasing x, from z0 = -0.5 over dx = 3 delta
    delta, z0, dx = 2e-6, -0.5, 6e-6
    ode = solve_ivp(lambda x, z: (1.0 - z) / delta, (0.0, dx), [z0], rtol=1e-11, atol=1e-13)
    assert fl.dahl_update(z0, dx, delta) == pytest.approx(ode.y[0, -1], rel=1e-8)


def test_dahl_state_limiting_cases():
    x = np.array([0.0, 1.0, 2.0, 1.0, 1.0])  # displacements far beyond delta: Coulomb switching
    z = fl.dahl_state(x, 1e-6, z0=0.0)
    np.testing.assert_allclose(z, [0.0, 1.0, 1.0, -1.0, -1.0], atol=1e-12)
    assert fl.dahl_state(x, np.array([1e-6, 1e-3])).shape == (5, 2)


def test_dahl_state_in_closed_form_per_run_equals_the_step_by_step_update():
    # a random walk of encoder counts with stops and a still start: the closed form over each run
    # of one direction must reproduce dahl_update applied step by step (the FMU's steps)
    x = np.r_[np.zeros(20), np.cumsum(np.random.default_rng(4).integers(-2, 3, 2000)) * 1e-6]
    x[500:560] = x[499]
    distances = np.array([1e-6, 5e-6, 3e-5])
    stepwise = np.empty((x.size, 3))
    stepwise[0] = 0.3
    for k in range(1, x.size):
        stepwise[k] = fl.dahl_update(stepwise[k - 1], x[k] - x[k - 1], distances)
    np.testing.assert_allclose(fl.dahl_state(x, distances, z0=0.3), stepwise, rtol=0, atol=1e-13)


def test_running_distance_and_preload_factor_by_hand():
    d = fl.running_distance([0.0, 0.2, 0.1, 0.4])
    np.testing.assert_allclose(d, [0.0, 0.2, 0.3, 0.6])
    # 1 - 0.3 (1 - e^-2) at D = 2 wear distances
    assert fl.preload_loss_factor(2.0, 0.3, 1.0) == pytest.approx(1 - 0.3 * (1 - math.exp(-2)))


def test_wear_law_is_the_preload_of_the_wear_model_at_its_initial_rate_limiting_case():
    # the preload-loss law "wear" takes the preload deformation down at a steady rate; the
    # fractal-creep model (physics/wear/raceway_wear.py) starts at that rate and slows as the balls unload:
    # the two agree to first order in the distance (0.02 % at 1 % of the loss distance, 0.6 %
    # at 5 %), and the law falls faster after
    from guideway_fmu.physics.wear import raceway_wear
    guide = raceway_wear.Guide(wear_coefficient=0.5)
    q0 = guide.state(0.0, (0.0, 0.0))["preload"]
    loss_distance = guide.preload_deformation / (guide.wear_rate(q0) / 2)  # dw/dD = rate / 2
    for share, tolerance in ((0.01, 5e-4), (0.05, 8e-3)):
        d = share * loss_distance
        preload = guide.state(0.0, guide.advance(0.0, (0.0, 0.0), d))["preload"]
        law = fl.preload_loss_factor(d, 1.0, loss_distance, "wear", 1.5)
        assert law == pytest.approx(preload / q0, rel=tolerance)
        assert law <= preload / q0
    # 0.3 of the level carried by a preload gone at D = 2: at D = 1 the factor is by hand
    assert fl.preload_loss_factor(1.0, 0.3, 2.0, "wear", 10 / 9) == pytest.approx(
        1 - 0.3 * (1 - 0.5 ** (10 / 9)))
    assert fl.preload_loss_factor(3.0, 0.3, 2.0, "wear") == pytest.approx(0.7)  # gone: flat


def test_table_factor_interpolates_equally_spaced_nodes_by_hand():
    # nodes at 0, 0.5, 1.0 with factors 1, 2, 0: at 0.25 -> 1.5, at 0.75 -> 1.0, held outside
    np.testing.assert_allclose(fl.table_factor([0.25, 0.75, -1.0, 2.0], 0.0, 1.0, [1.0, 2.0, 0.0]),
                               [1.5, 1.0, 1.0, 0.0])
    f = fl.position_dependent_friction(-0.1, 0.25, 4.0, 0.0, 1.0, [1.0, 2.0, 0.0])
    assert f == pytest.approx(4.0 * 1.5)
    f = fl.ball_to_ball_friction(0.1, 0.75, 4.0, 0.0, 1.0, [1.0, 2.0, 0.0])
    assert f == pytest.approx(-4.0 * 1.0)


def test_horizontal_rig_drive_force_hand_calculation():
    # drive = m a - F_friction + offset: 2 kg at 3 m/s2 against friction -5 N (opposing +u)
    assert horizontal.drive_force(3.0, -5.0, 2.0, 0.5) == pytest.approx(6.0 + 5.0 + 0.5)
    assert horizontal.friction_force(-5.0, 0.5) == pytest.approx(5.5)


# -- the continuous-time models of the friction FMUs -------------------------------------------
COULOMB = {"coefficient": 0.01, "rollers_per_groove": 10, "velocity_tolerance": 1e-4}
LOADS = {"F_upper": 100.0, "F_lower": 50.0}  # level 0.01 * 2 * 10 * 150 = 30 N


def test_dahl_model_derivative_is_the_limit_of_its_exact_path_update_numerical_derivative():
    model = fl.DahlModel(1e-5, 1e-4, 1e-3, 0.3, 0.2, 0.0, **COULOMB)
    z = np.array([0.2, -0.5, 0.9])
    for u in (0.02, -0.03):
        dt = 1e-9
        finite = (model.update(z, u * dt) - z) / dt
        np.testing.assert_allclose(model.derivatives(0.0, z, {**LOADS, "u": u}), finite,
                                   rtol=1e-4)


def test_dahl_model_force_at_saturation_is_the_coulomb_level_hand_calculation():
    model = fl.DahlModel(1e-5, 1e-4, 1e-3, 0.3, 0.2, 0.0, **COULOMB)
    out = model.outputs(0.0, np.ones(3), {**LOADS, "u": 0.1})
    assert out["F_friction"] == pytest.approx(-30.0, rel=1e-12)
    assert model.initial_state(0.0, {}) == (0.0, 0.0, 0.0)


def test_running_distance_models_integrate_the_speed_hand_calculation():
    loss = fl.PreloadLossModel(0.4, 2.0, **COULOMB)
    assert loss.derivatives(0.0, (1.0,), {**LOADS, "u": -0.3}) == (0.3,)
    at = loss.outputs(0.0, (2.0,), {**LOADS, "u": 1.0})["F_friction"]
    assert at == pytest.approx(-30.0 * (1.0 - 0.4 * (1.0 - np.exp(-1.0))), rel=1e-9)
    table = fl.BallToBallModel(table_start=0.0, table_end=1.0, factors="1 3",
                                             **COULOMB)
    assert table.state_scales() == (1.0,)
    assert table.outputs(0.0, (0.5,), {**LOADS, "u": 1.0})["F_friction"] == pytest.approx(-60.0)


@pytest.mark.parametrize("make, message", [
    (lambda: fl.DahlModel(0.0, 1e-4, 1e-3, 0.0, 0.0, 0.0, **COULOMB),
     "presliding_distance"),
    (lambda: fl.DahlModel(1e-5, 1e-4, 1e-3, 0.6, 0.5, 0.0, **COULOMB), "third_share"),
    (lambda: fl.StribeckModel(0.01, -1.0, 2.0, 0.0, 1.0, **COULOMB),
     "stribeck_velocity"),
    (lambda: fl.PreloadLossModel(0.2, 0.0, **COULOMB), "wear_distance"),
    (lambda: fl.PreloadLossModel(0.2, 1.0, "table", profile="0 0.6 0.4 1", **COULOMB), "profile"),
    (lambda: fl.PreloadLossModel(0.2, 1.0, "table", profile="0 0.5 0.9", **COULOMB), "profile"),
    (lambda: fl.PreloadLossModel(0.2, 1.0, "linear", **COULOMB), "law"),
    (lambda: fl.PositionTableModel(0.0, 1.0, "1 x", **COULOMB), "factors"),
    (lambda: fl.PositionTableModel(1.0, 1.0, "1 2", **COULOMB), "table_end"),
    (lambda: fl.StribeckModel(0.01, 0.01, 2.0, 0.0, 1.0,
                                            **{**COULOMB, "rollers_per_groove": 0}),
     "rollers_per_groove"),
])
def test_effect_models_refuse_bad_parameters_naming_them(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_preload_table_law_interpolates_its_profile_hand_value():
    # nodes at 0, 1, 2 m; D = 0.75 m lies three quarters up the first ramp (g = 0.375), and
    # beyond the last node the whole loss stays
    profile = (0.0, 0.5, 1.0)
    assert fl.preload_loss_factor(0.75, 0.4, 2.0, "table", profile=profile) == pytest.approx(0.85)
    assert fl.preload_loss_factor(3.0, 0.4, 2.0, "table", profile=profile) == pytest.approx(0.6)
