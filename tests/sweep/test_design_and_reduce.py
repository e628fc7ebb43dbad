"""Designs of experiments and reduced outputs, against counts and hand calculations."""

import numpy as np
import pytest

from guideway_fmu.cosim.recording import Recording
from guideway_fmu.sweep import design
from guideway_fmu.sweep.reduce import Output, dominant_frequency, envelope, peak, rms


def test_factorial_is_every_combination_once():
    levels = {"A.a": [1.0, 2.0, 3.0], "B.b": [10.0, 20.0], "C.c": ["x", "y"]}
    points = design.factorial(levels)
    assert len(points) == 3 * 2 * 2
    # independent: the combinations written out by nested loops
    expected = {(a, b, c) for a in levels["A.a"] for b in levels["B.b"] for c in levels["C.c"]}
    assert {(p["A.a"], p["B.b"], p["C.c"]) for p in points} == expected


def test_latin_hypercube_puts_one_point_in_each_bin_of_every_parameter():
    n, ranges = 12, {"A.a": (2.0, 5.0), "B.b": (-1.0, 1.0), "C.c": (1e3, 1e4)}
    points = design.latin_hypercube(ranges, n, seed=3)
    assert len(points) == n
    for name, (low, high) in ranges.items():
        values = np.array([p[name] for p in points])
        assert np.all((values >= low) & (values < high))
        bins = np.floor((values - low) / (high - low) * n).astype(int)
        assert sorted(bins) == list(range(n)), name  # each of the n bins hit exactly once
    assert design.latin_hypercube(ranges, n, seed=3) == points  # the seed fixes the design
    assert design.latin_hypercube(ranges, n, seed=4) != points


def test_point_id_depends_on_the_experiment_and_the_values_not_their_order():
    experiment = {"stop": 0.05, "step": 4e-6}
    a = design.point_id("rig", experiment, {"A.a": 1.0, "B.b": 2.0})
    assert a == design.point_id("rig", dict(experiment), {"B.b": 2.0, "A.a": 1.0})
    assert a != design.point_id("rig", {**experiment, "stop": 0.1}, {"A.a": 1.0, "B.b": 2.0})
    assert a != design.point_id("rig", experiment, {"A.a": 1.0, "B.b": 2.5})


def _sine(amplitude=3.0, frequency=50.0, offset=0.0, rate=5000.0, periods=10):
    t = np.arange(int(periods * rate / frequency) + 1) / rate
    return t, offset + amplitude * np.sin(2 * np.pi * frequency * t)


def test_rms_of_a_sine_is_its_amplitude_over_root_two_also_unevenly_sampled():
    t, x = _sine(amplitude=3.0)
    assert rms(t, x) == pytest.approx(3.0 / np.sqrt(2), rel=1e-9)  # hand calculation: A / sqrt 2
    # uneven samples weigh by time: every other interval ten times shorter, the same answer
    fine = np.sort(np.concatenate([t, t[:-1] + 0.1 * np.diff(t)]))
    assert rms(fine, 3.0 * np.sin(2 * np.pi * 50.0 * fine)) == pytest.approx(3.0 / np.sqrt(2), rel=1e-3)


def test_peak_and_envelope_of_an_offset_sine():
    t, x = _sine(amplitude=2.0, offset=-5.0, periods=3)
    assert peak(t, x) == pytest.approx(7.0, rel=1e-6)  # |offset| + amplitude
    assert envelope(t, x) == pytest.approx(4.0, rel=1e-6)  # 2 amplitude


def test_dominant_frequency_of_a_sampled_sine_between_bins():
    rate, span, f0 = 10000.0, 0.1, 437.3  # bins of 10 Hz: 437.3 Hz lies 0.73 of a bin past 430
    t = np.arange(int(span * rate)) / rate
    x = 0.4 + np.sin(2 * np.pi * f0 * t) + 0.1 * np.sin(2 * np.pi * 1500.0 * t)
    assert abs(dominant_frequency(t, x) - f0) < 0.05 * 10.0  # within 5 % of a bin of the truth


def test_the_settle_time_leaves_the_transient_out():
    t, x = _sine(amplitude=1.0, frequency=100.0, rate=10000.0, periods=20)  # a sample at each crest
    x = x + 50.0 * (t < 0.02)  # a transient over the first 20 ms
    rec = Recording(t, {"A.x": x}, {"A.x": "N"})
    assert Output("A.x", "peak").of(rec) == pytest.approx(51.0, rel=1e-3)
    assert Output("A.x", "peak", settle=0.02).of(rec) == pytest.approx(1.0, rel=1e-3)
    assert Output("A.x", "envelope", settle=0.02).column == "envelope(A.x)"
    with pytest.raises(ValueError, match=r"peak\(A.x\): 1 recorded samples after the settle"):
        Output("A.x", "peak", settle=t[-1]).of(rec)
