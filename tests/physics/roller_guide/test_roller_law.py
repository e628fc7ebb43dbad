"""Checks of the roller contact law F = k delta^(10/9) (Soleimanian et al. 2020, eq. 2) and Palmgren's k."""
import numpy as np
import pytest

from guideway_fmu.physics.roller_guide import four_rows
from guideway_fmu.physics.roller_guide import roller_law as rc
from guideway_fmu.physics.roller_guide.roller_law import OpposedRows

ROLLER_LENGTH = 8.0e-3  # m, Soleimanian et al. (2020) Table 2
# Palmgren by hand, two contacts in series, l = 8 mm:
# delta[mm] = 2 * 3.84e-5 Q^0.9 / 8^0.8 = 7.68e-5 / 5.278032 Q^0.9 = 1.455088e-5 Q^0.9,
# so Q = (1e3 delta[m] / 1.455088e-5)^(1/0.9) = k delta^(10/9), k = (6.872437e7)^(1/0.9) = 5.10388e8.
K_HAND = (1e3 * (ROLLER_LENGTH * 1e3) ** 0.8 / (2 * 3.84e-5)) ** (1 / 0.9)
DELTAS = np.geomspace(1e-9, 1e-5, 25)  # m, from far below to far above the preload approach


def test_palmgren_stiffness_hand_calculation():
    assert K_HAND == pytest.approx(5.10e8, rel=2e-3)
    assert rc.palmgren_stiffness(ROLLER_LENGTH) == pytest.approx(K_HAND, rel=1e-12)


def test_palmgren_stiffness_hand_calculation_single_contact():
    # One contact deflects half as much: k_1 = k_2 * 2^(1/0.9).
    assert rc.palmgren_stiffness(ROLLER_LENGTH, contacts_in_series=1) == pytest.approx(
        K_HAND * 2 ** (1 / 0.9), rel=1e-12)


@pytest.mark.parametrize("delta", [0.0, -0.0, -1e-12, -1e-6, -1.0, -np.inf])
def test_contact_force_limiting_case_no_approach_gives_exactly_zero(delta):
    force = rc.contact_force(delta, K_HAND)
    stiffness = rc.contact_stiffness(delta, K_HAND)
    assert force == 0.0 and not np.isnan(force)
    assert stiffness == 0.0 and not np.isnan(stiffness)


def test_contact_force_limiting_case_mixed_array_keeps_shape_and_zeros():
    delta = np.array([-2e-6, 0.0, 1e-6])
    force = rc.contact_force(delta, K_HAND)
    assert force.shape == delta.shape
    assert np.array_equal(force[:2], [0.0, 0.0])
    assert force[2] == pytest.approx(K_HAND * 1e-6 ** (10 / 9), rel=1e-12)


def test_contact_stiffness_numerical_derivative():
    step = 1e-6 * DELTAS
    central = (rc.contact_force(DELTAS + step, K_HAND)
               - rc.contact_force(DELTAS - step, K_HAND)) / (2 * step)
    np.testing.assert_allclose(rc.contact_stiffness(DELTAS, K_HAND), central, rtol=1e-8)


def test_approach_for_load_inverts_contact_force():
    loads = rc.contact_force(DELTAS, K_HAND)
    np.testing.assert_allclose(rc.approach_for_load(loads, K_HAND), DELTAS, rtol=1e-12)
    forces = np.geomspace(1e-3, 1e4, 25)
    np.testing.assert_allclose(
        rc.contact_force(rc.approach_for_load(forces, K_HAND), K_HAND), forces, rtol=1e-12)


@pytest.mark.parametrize("load", [0.0, -5.0])
def test_approach_for_load_limiting_case_no_load_gives_zero(load):
    assert rc.approach_for_load(load, K_HAND) == 0.0


def test_palmgren_stiffness_refuses_bad_length_naming_it():
    with pytest.raises(ValueError, match="roller_length"):
        rc.palmgren_stiffness(0.0)


def test_opposed_rows_hand_calculation_both_rows_and_an_opened_row():
    rows = OpposedRows(force_1um=1000.0, exponent=10 / 9, sine=0.5, approach_upper=2e-6,
                       approach_lower=1e-6, rate_upper=1e-3, rate_lower=-2e-3)
    # y = 1e-6, tau = 0: d_U = 2.5 um, d_L = 0.5 um
    assert rows.force(1e-6) == pytest.approx(1000.0 * (2.5 ** (10 / 9) - 0.5 ** (10 / 9)), rel=1e-14)
    # tau = 1e-4 s: d_U = 2.6 um, d_L = 0.3 um
    assert rows.force(1e-6, 1e-4) == pytest.approx(1000.0 * (2.6 ** (10 / 9) - 0.3 ** (10 / 9)),
                                                   rel=1e-14)
    # y = 3e-6: d_L = -0.5 um, the lower row is open and carries nothing
    assert rows.force(3e-6) == pytest.approx(1000.0 * 3.5 ** (10 / 9), rel=1e-14)


@pytest.mark.parametrize("y", [-3e-6, 0.0, 1e-6, 4e-6])
def test_opposed_rows_stiffness_matches_numerical_derivative(y):
    rows = OpposedRows(force_1um=1000.0, exponent=10 / 9, sine=0.5, approach_upper=2e-6,
                       approach_lower=1e-6)
    dy = 1e-12
    assert rows.stiffness(y) == pytest.approx((rows.force(y + dy) - rows.force(y - dy)) / (2 * dy),
                                              rel=1e-6)


def test_opposed_rows_of_the_guideway_kernel_equal_its_net_force_with_moved_films():
    kernel = four_rows.RowKernel(four_rows.Guideway())
    rows = kernel.rows(3e-7, 2e-7, 1e-3, -5e-4)
    for y in (-2e-6, 0.0, 5e-7, 3e-6):
        assert rows.force(y) == pytest.approx(kernel.contact(y, 3e-7, 2e-7)[0], rel=1e-12)
        assert rows.force(y, 1e-4) == pytest.approx(kernel.contact(y, 4e-7, 1.5e-7)[0], rel=1e-12)
        assert rows.stiffness(y) == pytest.approx(kernel.contact(y, 3e-7, 2e-7)[1], rel=1e-12)
