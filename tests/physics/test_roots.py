"""The shared solves of physics/roots.py against hand calculations and limiting cases."""
import math

import numpy as np

from guideway_fmu.physics.roots import load_steps, newton_system


def _circle_line(load):
    """x^2 + y^2 = 2 load^2 and x = y: the root (load, load) by hand."""
    return (lambda v: np.array([v[0] ** 2 + v[1] ** 2 - 2 * load**2, v[0] - v[1]]),
            lambda v: np.array([[2 * v[0], 2 * v[1]], [1.0, -1.0]]))


def test_newton_finds_the_hand_root_and_reports_the_error_left():
    residual, jacobian = _circle_line(3.0)
    x, error = newton_system(residual, jacobian, [2.0, 1.0], 1e-12, 50)
    np.testing.assert_allclose(x, [3.0, 3.0], rtol=1e-12)
    assert error <= 1e-12


def test_newton_stops_at_its_iteration_bound_and_at_a_singular_jacobian():
    residual, jacobian = _circle_line(3.0)
    _, error = newton_system(residual, jacobian, [2.0, 1.0], 0.0, 1)  # one step: not there yet
    assert error > 1e-3
    x, error = newton_system(residual, jacobian, [0.0, 0.0], 1e-12, 50)  # J singular at 0
    assert error == math.inf and np.all(x == 0.0)


def test_load_steps_reach_the_root_a_direct_solve_from_far_misses_limiting_case():
    # atan(x) = 1: Newton from x = 10 overshoots far and diverges; from 0 in load steps
    # each step starts within reach, and the root is tan(load) by hand
    def solve(load, start):
        return newton_system(lambda x: np.arctan(x) - load, lambda x: np.diag(1.0 / (1.0 + x**2)),
                             start, 1e-13, 50)

    with np.errstate(over="ignore", invalid="ignore"):  # the direct solve runs off to inf
        _, direct = solve(np.array([1.0]), np.array([10.0]))
        x, error = load_steps(solve, np.array([1.0]), np.array([10.0]), 1e-13, 64)
    assert not direct <= 1e-13
    np.testing.assert_allclose(x, [math.tan(1.0)], rtol=1e-12)
    assert error <= 1e-13
