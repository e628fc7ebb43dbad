"""The physics checks of a record's motion (record_checks.py) and of its load (plausible.py):
each refusal names data.csv and what is wrong, each warning says what the record cannot show.
Hand-built motions, their distances and counts computed by hand."""
from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from guideway_fmu.diagnose import plausible, record_checks

SOURCE = Path("run") / "data.csv"


def _motion(v, step=1e-3):
    time = step * np.arange(v.size)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * step)])
    return SimpleNamespace(time=time, v=v, x=x)


def test_one_way_record_with_standstill_jitter_is_refused_by_distance_hand_count():
    # a trolley pulled one way (2.5 m/s for 1 s: 2.5 m) with tracking jitter at the stops: 40
    # "backward" samples at 0.24 m/s, 3.8 % of the moving samples (a count of samples passes a
    # 2 % rule), but 40 x 0.24 mm = 9.6 mm back: 0.4 % of the distance
    forward = np.full(1000, 2.5)
    jitter = np.concatenate([np.r_[-0.24, 0.0, 0.0] for _ in range(40)])
    v = np.concatenate([np.zeros(5), forward[:500], jitter, forward[500:], np.zeros(5)])
    motion = _motion(v)
    usable = v != 0.0
    assert np.sum(v < 0) / usable.sum() > 0.02
    with pytest.raises(ValueError, match=r"data.csv: the feed moves one way only \(2\.5 m forward, "
                                         r"0\.0096 m backward by the distance travelled; 40 of the "
                                         r"42 stretches .* jitter"):
        record_checks.direction(SOURCE, motion, usable)


def test_jitter_outnumbering_the_strokes_is_warned_about_and_strokes_both_ways_pass():
    stroke = np.r_[np.ones(500), -np.ones(500)]  # 0.5 m each way, hand trapezoid 0.4995 m
    jitter = np.concatenate([np.r_[0.05, -0.05] for _ in range(10)])
    usable_v = np.concatenate([stroke, jitter, stroke])
    motion = _motion(usable_v)
    notes = record_checks.direction(SOURCE, motion, usable_v != 0.0)
    assert len(notes) == 1 and "20 of the 24 stretches" in notes[0] and "not strokes" in notes[0]
    assert record_checks.direction(SOURCE, _motion(np.r_[stroke, stroke]), np.ones(2000, bool)) == []


def _strokes(per_stroke, count=10, dwell=()):
    """Velocity of ``count`` strokes of ``per_stroke`` samples each, alternating in direction,
    each followed by the samples ``dwell``."""
    return np.concatenate([np.r_[np.full(per_stroke, (-1.0) ** i), dwell] for i in range(count)])


@pytest.mark.parametrize("per_stroke, outcome", [(5, "refused"), (20, "warned"), (200, "quiet")])
def test_sampling_against_the_strokes_hand_count(per_stroke, outcome):
    v = _strokes(per_stroke)
    motion, usable = _motion(v), np.ones(v.size, bool)
    assert np.array_equal(record_checks.stroke_reversals(motion, usable),
                          per_stroke * np.arange(1, 10))
    if outcome == "refused":
        with pytest.raises(ValueError, match=r"data.csv: column 'time': 5 samples between reversals"):
            record_checks.sampling(SOURCE, motion, usable)
        return
    notes = record_checks.sampling(SOURCE, motion, usable)
    assert (len(notes) == 1 and "resolved by a few samples" in notes[0]) == (outcome == "warned")


def test_jitter_flickers_at_the_stops_are_not_reversals_of_a_well_sampled_record():
    # 100-sample strokes of 0.1 m with 20 samples of jitter (1e-4 m/s flickers, 1e-7 m each)
    # at each stop: 20 direction changes a stop, but a stroke reversal every 120 samples
    flicker = 1e-4 * (-1.0) ** np.arange(20)
    v = _strokes(100, dwell=flicker)
    motion, usable = _motion(v), np.ones(v.size, bool)
    assert np.count_nonzero(np.diff(np.sign(v))) > 150  # every flicker changes the direction
    # (a stop's last flicker may run on into the next stroke: one sample early)
    reversals = record_checks.stroke_reversals(motion, usable)
    assert reversals.size == 9 and np.all(np.abs(reversals - 120 * np.arange(1, 10)) <= 1)
    assert record_checks.sampling(SOURCE, motion, usable) == []


def _run(x):
    return SimpleNamespace(inputs=["feed_position"], columns={"feed_position": x},
                           time=1e-3 * np.arange(x.size))


def test_position_of_a_handful_of_levels_is_refused_and_a_coarse_one_warned():
    x = 0.05 * np.sin(np.linspace(0.0, 12 * np.pi, 6000))
    with pytest.raises(ValueError, match=r"column 'feed_position' takes steps of 0\.01 m, 10 levels"):
        record_checks.position_channel(SOURCE, _run(np.round(x / 0.01) * 0.01))
    notes = record_checks.position_channel(SOURCE, _run(np.round(x / 0.001) * 0.001))
    assert any("100 levels" in n and "not resolved" in n for n in notes)
    assert record_checks.position_channel(SOURCE, _run(np.round(x / 1e-6) * 1e-6)) == []


def test_a_position_held_for_two_samples_is_warned_about():
    x = 0.05 * np.sin(np.linspace(0.0, 12 * np.pi, 3000))
    notes = record_checks.position_channel(SOURCE, _run(np.repeat(x, 2)))
    assert any("repeats its previous value in 50%" in n and "about every 2 samples" in n
               for n in notes)


def test_friction_against_a_zero_normal_load_is_not_skipped_silently():
    run = SimpleNamespace(columns={"friction_force": np.ones(100)}, normal_load=lambda: 0.0)
    notes = plausible._force_scale(run, SOURCE)
    assert len(notes) == 1 and "normal load adds up to 0 N" in notes[0]
