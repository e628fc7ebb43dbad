"""Checks of the prescribed feed motions against independent references."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from guideway_fmu.physics.rigs.feed_motion import (BiHarmonic, Constant, Oscillating, Table,
                                                   Trapezoid, make_profile)

RAMP_TABLE = Table(time=(0.0, 0.05, 0.12, 0.2, 0.31), velocity=(0.1, 0.3, -0.2, -0.25, 0.05))

# (profile, times where u or a have a kink or jump)
PROFILES = {
    "biharmonic": (BiHarmonic(), []),
    "oscillating": (Oscillating(), []),
    "constant": (Constant(), []),
    "trapezoid": (Trapezoid(t_start=0.05), [0.05, 0.15, 0.05 + 1 / 3, 0.05 + 13 / 30]),
    "triangle": (Trapezoid(distance=-0.01, t_start=0.02),
                 [0.02, 0.02 + 0.1 / 3**0.5, 0.02 + 0.2 / 3**0.5]),
    "table": (RAMP_TABLE, list(RAMP_TABLE.time)),
}


def _times_away_from(kinks, h):
    t = np.linspace(0.0, 0.6, 241)[1:]
    if kinks:
        t = t[np.min(np.abs(t[:, None] - np.array(kinks)[None, :]), axis=1) > 10 * h]
    return t


@pytest.mark.parametrize("name", PROFILES)
def test_central_finite_difference_of_x_and_u(name):
    profile, kinks = PROFILES[name]
    h = 1e-6
    t = _times_away_from(kinks, h)
    x, u, a = profile.evaluate(t)
    x_plus, u_plus, _ = profile.evaluate(t + h)
    x_minus, u_minus, _ = profile.evaluate(t - h)
    np.testing.assert_allclose((x_plus - x_minus) / (2 * h), u, rtol=0, atol=1e-8)
    np.testing.assert_allclose((u_plus - u_minus) / (2 * h), a, rtol=0, atol=1e-6)


@pytest.mark.parametrize("name", PROFILES)
def test_x_equals_scipy_quad_of_u(name):
    profile, kinks = PROFILES[name]
    for t_end in (0.013, 0.137, 0.29, 0.55):
        points = [k for k in kinks if 0.0 < k < t_end] or None
        reference, _ = quad(lambda s: profile.evaluate(s)[1], 0.0, t_end,
                            points=points, epsabs=1e-13, epsrel=1e-12)
        assert profile.evaluate(t_end)[0] == pytest.approx(reference, abs=1e-11)


def test_scalar_time_gives_floats_and_array_keeps_shape():
    x, u, a = Oscillating().evaluate(0.1)
    assert all(isinstance(v, float) for v in (x, u, a))
    t = np.zeros((3, 2))
    for profile, _ in PROFILES.values():
        assert all(v.shape == (3, 2) for v in profile.evaluate(t))


def test_biharmonic_at_zero_by_hand():
    p = BiHarmonic()
    x, u, _ = p.evaluate(0.0)
    assert x == 0.0
    assert u == pytest.approx(0.2919 * math.sin(2.0588) + 0.0178 * math.sin(1.2679), rel=1e-14)


def test_biharmonic_has_period_one_over_f():
    p = BiHarmonic(frequency=7.0)
    t = np.linspace(0.0, 0.3, 101)
    # zero-mean velocity, so even the position repeats
    for now, later in zip(p.evaluate(t), p.evaluate(t + 1 / 7.0)):
        np.testing.assert_allclose(later, now, rtol=0, atol=1e-12)


def test_biharmonic_fft_has_energy_only_at_f_and_3f():
    p = BiHarmonic()
    periods, per_period = 4, 64
    n = periods * per_period
    t = np.arange(n) / (per_period * p.frequency)
    spectrum = np.fft.rfft(p.evaluate(t)[1])
    amplitude = 2 * np.abs(spectrum) / n
    assert amplitude[periods] == pytest.approx(p.amplitude1, rel=1e-12)
    assert amplitude[3 * periods] == pytest.approx(p.amplitude2, rel=1e-12)
    rest = np.delete(amplitude, [periods, 3 * periods])
    assert np.max(rest) < 1e-14


def test_oscillating_by_hand_at_quarter_period():
    p = Oscillating()
    _, u, a = p.evaluate(1 / (4 * p.frequency))
    assert u == pytest.approx(0.2375 - 0.25, abs=1e-15)
    assert a == pytest.approx(0.0, abs=1e-12)
    # over one period the sine averages out: x = u_bar / f
    assert p.evaluate(1 / p.frequency)[0] == pytest.approx(0.2375 / 5.0, rel=1e-13)


def test_constant_by_hand():
    assert Constant().evaluate(2.0) == (pytest.approx(0.58), 0.29, 0.0)


def test_trapezoid_reaches_distance_with_peak_v_max_by_hand():
    p = Trapezoid()
    # 0.1 m at 0.3 m/s plus one ramp time 0.3 / 3 s
    assert p.duration == pytest.approx(0.1 / 0.3 + 0.3 / 3.0, rel=1e-14)
    t = np.linspace(0.0, p.duration, 2001)
    x, u, a = p.evaluate(t)
    assert x[-1] == pytest.approx(0.1, rel=1e-14)
    assert np.max(u) == pytest.approx(0.3, rel=1e-14)
    assert np.max(np.abs(a)) == 3.0
    assert np.all(np.diff(x) >= 0)


def test_trapezoid_triangular_peak_is_sqrt_distance_times_a_max_by_hand():
    p = Trapezoid(distance=0.01, v_max=0.3, a_max=3.0)
    peak = math.sqrt(0.01 * 3.0)
    assert p.duration == pytest.approx(2 * peak / 3.0, rel=1e-14)
    t = np.linspace(0.0, p.duration, 2001)  # odd count: the middle sample is the peak
    x, u, _ = p.evaluate(t)
    assert np.max(u) == pytest.approx(peak, rel=1e-12)
    assert np.max(u) < 0.3
    assert x[-1] == pytest.approx(0.01, rel=1e-14)


def test_trapezoid_negative_distance_moves_backwards_as_mirror_image():
    forward, backward = Trapezoid(distance=0.1), Trapezoid(distance=-0.1)
    t = np.linspace(-0.1, 0.6, 57)
    for f, b in zip(forward.evaluate(t), backward.evaluate(t)):
        np.testing.assert_array_equal(b, -f)
    assert backward.evaluate(1.0)[0] == pytest.approx(-0.1)


def test_trapezoid_at_rest_before_start_and_after_end():
    p = Trapezoid(t_start=0.2)
    before = np.linspace(-1.0, 0.2, 7)[:-1]
    after = np.linspace(0.2 + p.duration, 5.0, 7)
    x, u, a = p.evaluate(before)
    assert np.all(x == 0) and np.all(u == 0) and np.all(a == 0)
    x, u, a = p.evaluate(after)
    np.testing.assert_allclose(x, 0.1, rtol=1e-14)
    assert np.all(u == 0) and np.all(a == 0)


def test_table_linear_ramp_reproduced_exactly_by_hand():
    accel = 2.5
    time = np.linspace(0.0, 1.0, 11)
    p = Table(time=time, velocity=accel * time)
    t = np.array([0.0, 0.033, 0.25, 0.5, 0.77, 0.999])
    x, u, a = p.evaluate(t)
    np.testing.assert_allclose(x, 0.5 * accel * t**2, rtol=1e-14, atol=1e-16)
    np.testing.assert_allclose(u, accel * t, rtol=1e-14, atol=1e-16)
    np.testing.assert_allclose(a, accel, rtol=1e-12)


def test_table_holds_end_values_outside_by_hand():
    p = Table(time=(1.0, 2.0, 3.0), velocity=(0.5, 1.5, 1.0))
    x, u, a = p.evaluate(np.array([-2.0, 0.5, 1.0]))
    np.testing.assert_array_equal(x, 0.0)
    np.testing.assert_array_equal(u, 0.5)
    np.testing.assert_array_equal(a, [0.0, 0.0, 1.0])
    # area up to 3 s: (0.5 + 1.5)/2 + (1.5 + 1.0)/2 = 2.25, then 1.0 m/s
    x, u, a = p.evaluate(np.array([3.0, 5.0]))
    np.testing.assert_allclose(x, [2.25, 4.25], rtol=1e-15)
    np.testing.assert_array_equal(u, 1.0)
    np.testing.assert_array_equal(a, 0.0)


@pytest.mark.parametrize("column", ["feed_velocity", "u"])
def test_table_from_csv_round_trip_through_temporary_file(tmp_path, column):
    time = np.linspace(0.0, 0.4, 9)
    velocity = 0.3 * np.sin(2 * np.pi * 5 * time) + 0.01
    path = tmp_path / "rig.csv"
    rows = [f"1.0,{float(t)!r},{float(v)!r}" for t, v in zip(time, velocity)]
    lines = [f"force,time,{column}"] + rows
    path.write_text("\n".join(lines) + "\n")
    p = Table.from_csv(path)
    assert p == Table(time=time, velocity=velocity)
    assert make_profile("table", path=str(path)) == p


@pytest.mark.parametrize("body, row, column", [
    ("time,speed\n0,1\n1,2\n", 1, "feed_velocity"),
    ("velocity,u\n0,1\n1,2\n", 1, "time"),
    ("time,u\n0,0.1\n0.1,nan\n0.2,0.3\n", 3, "u"),
    ("time,feed_velocity\n0,0.1\n0.1,0.2\n0.1,0.3\n", 4, "time"),
    ("time,feed_velocity\n0,0.1\n0.1,0.2\n0.05,0.3\n", 4, "time"),
    ("time,u\n0,0.1\n\n0.1,0.2\n0.2,abc\n", 5, "u"),
    ("time,u\n0,0.1\n0.1\n", 3, "u"),
])
def test_table_from_csv_refusal_names_file_row_and_column(tmp_path, body, row, column):
    path = tmp_path / "broken_rig.csv"
    path.write_text(body)
    with pytest.raises(ValueError) as info:
        Table.from_csv(path)
    message = str(info.value)
    assert "broken_rig.csv" in message
    assert f"row {row}" in message
    assert column in message


def test_table_from_csv_refuses_single_data_row(tmp_path):
    path = tmp_path / "short.csv"
    path.write_text("time,u\n0,1\n")
    with pytest.raises(ValueError, match="short.csv.*2 data rows"):
        Table.from_csv(path)


@pytest.mark.parametrize("kwargs, fragment", [
    ({"time": (0.0, 1.0, 1.0), "velocity": (0, 0, 0)}, r"Table\.time\[2\]"),
    ({"time": (0.0, np.inf, 2.0), "velocity": (0, 0, 0)}, r"Table\.time\[1\]"),
    ({"time": (0.0, 1.0, 2.0), "velocity": (0, 0, np.nan)}, r"Table\.velocity\[2\]"),
    ({"time": (0.0, 1.0, 2.0), "velocity": (0, 0)}, r"Table\.velocity"),
    ({"time": (0.0,), "velocity": (0.0,)}, r"Table\.time"),
])
def test_table_validate_names_field_and_first_bad_index(kwargs, fragment):
    with pytest.raises(ValueError, match=fragment):
        Table(**kwargs)


@pytest.mark.parametrize("cls, kwargs, field", [
    (BiHarmonic, {"frequency": -5.0}, "BiHarmonic.frequency"),
    (BiHarmonic, {"amplitude1": float("nan")}, "BiHarmonic.amplitude1"),
    (Oscillating, {"frequency": 0.0}, "Oscillating.frequency"),
    (Oscillating, {"amplitude": float("nan")}, "Oscillating.amplitude"),
    (Constant, {"velocity": float("inf")}, "Constant.velocity"),
    (Trapezoid, {"v_max": 0.0}, "Trapezoid.v_max"),
    (Trapezoid, {"v_max": -0.3}, "Trapezoid.v_max"),
    (Trapezoid, {"a_max": 0.0}, "Trapezoid.a_max"),
    (Trapezoid, {"t_start": -1.0}, "Trapezoid.t_start"),
])
def test_validate_refuses_bad_values_naming_the_field(cls, kwargs, field):
    with pytest.raises(ValueError, match=field):
        cls(**kwargs)
    cls().validate()  # the defaults pass


def test_make_profile_builds_named_classes_with_keywords():
    assert make_profile("Oscillating", frequency=3.0) == Oscillating(frequency=3.0)
    assert make_profile("trapezoid", distance=-0.2) == Trapezoid(distance=-0.2)
    assert make_profile("biharmonic") == BiHarmonic()
    assert make_profile("constant", velocity=0.1) == Constant(0.1)


def test_make_profile_refuses_unknown_name_listing_valid_names():
    with pytest.raises(ValueError, match="sawtooth") as info:
        make_profile("sawtooth")
    for name in ("biharmonic", "oscillating", "constant", "trapezoid", "table"):
        assert name in str(info.value)


def test_make_profile_refuses_unknown_keyword_naming_it():
    with pytest.raises(ValueError, match="'speed'"):
        make_profile("constant", speed=0.1)
    with pytest.raises(ValueError, match="'frequency'"):
        make_profile("table", path="x.csv", frequency=5.0)
