"""The choice of criterion and the statistics verdict (guideway_fmu.reference.criterion) on
synthetic regular and chaotic signals."""
import numpy as np
import pytest

from guideway_fmu.reference import criterion, statistics


def logistic(x0: float, n: int, r: float = 3.9) -> np.ndarray:
    """The logistic map x <- r x (1 - x) from x0: chaotic at r = 3.9 (Lyapunov exponent ~0.5
    per iterate, so a 1e-9 difference of x0 reaches order one within ~40 iterates)."""
    x = np.empty(n)
    x[0] = x0
    for i in range(1, n):
        x[i] = r * x[i - 1] * (1 - x[i - 1])
    return x


def test_relative_error_by_hand():
    # reference 0, 1, 0, 1 (range 1); error 0.1 everywhere: RMS 0.1, peak 0.1; a constant
    # reference 2 with error 0.2 is measured against its magnitude: 0.1
    assert criterion.relative_error([0.1, 1.1, 0.1, 1.1], [0, 1, 0, 1]) == pytest.approx((0.1, 0.1))
    assert criterion.relative_error([2.2, 2.2], [2.0, 2.0]) == pytest.approx((0.1, 0.1))


def test_a_regular_signal_is_judged_pointwise_and_a_chaotic_one_by_statistics():
    # independent check: a sine whose phase is disturbed by 1e-9 moves by ~1e-9 of its range;
    # the logistic map from a start disturbed by 1e-9 decorrelates (its differences are of the
    # order of its range, ~0.3)
    t = np.linspace(0.0, 1.0, 5001)
    sine = {k: np.sin(2 * np.pi * 50 * t + phase) for k, phase in (("ref", 0), ("a", 1e-9), ("b", -2e-9))}
    chosen, spreads, reason = criterion.choose(sine["ref"], {"a": sine["a"], "b": sine["b"]})
    assert chosen == "pointwise" and max(spreads.values()) < 1e-8 and "predictable" in reason
    x0 = 0.3
    chaos = {k: logistic(x0 * (1 + d), 5000) for k, d in (("ref", 0), ("a", 1e-9), ("b", 1e-10))}
    chosen, spreads, reason = criterion.choose(chaos["ref"], {"a": chaos["a"], "b": chaos["b"]})
    assert chosen == "statistics" and min(spreads.values()) > 0.1 and "unpredictable" in reason


@pytest.mark.parametrize("amplitude, expected", [(0.5e-3, "pointwise"), (2e-3, "statistics")])
def test_the_threshold_is_a_tenth_of_the_tolerance(amplitude, expected):
    # a disturbed copy that differs by a square wave of +-amplitude x range has an RMS
    # difference of exactly that amplitude: below 1e-3 pointwise, above it statistics
    ref = np.tile([0.0, 1.0], 100)
    moved = ref + amplitude * np.tile([1.0, -1.0], 100)
    assert criterion.choose(ref, {"a": moved, "b": ref})[0] == expected


def test_statistics_pass_a_differently_started_chaotic_run_and_fail_a_changed_system():
    # another start of the same map is an equally valid run: its statistics fall within K spreads
    # of the reference's (the spread measured by two other starts); the map at r = 3.8 is a
    # different system, and its distribution differs far beyond (its q50 by 0.09 by measurement, against spreads under 0.004)
    n, period = 20000, 10.0
    t = np.arange(n, dtype=float)
    ref, *disturbed = (logistic(0.3 * (1 + d), n) for d in (0.0, 1e-9, -1e-9))
    other, changed = logistic(0.3 * (1 + 3e-9), n), logistic(0.3, n, r=3.8)
    peaks = statistics.spectral_peaks(t, ref)[0]

    def judged(run):
        return criterion.judge_statistics(
            statistics.load_statistics(t, run, period, peaks),
            statistics.load_statistics(t, ref, period, peaks),
            [statistics.load_statistics(t, d, period, peaks) for d in disturbed],
            float(np.ptp(ref)), 1.0 / n)

    assert all(s["passed"] for s in judged(other).values()), judged(other)
    failed = [name for name, s in judged(changed).items() if not s["passed"]]
    assert "q50" in failed and "cycle_min_mean" in failed, judged(changed)
