"""How the discrepancy workflow scores and judges a model against the samples, for every rig:
the Bayesian information criterion of a least-squares fit, whether a gap is significant, the
confidence of a naming and the intervals of fitted numbers."""
from __future__ import annotations

import numpy as np
from scipy import stats

SIGNIFICANT_ERRORS = 3.0  # standard errors of the noise's held-out RMS a significant gap exceeds
SCORE_MIN = 10.0  # held-out BIC improvement a candidate needs to be named
EXPLAINED = 0.4  # share of the gap's excess variance over the noise a named effect must explain
NEAR_NOISE = 1.3  # gap before over the noise floor at or under which a naming is doubted ...
DOUBT = 0.5  # ... and its confidence at most this
LEVEL = 0.95  # confidence level of the intervals of fitted numbers
#: least mean square a BIC takes [unit of the residual squared]: a fit exact to the last bit
#: keeps a finite score
LEAST_MEAN_SQUARE = 1e-300


def bic(rss: float, samples: int, parameters: int) -> float:
    """BIC [-] of a least-squares fit with Gaussian errors: n ln(RSS / n) + k ln n for the
    residual sum of squares ``rss`` over n = ``samples`` and k = ``parameters`` fitted numbers
    (the constant terms dropped: only differences between models on the same samples count;
    lower is better)."""
    return float(samples * np.log(max(rss / samples, LEAST_MEAN_SQUARE))
                 + parameters * np.log(samples))


def significant_gap(gap, noise, n) -> bool:
    """Whether an RMS ``gap`` over ``n`` samples exceeds ``noise`` by SIGNIFICANT_ERRORS
    standard errors (the RMS of n white-noise samples has a relative one of 1 / sqrt(2 n))."""
    return bool(gap > (1.0 + SIGNIFICANT_ERRORS / np.sqrt(2.0 * n)) * noise)


def confidence(scores: dict, chosen: str) -> float:
    """Posterior weight of ``chosen`` among the baseline ("none", score 0) and the candidates,
    exp((score - SCORE_MIN) / 2) normalised (BIC approximation of the model evidence, with the
    naming margin SCORE_MIN as the prior odds against an extension)."""
    values = np.array([v - (SCORE_MIN if k != "none" else 0.0) for k, v in scores.items()])
    weights = np.exp((values - values.max()) / 2.0)
    weights /= weights.sum()
    if chosen == "unknown":  # no named model holds: the weight of the best one is what is doubted
        return float(1.0 - weights.max()) if len(weights) > 1 else 0.0
    return float(dict(zip(scores, weights))[chosen])


def capped(value: float, gap: float, floor: float) -> float:
    """A naming's confidence ``value`` at most DOUBT where the gap before any fit ``gap`` lies
    within NEAR_NOISE noise floors ``floor`` (the same normalisation): the floor is itself an
    estimate (its white part a lower bound, its incoherent part of the reported model), and a
    gap that close to it is as likely noise of another colour as an effect."""
    return min(value, DOUBT) if gap <= NEAR_NOISE * floor else value


def jackknife_intervals(folds: list[dict], centre: dict, level: float = LEVEL) -> dict:
    """``level`` intervals [low, high] of the real numbers of ``centre`` (a fit's parameters)
    that each of the ``folds`` (the same model fitted with one group of blocks of the record
    left out in turn, locate.folds) carries: centre +- t se, se^2 = (g - 1) / g sum (theta_i -
    mean theta)^2 over the g folds (the delete-a-group jackknife: whole blocks of the record
    are left out, so residuals correlated over time stay together), t Student's quantile for
    g - 1 degrees of freedom (4.30 at 95 % for three folds: few folds, wide intervals)."""
    g = len(folds)
    t = float(stats.t.ppf(0.5 + 0.5 * level, g - 1))
    out = {}
    for key, value in centre.items():
        values = [f.get(key) for f in folds] + [value]
        if not all(isinstance(v, float) and np.isfinite(v) for v in values):
            continue
        spread = np.asarray(values[:-1])
        se = float(np.sqrt((g - 1) / g * np.sum((spread - spread.mean()) ** 2)))
        out[key] = [value - t * se, value + t * se]
    return out
