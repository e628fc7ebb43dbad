"""Checks of a horizontal record's motion that look at the physics, not the units (those are
plausible.py's): whether the record can show what the workflow fits. Each check either refuses
(ValueError naming data.csv, the column and what is wrong) or returns warnings, plain sentences
the report and diagnosis.json carry.

- Direction: the Coulomb level and the force offset are told apart only by motion both ways, so
  each direction must carry ONE_WAY of the distance travelled (not of the samples: video
  tracking jitter at standstill makes many short "backward" samples that travel nothing).
  Direction changes whose stretch travels less than JITTER of the stroke are jitter or
  vibration, not strokes, and are reported where they outnumber the strokes.
- Sampling against the motion: a stroke needs MIN_PER_STROKE samples for the reversal to be
  seen at all (refused below), FEW_PER_STROKE to resolve the build-up after it (warned below).
- The position channel: quantised to steps so coarse that it holds fewer than COARSE levels over
  its span (warned: pre-sliding below a step and the derived acceleration are not resolved;
  refused below MIN_LEVELS), or held, repeating its previous value in HELD of the moving samples
  (updated less often than the time base: the derived velocity steps).
"""
from __future__ import annotations

import numpy as np

from .signals import Motion, sampling_step

JITTER = 0.01  # share of the stroke under which a one-direction stretch is jitter, not a stroke
#: jitter stretches warned about from this many on, and only where they outnumber the strokes (a
#: few flickers of the direction at a dwell's ends are normal)
JITTER_COUNT = 5
#: least share of the distance travelled each direction must carry: a direction travelling less
#: in all than a jitter stretch holds no stroke
ONE_WAY = JITTER
MIN_PER_STROKE, FEW_PER_STROKE = 10, 40  # samples between reversals: refused, warned below
MIN_LEVELS, COARSE = 20, 500  # distinct position levels over the span: refused, warned below
HELD = 0.2  # share of moving samples repeating the previous position above which it is held
HELD_REACH = 4  # samples each side over which the position must change for a pair to be moving


def stretches(motion: Motion, usable: np.ndarray) -> list[tuple[float, float, int]]:
    """(direction +-1, distance travelled [m], first sample) of each maximal run of usable
    samples moving one way, the distance as the sum of |v| over the run, each sample weighted by
    half the time to its neighbours (a single sample of jitter travels its own share)."""
    direction = np.where(usable, np.sign(motion.v), 0.0)
    travelled = np.abs(motion.v) * np.gradient(motion.time)
    change = np.flatnonzero(np.diff(direction) != 0.0) + 1
    return [(float(direction[run[0]]), float(np.sum(travelled[run])), int(run[0]))
            for run in np.split(np.arange(direction.size), change) if direction[run[0]] != 0.0]


def _stroke_length(motion: Motion) -> float:
    """The span of the position [m]: a stretch shorter than JITTER of it is no stroke."""
    return float(np.ptp(motion.x))


def direction(source, motion: Motion, usable: np.ndarray) -> list[str]:
    """Refuse a record whose feed travels one way only (by distance); warn about jitter."""
    parts = stretches(motion, usable)
    forward = sum(d for s, d, _ in parts if s > 0.0)
    backward = sum(d for s, d, _ in parts if s < 0.0)
    total = forward + backward
    stroke = _stroke_length(motion)
    short = [d for _, d, _ in parts if d < JITTER * stroke]
    said = (f"{len(short)} of the {len(parts)} stretches of motion one way travel less than "
            f"{JITTER:.0%} of the {stroke * 1e3:.4g} mm stroke each ({sum(short) * 1e3:.3g} mm in "
            f"all): jitter or vibration at standstill, not strokes")
    if total <= 0.0 or min(forward, backward) < ONE_WAY * total:
        raise ValueError(f"{source}: the feed moves one way only ({forward:.4g} m forward, "
                         f"{backward:.4g} m backward by the distance travelled"
                         + (f"; {said}" if short else "") + "): the Coulomb level and the "
                         f"force offset cannot be told apart; record strokes in both directions "
                         f"(each at least {ONE_WAY:.0%} of the distance travelled)")
    strokes = len(parts) - len(short)
    return [f"{source}: {said}"] if len(short) >= max(JITTER_COUNT, strokes) else []


