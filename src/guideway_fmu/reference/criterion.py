"""Which criterion ``verify`` judges a scenario by, and its verdicts.

The reference's own predictability decides. It is run twice more: its start moved by
START_OFFSET of each state's nominal scale, and at LOOSE_RTOL_FACTOR times its tolerance. The
spread is the RMS difference of each from the reference, relative to the reference's range.

* pointwise, where both spreads are at most PREDICTABLE (0.1 %, a tenth of the 1 % TOLERANCE):
  disturbances far smaller than any co-simulation's own errors then move the trajectory by
  under a tenth of what the co-simulation is allowed, so its pointwise error measures its
  coupling, not the response's sensitivity. It passes at an RMS error of at most TOLERANCE.
* statistics otherwise (reference/statistics.py): each statistic passes when its difference
  from the reference's is at most K times the reference's spread of it (the larger difference
  of the two disturbed runs) or its floor, whichever is larger. The two disturbed runs sample
  how far an equally valid run's statistic wanders; the co-simulation is one more such run. The
  larger of two normal differences averages about 1.13 standard deviations, so K = 3 allows
  about 3.4 of them: a valid run fails about once in a thousand. The floor holds a statistic
  the disturbances do not move to the pointwise tolerance (FLOOR of the range) rather than to
  zero, and a frequency to one bin of the spectrum (1 / duration), its resolution.
"""
from __future__ import annotations

import numpy as np

TOLERANCE = 0.01  # RMS error / range allowed pointwise
PREDICTABLE = 0.1 * TOLERANCE  # largest spread / range judged pointwise
START_OFFSET = 1e-9  # start disturbance, of each state's nominal scale
LOOSE_RTOL_FACTOR = 10.0  # the looser reference's rtol over the reference's
K = 3.0  # allowed difference of a statistic, in spreads of the reference's
FLOOR = TOLERANCE  # smallest allowed difference of a statistic, of the range


def relative_error(values, reference) -> tuple[float, float]:
    """RMS and peak of values - reference relative to the reference's range (max - min), or to
    its largest magnitude where it is constant."""
    reference = np.asarray(reference, float)
    err = np.asarray(values, float) - reference
    span = float(np.ptp(reference))
    scale = span if span > 0 else max(float(np.max(np.abs(reference))), 1e-300)
    return float(np.sqrt(np.mean(err**2)) / scale), float(np.max(np.abs(err)) / scale)


def choose(reference, disturbed: dict[str, np.ndarray]) -> tuple[str, dict[str, float], str]:
    """The criterion ("pointwise" or "statistics") for a signal, from the ``reference`` and the
    same signal of ``disturbed`` runs (label -> values on the same times); returns it, the
    spreads (label -> RMS difference / range) and the reason in words."""
    spreads = {label: relative_error(values, reference)[0] for label, values in disturbed.items()}
    worst = max(spreads, key=spreads.get)
    if spreads[worst] <= PREDICTABLE:
        return "pointwise", spreads, (
            f"predictable: the disturbed references stay within {spreads[worst]:.2g} of the range "
            f"(largest: {worst}), at most {PREDICTABLE:g}, a tenth of the {TOLERANCE:g} tolerance")
    return "statistics", spreads, (
        f"unpredictable: the reference {worst} moves by {spreads[worst]:.2g} of the range, over "
        f"{PREDICTABLE:g} (a tenth of the {TOLERANCE:g} tolerance): its trajectory cannot be "
        f"followed pointwise, only its statistics")


def judge_statistics(cosim: dict[str, float], reference: dict[str, float],
                     disturbed: list[dict[str, float]], scale: float,
                     bin_width: float) -> dict[str, dict]:
    """Each statistic (name -> value, reference/statistics.py) of the co-simulation against the
    reference's: difference, the reference's spread (largest |disturbed - reference|), the
    difference allowed (K spreads or the floor: FLOOR x ``scale`` [unit of the signal], or
    ``bin_width`` [Hz] for a frequency) and whether it passes."""
    out = {}
    for name, ref in reference.items():
        spread = max(abs(d[name] - ref) for d in disturbed)
        floor = bin_width if name.endswith("_frequency") else FLOOR * scale
        allowed = max(K * spread, floor)
        difference = cosim[name] - ref
        out[name] = {"reference": ref, "cosim": cosim[name], "difference": difference,
                     "spread": spread, "allowed": allowed, "passed": bool(abs(difference) <= allowed)}
    return out
