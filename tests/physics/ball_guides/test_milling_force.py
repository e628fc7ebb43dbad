"""The end-milling force source against hand calculations and the closed-form mean forces."""
import numpy as np
import pytest

from guideway_fmu.physics.ball_guides import milling_force as mf

COEFFS = dict(K_tc=800e6, K_rc=170e6, K_ac=220e6, K_te=28e3, K_re=31e3, K_ae=2e3)


def mill(entry=0.0, exit_=np.pi, teeth=3, **changes):
    values = dict(spindle_speed=200.0, teeth=teeth, axial_depth=2e-3, entry_angle=entry,
                  exit_angle=exit_, **COEFFS)
    values.update(changes)
    return mf.EndMill(**values)


def mean_force_closed_form(m: mf.EndMill, c: float) -> np.ndarray:
    # the per-revolution average of the force on the tool, integrated by hand over the
    # immersion: (N a c / 8 pi)[K_tc cos 2phi - K_rc (2 phi - sin 2phi)] + (N a / 2 pi)
    # [-K_te sin phi + K_re cos phi] along x, likewise along y and z, between entry and exit
    # (Altintas 2012, ch. 2)
    a, n = m.axial_depth, m.teeth

    def at(phi):
        fx = (n * a * c / (8 * np.pi) * (m.K_tc * np.cos(2 * phi) - m.K_rc * (2 * phi - np.sin(2 * phi)))
              + n * a / (2 * np.pi) * (-m.K_te * np.sin(phi) + m.K_re * np.cos(phi)))
        fy = (n * a * c / (8 * np.pi) * (m.K_tc * (2 * phi - np.sin(2 * phi)) + m.K_rc * np.cos(2 * phi))
              - n * a / (2 * np.pi) * (m.K_te * np.cos(phi) + m.K_re * np.sin(phi)))
        fz = n * a / (2 * np.pi) * (-m.K_ac * c * np.cos(phi) + m.K_ae * phi)
        return np.array([fx, fy, fz])

    return at(m.exit_angle) - at(m.entry_angle)


@pytest.mark.parametrize("entry, exit_", [(0.0, np.pi), (0.0, np.pi / 2), (np.pi / 2, np.pi),
                                          (0.3, 1.2)], ids=["slot", "up", "down", "partial"])
def test_mean_force_over_a_revolution_matches_the_closed_form_integral(entry, exit_):
    m = mill(entry, exit_)
    t = (np.arange(200_000) + 0.5) / 200_000 / m.spindle_speed  # one revolution, midpoints
    on_table = m.force_on_table(t, 0.1).mean(axis=1)
    expected = -mean_force_closed_form(m, m.feed_per_tooth(0.1))
    np.testing.assert_allclose(on_table, expected, rtol=2e-4, atol=1e-3)


def test_one_tooth_at_ninety_degrees_hand_calculation():
    # phi = pi/2: h = c, the tangential force points along +y on the tool, the radial along -x
    m = mill(teeth=1, start_angle=np.pi / 2)
    c = m.feed_per_tooth(0.1)
    f_t = 800e6 * 2e-3 * c + 28e3 * 2e-3
    f_r = 170e6 * 2e-3 * c + 31e3 * 2e-3
    f_a = 220e6 * 2e-3 * c + 2e3 * 2e-3
    np.testing.assert_allclose(m.force_on_table(0.0, 0.1), (f_r, -f_t, -f_a), rtol=1e-12)


def test_force_repeats_at_the_tooth_passing_period():
    m = mill(start_angle=0.1)
    t = np.linspace(0.0, 0.01, 101)
    np.testing.assert_allclose(m.force_on_table(t + 1 / 600, 0.1), m.force_on_table(t, 0.1),
                               rtol=1e-9, atol=1e-9)


def test_no_depth_no_force_and_no_feed_leaves_the_edge_forces_limiting_cases():
    t = np.linspace(0.0, 0.01, 57)
    assert np.all(mill(axial_depth=0.0).force_on_table(t, 0.1) == 0.0)
    edge_only = mill(K_tc=0.0, K_rc=0.0, K_ac=0.0)
    np.testing.assert_allclose(mill().force_on_table(t, 0.0), edge_only.force_on_table(t, 0.3))


@pytest.mark.parametrize("changes, message", [
    (dict(spindle_speed=0.0), "spindle_speed"), (dict(teeth=0), "teeth"),
    (dict(axial_depth=-1e-3), "axial_depth"), (dict(exit_angle=4.0), "exit_angle"),
    (dict(entry_angle=2.0, exit_angle=1.0), "exit_angle"), (dict(K_tc=float("nan")), "K_tc"),
])
def test_bad_parameters_are_refused_naming_them(changes, message):
    with pytest.raises(ValueError, match=message):
        mill(**changes)
