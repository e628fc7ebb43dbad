"""Checks of the guideway friction models by hand calculation and limiting cases."""
import math

import numpy as np
import pytest

from guideway_fmu.physics.roller_guide import friction as fr
from guideway_fmu.physics.roller_guide.greenwood_tripp import Surface

PARAMS = fr.MixedFrictionParams()
LOAD = 115.0  # N per roller

# Hand values for one 115 N contact with the default (Soleimanian et al. 2020, Table 2/3) parameters:
# w' = 115 / 8e-3 = 14375 N/m, b = sqrt(8 w' R / (pi E')) = sqrt(8 * 14375 * 2.5e-3 / (pi * 2e11))
# = 2.13909e-5 m, A = 2 b l = 3.42254e-7 m^2, p_mean = 115 / A = 3.36007e8 Pa,
# tau_L = 2e6 + 0.047 * 3.36007e8 = 1.77923e7 Pa.
AREA = 3.42254e-7
TAU_L = 1.77923e7


def test_contact_friction_limiting_case_zero_load_gives_zero():
    boundary, viscous = fr.contact_friction(np.zeros(3), np.array([0.0, 1e-7, 1e-6]), 0.25, PARAMS)
    assert np.all(boundary == 0.0) and np.all(viscous == 0.0)
    total, b, v = fr.mixed_ehl_friction(0.0, 0.0, 0.0, 0.0, 0.25, PARAMS)
    assert total == 0.0 and b == 0.0 and v == 0.0


def test_contact_boundary_friction_hand_calculation_at_zero_film():
    # lambda = 0: W_a = p_a(0) A = 4.25311e7 * 3.42254e-7 = 14.5565 N (below the 115 N load),
    # A_a = pi^2 (n beta sigma)^2 A F_2(0) = 9.869604 * 1.3286025e-3 * 3.42254e-7 * 0.5 = 2.24395e-9 m^2,
    # F_b = tau_l0 A_a + beta_m W_a = 2e6 * 2.24395e-9 + 0.047 * 14.5565 = 4.4879e-3 + 0.684155 = 0.688642 N.
    boundary, _ = fr.contact_friction(LOAD, 0.0, 0.25, PARAMS)
    assert boundary == pytest.approx(0.688642, rel=1e-5)


def test_contact_viscous_friction_hand_calculation_couette():
    # h = 2e-6 m (lambda = 4.4, A_a / A < 1e-8): tau_v = mu_0 |u| / h = 0.195 * 0.25 / 2e-6
    # = 24375 Pa << tau_L, F_v = tau_v A = 24375 * 3.42254e-7 = 8.34244e-3 N.
    for u in (0.25, -0.25):
        _, viscous = fr.contact_friction(LOAD, 2e-6, u, PARAMS)
        assert viscous == pytest.approx(8.34244e-3, rel=1e-5)


def test_contact_viscous_friction_limiting_case_thin_film_bounded_by_tau_l():
    h = np.concatenate([np.geomspace(1e-6, 1e-15, 200), [0.0]])
    _, viscous = fr.contact_friction(LOAD, h, 0.25, PARAMS)
    assert np.all(np.isfinite(viscous))
    assert np.all(viscous <= TAU_L * AREA * (1.0 + 1e-5))
    # Couette range (h above mu_0 u / tau_L = 0.195 * 0.25 / 1.77923e7 = 2.7e-9 m): grows as 1/h.
    couette = h > 1e-8
    assert np.all(np.diff(viscous[couette]) > 0.0)
    # At h = 0, F_v = tau_L (A - A_a) = 1.77923e7 * (3.42254e-7 - 2.24395e-9) = 6.04958 N,
    # and the limit h -> 0+ reaches the same value (continuity).
    assert viscous[-1] == pytest.approx(6.04958, rel=1e-5)
    assert viscous[-2] == pytest.approx(viscous[-1], rel=1e-6)


def test_contact_boundary_friction_limiting_case_thick_film_negligible():
    thin, _ = fr.contact_friction(LOAD, 0.0, 0.25, PARAMS)
    thick, _ = fr.contact_friction(LOAD, 4.5 * PARAMS.surface.roughness, 0.25, PARAMS)
    assert thick < 1e-3 * thin