def stroke_reversals(motion: Motion, usable: np.ndarray) -> np.ndarray:
    """First samples of the strokes (stretches travelling at least JITTER of the stroke) that
    run against the stroke before them: the reversals of the motion, jitter's flickers of the
    direction at a dwell and a stroke broken by a flicker not counted."""
    stroke = _stroke_length(motion)
    strokes = [(s, first) for s, d, first in stretches(motion, usable) if d >= JITTER * stroke]
    return np.array([first for (s, first), (before, _) in zip(strokes[1:], strokes[:-1])
                     if s != before], dtype=int)


def sampling(source, motion: Motion, usable: np.ndarray) -> list[str]:
    """Refuse a record sampled too slowly for its strokes; warn where the reversals are coarse.
    Samples are counted between :func:`stroke_reversals` (dwells included, jitter not a
    reversal: a well-sampled record that flickers at its stops is not too slow)."""
    reversals = stroke_reversals(motion, usable)
    if reversals.size < 3:
        return []
    per_stroke = float(np.median(np.diff(reversals)))
    said = (f"{source}: column 'time': {per_stroke:.3g} samples between reversals (median), "
            f"{np.median(np.diff(motion.time)):.3g} s apart")
    if per_stroke < MIN_PER_STROKE:
        raise ValueError(f"{said}: too few to see a stroke's motion; the time base does not fit "
                         f"the motion (sampled too slowly, or 'time' in the wrong unit); at "
                         f"least {MIN_PER_STROKE} are needed")
    if per_stroke < FEW_PER_STROKE:
        return [f"{said}: the build-up after a reversal is resolved by a few samples only"]
    return []


def position_channel(source, run) -> list[str]:
    """Refuse a position quantised to a handful of levels; warn about a coarse or held one."""
    if "feed_position" not in run.inputs:
        return []
    x = np.asarray(run.columns["feed_position"], dtype=float)
    levels = np.unique(x)
    span = float(levels[-1] - levels[0])
    if span <= 0.0:
        return []
    steps = np.diff(levels)
    quantum = float(np.quantile(steps, 0.05))  # the smallest steps: a few noisy ones aside
    notes = []
    count = span / quantum
    said = (f"{source}: column 'feed_position' takes steps of {quantum:.3g} m, {count:.3g} "
            f"levels over its {span:.3g} m span")
    if count < MIN_LEVELS:
        raise ValueError(f"{said}: too coarse to derive a motion from (at least {MIN_LEVELS} "
                         f"levels are needed)")
    if count < COARSE:
        notes.append(f"{said}: pre-sliding shorter than a step and the derived acceleration are "
                     f"not resolved")
    moving = np.abs(np.diff(x)) > 0.0
    # a held channel: equal neighbours inside stretches that move (a standstill repeats too),
    # a nominal step apart (a bursty record's clusters of samples share a reading)
    pair = np.arange(x.size - 1)
    around = x[np.minimum(pair + 1 + HELD_REACH, x.size - 1)] != x[np.maximum(pair - HELD_REACH, 0)]
    inside = around & (np.diff(run.time) > 0.5 * sampling_step(run.time))
    held = float(np.mean(~moving[inside])) if inside.any() else 0.0
    if held > HELD:
        notes.append(f"{source}: column 'feed_position' repeats its previous value in "
                     f"{held:.0%} of the samples while the feed moves: it is updated less often "
                     f"than 'time' (about every {1.0 / max(1.0 - held, 1e-9):.2g} samples), so "
                     f"the derived velocity steps")
    return notes


def check(run, motion: Motion, usable: np.ndarray) -> list[str]:
    """Warnings on the motion of ``run`` (run_io.MeasuredRun) derived as ``motion``, over its
    ``usable`` samples; ValueError where the record cannot be diagnosed (module docstring)."""
    source = run.path / "data.csv"
    return (position_channel(source, run) + sampling(source, motion, usable)
            + direction(source, motion, usable))
