"""Step 5 of the workflow: a record may miss more than one effect.

After the first effect is named (decide.py), the workflow looks again: with the named effects'
extensions over the baseline (candidates.extension) held fixed, every other candidate is fitted
beside them (its own Coulomb level and offset free: the level is shared, so the joint model has
the parameters of both less one level and one offset), scored on the held-out samples against
the model before the step, as the first effect was scored against the baseline, and the best one
added where the gap before the step is still significant (scoring.significant_gap), it scores
above SCORE_MIN and explains EXPLAINED of that gap's excess variance over the noise. The named
effects are then refitted, each with the others' extensions fixed and the newest last (one sweep
of backfitting), so that a first effect that had taken up part of the second gives it back.
Every step is cross-validated over the same folds as the first naming; it stops at MAX_EFFECTS,
when the gap is within the noise or when no candidate qualifies.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import locate
from .candidates import CANDIDATES, Context, Fit, candidates_for, extension, with_fixed
from .scoring import EXPLAINED, SCORE_MIN, bic, jackknife_intervals, significant_gap

MAX_EFFECTS = 3  # effects named in one record at most


@dataclass
class Step:
    """One named effect of the record, in the joint model of all the effects named."""

    effect: str
    fit: Fit  # fold-1 fit, with the other named effects' extensions held fixed
    folds: list  # the fit of every fold (fit.parameters of each: the intervals)
    gap_after: float  # held-out gap (fold 1) of the joint model up to this step [-]
    score: float  # cross-validated held-out BIC gain over the model before this step
    cross_gap: float  # cross-validated gap [-] of that joint model over all usable samples
    intervals: dict = field(default_factory=dict)  # parameter -> [low, high] (scoring.LEVEL)


def _joint_parameters(named: dict) -> int:
    """Parameters of the joint model of the ``named`` effects (effect -> fold fits): each fit's
    own, less a Coulomb level and an offset for every effect after the first (shared)."""
    return sum(folds[0].n_parameters for folds in named.values()) - 2 * (len(named) - 1)


def further_effects(ctx: Context, splits, usable: np.ndarray, noise: float,
                    first: list[Fit], first_score: float) -> list[Step]:
    """The effects the record misses, in the order named (module docstring): the first one's
    fold fits ``first`` (scored ``first_score``), then any further ones. ``noise`` is the
    cross-validated noise floor [-] the gaps are judged against, over ``usable`` samples split
    by ``splits`` (locate.folds)."""
    y, n = ctx.y, int(usable.sum())
    held = splits[0][1]

    def predicted(folds):
        return locate.out_of_fold(splits, [f.prediction for f in folds])

    def held_out_bic(folds, parameters):
        return bic(float(np.sum((y - predicted(folds))[usable] ** 2)), n, parameters)

    def beside(candidate, others):
        """``candidate`` fitted in every fold with the extensions of ``others`` (fold fits of
        named effects) fixed; None where a fold's fit is unphysical."""
        folds = []
        for i, (fit_mask, _) in enumerate(splits):
            fixed = ctx.fixed + sum((extension(ctx, other[i]) for other in others), 0.0)
            fitted = candidate.fit(with_fixed(ctx, fixed), fit_mask)
            if fitted is None:
                return None
            folds.append(fitted)
        return folds

    named = {first[0].effect: first}
    scores = {first[0].effect: first_score}
    gaps = {first[0].effect: (locate.gap(y, first[0].prediction, held),
                              locate.gap(y, predicted(first), usable))}
    joint = first  # the fold fits whose predictions are the joint model's
    while len(named) < MAX_EFFECTS:
        gap = locate.gap(y, predicted(joint), usable)
        if not significant_gap(gap, noise, n):
            break
        before = held_out_bic(joint, _joint_parameters(named))
        best = None
        for candidate in candidates_for(ctx.run):
            if candidate.effect in named:
                continue
            folds = beside(candidate, list(named.values()))
            if folds is None:
                continue
            score = before - held_out_bic(folds, _joint_parameters({**named,
                                                                    candidate.effect: folds}))
            if best is None or score > best[0]:
                best = (score, candidate.effect, folds)
        if best is None:
            break
        score, effect, folds = best
        after = locate.gap(y, predicted(folds), usable)
        if score <= SCORE_MIN or (gap**2 - after**2) < EXPLAINED * (gap**2 - noise**2):
            break
        named[effect], scores[effect] = folds, score
        for each in list(named)[:-1] + [effect]:  # one sweep of backfitting, the newest last
            refitted = beside(CANDIDATES[each](), [f for e, f in named.items() if e != each])
            if refitted is not None:
                named[each] = refitted
        joint = named[effect]
        gaps[effect] = (locate.gap(y, joint[0].prediction, held),
                        locate.gap(y, predicted(joint), usable))
    return [Step(effect, folds[0], folds, gaps[effect][0], scores[effect], gaps[effect][1],
                 jackknife_intervals([f.parameters for f in folds], folds[0].parameters))
            for effect, folds in named.items()]