def test_mixed_friction_sum_over_rollers_hand_calculation():
    # 2N = 40 upper and 40 lower contacts; at u = 1 m/s, tanh(1 / 1e-4) = 1.
    b_one, v_one = fr.contact_friction(LOAD, 3e-7, 1.0, PARAMS)
    total, boundary, viscous = fr.mixed_ehl_friction(LOAD, LOAD, 3e-7, 3e-7, 1.0, PARAMS)
    assert boundary == pytest.approx(-80.0 * b_one, rel=1e-12)
    assert viscous == pytest.approx(-80.0 * v_one, rel=1e-12)
    assert total == pytest.approx(boundary + viscous, rel=1e-12)


def test_mixed_friction_sign_test_opposes_velocity():
    u = np.array([-0.25, -0.01, 0.01, 0.25])
    load = np.full(4, LOAD)
    h = np.full(4, 2e-7)
    total, boundary, viscous = fr.mixed_ehl_friction(load, 0.8 * load, h, h, u, PARAMS)
    for force in (total, boundary, viscous):
        assert np.all(force * u < 0.0)
        assert force[0] == pytest.approx(-force[3]) and force[1] == pytest.approx(-force[2])


def test_mixed_friction_continuous_through_zero_velocity():
    u = np.linspace(-1e-3, 1e-3, 4001)  # steps of 5e-7 m/s, tolerance 1e-4 m/s
    total, _, _ = fr.mixed_ehl_friction(LOAD, LOAD, 1e-7, 1e-7, u, PARAMS)
    assert total[2000] == 0.0
    assert np.max(np.abs(np.diff(total))) < 0.01 * np.max(np.abs(total))


def test_coulomb_friction_hand_calculation():
    # mu 2N (F_U + F_L) = 0.005 * 40 * (115 + 115) = 46 N, opposing u.
    params = fr.CoulombParams()
    assert fr.coulomb_friction(LOAD, LOAD, 0.5, params) == pytest.approx(-46.0, rel=1e-12)
    assert fr.coulomb_friction(LOAD, LOAD, -0.5, params) == pytest.approx(46.0, rel=1e-12)
    # Regularised switch: tanh(5e-5 / 1e-4) = 0.462117 of the full value.
    assert fr.coulomb_friction(LOAD, LOAD, 5e-5, params) == pytest.approx(-46.0 * math.tanh(0.5))


def test_coulomb_friction_exact_sign_without_tolerance():
    params = fr.CoulombParams(velocity_tolerance=0.0)
    forces = fr.coulomb_friction(LOAD, LOAD, np.array([-1e-9, 0.0, 1e-9]), params)
    np.testing.assert_array_equal(forces, [46.0, 0.0, -46.0])


@pytest.mark.parametrize("name", ["F_upper", "F_lower"])
def test_negative_load_raises_naming_argument(name):
    loads = {"F_upper": LOAD, "F_lower": LOAD, name: np.array([1.0, -1.0])}
    with pytest.raises(ValueError, match=name):
        fr.coulomb_friction(loads["F_upper"], loads["F_lower"], 0.1, fr.CoulombParams())
    with pytest.raises(ValueError, match=name):
        fr.mixed_ehl_friction(loads["F_upper"], loads["F_lower"], 1e-7, 1e-7, 0.1, PARAMS)
    with pytest.raises(ValueError, match="load"):
        fr.contact_friction(-1.0, 1e-7, 0.1, PARAMS)


def test_default_params_are_valid():
    PARAMS.validate()
    fr.CoulombParams().validate()


@pytest.mark.parametrize(
    "params, field",
    [
        (fr.MixedFrictionParams(rollers_per_groove=0), "rollers_per_groove"),
        (fr.MixedFrictionParams(rollers_per_groove=2.5), "rollers_per_groove"),
        (fr.MixedFrictionParams(viscosity=-0.1), "viscosity"),
        (fr.MixedFrictionParams(roller_radius=float("inf")), "roller_radius"),
        (fr.MixedFrictionParams(surface=Surface(roughness=float("nan"))), "roughness"),
        (fr.CoulombParams(rollers_per_groove=0), "rollers_per_groove"),
        (fr.CoulombParams(coefficient=-0.005), "coefficient"),
        (fr.CoulombParams(velocity_tolerance=float("nan")), "velocity_tolerance"),
    ],
)
def test_invalid_params_raise_naming_field(params, field):
    with pytest.raises(ValueError, match=field):
        params.validate()
