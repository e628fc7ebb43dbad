"""The decision of the discrepancy workflow (steps 1-5): which effects a measured run misses.

1. load and check the measured run (run_io), derive the motion that drives the model (signals)
   and find how many samples the compared channel lags it (:func:`channel_delay`; a shift the
   search leaves open is kept where the best model driven by the moved motion scores SCORE_MIN
   better than the best one without it);
2. calibrate the baseline (the Coulomb level and the channel's offset) on the fit samples;
3. locate the gap: residual against motion, reversals, running distance and frequency, the noise
   floor from the residual's high-frequency part, whether the gap is significant;
4. fit every candidate extension on the fit samples and score it on the held-out samples
   (BIC of the held-out residuals: baseline minus candidate), cross-validated: the three folds of
   locate.folds each hold out a third of the blocks, so every usable sample is predicted once by
   models fitted without it (the reported gaps are those of fold 1). Name the best candidate when
   the gap exceeds the noise floor by SIGNIFICANT_ERRORS standard errors of an RMS of white noise
   (1 + 3 / sqrt(2 n): 2.7 % for n = 6000), its score exceeds SCORE_MIN and that of a law in
   foreign terms, and it explains at least EXPLAINED of the gap's excess variance over the
   noise, alone or, with its score above SCORE_MIN, together with the effects step 5 names
   after it (two effects of about equal size each leave the other's gap); else ``unknown``
   with a sparse-regression law for the residual when such a law (or the foreign one) scores
   above SCORE_MIN and explains LAW_EXPLAINED of it, or when the gap exceeds UNRESOLVED times
   the whole noise (locate.incoherent_noise: noise of any colour, where the white floor sees
   only its high-frequency part), and the same holds on the samples whose
   derived acceleration the filter resolves (signals.Motion.unresolved: a gap at the corners of
   the acceleration alone is the input's error times the mass); else ``none``: a small gap
   that neither physics nor a law accounts for is taken as what the data cannot resolve
   (coloured noise, errors of the measured inputs such as accelerations differenced from
   encoder counts: the true model fed such inputs misses by that much too). Significance and
   the share explained are judged against the white floor, a lower bound of the noise, so that
   coloured noise never hides a structured gap a candidate explains; it includes, in
   quadrature, the noise a derived acceleration carries into the model's m a (known from its
   filter: signals.Derivation.output_noise).
   The reported noise floor is the larger of the white floor and the
   incoherent noise left by the reported model (the named one, the baseline with its law for
   ``unknown``, else the baseline).
   A record that passes its positions once cannot show friction repeating at the same positions,
   the mark of position dependence: there a running-distance candidate within SCORE_MIN of the
   position table is named instead, the pair's evidence shared (:func:`_same_path_choice`);
   a candidate whose model a richer one contains is named where it scores within SCORE_MIN of
   it, times the correlation time of the richer one's residual (:func:`_nested_choice`:
   preload loss before ball-to-ball contact).
5. look again for further effects beside the named one (more_effects.py).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import lsq_linear, minimize_scalar

from . import calibration, locate, more_effects, record_checks, regression
from .candidates import (BASELINE, CANDIDATES, RUNNING_DISTANCE_EFFECTS, Context, Fit,
                         PreslidingHysteresis, candidates_for)
from .run_io import MeasuredRun, load_run
from .scoring import (DOUBT, EXPLAINED, NEAR_NOISE, SCORE_MIN, bic, capped, confidence,
                      jackknife_intervals, significant_gap)
from .signals import derive_motion, noise_rms, sampling_step

LAW_EXPLAINED = 0.6  # ... and a proposed law, for the answer unknown (its terms are not physics)
#: a significant gap no candidate or law explains is ``unknown`` above this many times the whole
#: noise, else ``none``: the errors of the measured inputs (a differenced, quantised motion) alone
#: leave the true model a gap of the noise's order, which the bound must clear with a margin
UNRESOLVED = 2.0
#: the acceleration derived from the position may carry this share of the force channel's noise
#: (over the moving mass): its error enters the model as m a, and 0.3 adds 4 % to the noise in
#: quadrature while the shortest such window keeps the filter's bias on short ramps small
INPUT_SHARE = 0.3
#: |corr(running distance, position)| over the usable samples above which the record passes its
#: positions once: 1 on one monotone stroke, hardly less with short jogs back, while a return
#: stroke over the same positions runs the distance up as the position falls, well below it
SAME_PATH = 0.99
MOTION_CHANNELS = ("feed_position", "feed_velocity", "feed_acceleration")
#: samples with a resolved acceleration the input check needs (signals.Motion.unresolved);
#: fewer, and a gap at the acceleration's corners is judged as any other
MIN_RESOLVED = 60
MAX_DELAY = 5  # samples: the longest delay of the compared channel behind the motion sought
#: a delay is taken where it cuts the free model's residual mean square in excess of the noise
#: below DELAY_GAIN of the unshifted one's (the delay is all there is: the shift removes most of
#: the excess, while a shape the free model lacks, pre-sliding say, leaves a large part of it
#: whatever the shift), or the whole mean square by DELAY_SHARE (another effect stays beside the
#: delay: the shift then removes a large share of the whole, more than a shift without a delay
#: removes by fitting noise and shape)
DELAY_GAIN = 0.15
DELAY_SHARE = 0.4
ODD_KNOTS = 10  # knots of the delay search's free friction curve over the speed (besides 0)
#: knots of its friction level over the running distance
LEVEL_KNOTS = 6


def _same_path_choice(ctx: Context, usable: np.ndarray, ranked: list) -> tuple[int, list[str]]:
    """(index into ``ranked`` of the candidate to name, effects the record cannot tell apart from it).

    The best-scoring candidate, except on a record that passes its positions once
    (|corr(S, x)| > SAME_PATH), where the position table and a running-distance candidate that
    lead the ranking within SCORE_MIN of each other are not told apart: S and x are one function
    of the other, so both tables fit the same curve and their score difference is noise, while
    the spec's mark of position dependence, friction repeating at the same positions in every
    stroke, is absent from the record. The running-distance candidate is named.
    """
    effects = [fitted.effect for _, fitted, _ in ranked]
    if "position_dependent_friction" not in effects:
        return 0, []
    if abs(np.corrcoef(ctx.distance[usable], ctx.motion.x[usable])[0, 1]) <= SAME_PATH:
        return 0, []
    position = ranked[effects.index("position_dependent_friction")][0]
    for i, (score, fitted, _) in enumerate(ranked):
        if (fitted.effect in RUNNING_DISTANCE_EFFECTS and abs(position - score) < SCORE_MIN
                and ranked[0][0] in (position, score)):
            return i, ["position_dependent_friction"]
    return 0, []


def _nested_choice(ranked: list, chosen: int, margin: float = SCORE_MIN) -> int:
    """Index into ``ranked`` of the candidate to name instead of ``ranked[chosen]``: one whose
    model the chosen one's contains (Candidate.nests: a free table over the running distance
    holds any monotone drift of the level) scoring within ``margin`` of it, the richer model
    not being needed by the data; else ``chosen``."""
    if not ranked:
        return chosen
    top, best, _ = ranked[chosen]
    nested = CANDIDATES[best.effect].nests
    for i, (score, fitted, _) in enumerate(ranked):
        if fitted.effect in nested and top - score < margin:
            return i
    return chosen


@dataclass
class Naming:
    """Steps 1-5 of the workflow on one run: the data, the models and the decision."""

    run: MeasuredRun
    ctx: Context
    fit_mask: np.ndarray
    held: np.ndarray
    usable: np.ndarray
    baseline: Fit
    noise: float  # reported noise floor: max(white, incoherent noise of the reported model)
    #: white (second-difference) floor of the baseline residual, held out, with the noise of a
    #: derived acceleration's m a in quadrature
    white_noise: float
    gap_base: float
    cross_gap: float  # cross-validated baseline gap over the white floor, all usable samples
    white: float
    significant: bool
    where: dict
    ranked: list  # (cross-validated score, Fit on the fold-1 fit samples, held-out gap), best first
    foreign_score: float
    effect: str
    winner: Fit | None
    equation: str | None
    law: np.ndarray | None
    #: share of right answers on never-seen draws with this evidence (calibration.py), held at
    #: scoring.DOUBT where ``doubts`` say why
    confidence: float
    not_told_apart: list  # effects scoring like the named one that the record cannot tell from it
    #: out-of-fold residual of the best-scoring model (a candidate or the baseline) and its
    #: number of parameters: what a shift the delay search left open is judged by
    best_residual: np.ndarray
    best_parameters: int
    #: baseline parameters the record contradicts, refitted first (:func:`corrected_mass`)
    corrections: list
    intervals: dict  # parameter of the named effect -> [low, high] (scoring.LEVEL)
    baseline_intervals: dict  # parameter of the baseline -> [low, high]
    doubts: list  # why the confidence was held at scoring.DOUBT (plain sentences)
    #: the answer's raw BIC weight (scoring.confidence), the evidence ``confidence`` is
    #: calibrated from (calibration.py) with the gap before over the noise floor
    weight: float
    #: the effects named in turn (more_effects.Step), the first the named one; empty for
    #: ``none`` and ``unknown``
    steps: list
    experiment: dict | None = None  # the separating experiment: none for horizontal runs yet


def motion_of(run: MeasuredRun, delay: float = 0.0):
    """The feed motion of ``run`` (signals.derive_motion) ``delay`` [s] before each sample, the
    acceleration allowed INPUT_SHARE of the force channel's noise over the moving mass where the
    model has a mass term."""
    columns = {c: run.columns[c] for c in MOTION_CHANNELS
               if c in run.inputs or (c == "feed_acceleration" and c in run.columns)}
    mass_term = run.channel == "drive_force" and run.moving_mass > 0.0
    tolerance = (INPUT_SHARE * noise_rms(run.columns[run.channel]) / run.moving_mass
                 if mass_term else None)
    return derive_motion(run.time, columns, tolerance, delay)


def channel_delay(ctx: Context, usable) -> tuple[float, bool]:
    """(shift [s], taken): the delay of the compared channel behind the motion, in whole nominal
    sampling intervals (signals.sampling_step) up to MAX_DELAY, that lets a free passive friction
    model driven by the motion that much earlier fit it best, on the samples whose moved motion
    has a clear direction (on an uneven record refined between the neighbouring steps: its
    nominal period is not the mean step; on an even one a fractional shift would blur the
    Coulomb switch the search aligns), where that cuts the residual mean square in excess of the
    noise's below DELAY_GAIN of the unshifted one's, or the whole mean square by DELAY_SHARE
    (a force that switches a few samples after each reversal leaves spikes no friction law
    describes). A shift not taken is for :func:`decide` to try beside none (0 where the least
    mean square lies at the search's edge: a trend, not a delay).

    The free model (:func:`_passive_friction`) holds any friction curve over the speed, any
    pre-sliding build-up over the displacement since the reversal, a level varying slowly with
    the running distance, m a and an offset: a
    Stribeck curve or a hysteresis beside the delay then leaves no residual a shift could
    reduce, while a delay, which acts in time at every reversal whatever its acceleration, is
    not among its shapes. The noise's share (the white floor of the best shift's residual) is
    taken off both: on a record whose derived acceleration is noisy (velocity only) it would
    otherwise hide the gain. The motion is moved, not the force: interpolated across a bursty
    record's dropouts, the switching force makes spikes."""
    t = ctx.motion.time
    step = sampling_step(t)
    reach = MAX_DELAY + 1  # one beyond: a least mean square at the edge is a trend, not a delay
    shifts = step * np.arange(-reach, reach + 1)
    inner = (t > t[0] + reach * step) & (t < t[-1] - reach * step)
    columns = _passive_friction(ctx, usable)

    def residual(shift):  # the smooth motion moved, not the switching force (bursty gaps), on
        moved = inner & (np.interp(t - shift, t, usable.astype(float)) == 1.0)  # the samples
        design = columns(t[moved] - shift)  # whose moved motion is usable
        target = ctx.y[moved] - np.interp(t[moved] - shift, t, ctx.fixed)
        lower = np.r_[np.zeros(design.shape[1] - 1), -np.inf]  # passive: friction opposes motion
        coef = lsq_linear(design, target, bounds=(lower, np.inf), method="bvls").x
        return target - design @ coef

    sums = [float(np.mean(residual(shift) ** 2)) for shift in shifts]  # mean squares
    best = int(np.argmin(sums))
    uneven = np.ptp(np.diff(t)) > 1e-6 * step
    if not 0 < best < 2 * reach:
        return 0.0, False
    if uneven:  # an uneven record's nominal period is not its
        found = minimize_scalar(lambda shift: float(np.mean(residual(shift) ** 2)),  # mean step:
                                bounds=(shifts[best - 1], shifts[best + 1]),  # refined between
                                method="bounded", options={"xatol": 0.01 * step})  # neighbours
        shift, least = float(found.x), float(found.fun)
    else:
        shift, least = float(shifts[best]), sums[best]
    noise = noise_rms(residual(shift)) ** 2
    gain = max(least - noise, 0.0) / max(sums[reach] - noise, 1e-300)
    return shift, shift != 0.0 and bool(gain < DELAY_GAIN
                                        or least < (1.0 - DELAY_SHARE) * sums[reach])


def _passive_friction(ctx: Context, usable):
    """The design of the delay search's free friction model at the times ``when`` [s]: a
    function ``when -> columns`` (the motion interpolated there). Columns: the baseline's
    Coulomb law, hat functions over the speed on ODD_KNOTS geometric knots from the 1 % quantile
    of the speed to its maximum (and zero) times the direction, the Dahl states of the
    pre-sliding candidate's distance grid (a Maxwell-slip model), hat functions over the running
    distance on LEVEL_KNOTS even knots times the direction (a level that wears or settles: a
    preload lost over a tribometer's first millimetre read as a 5-sample delay without them),
    all with coefficients >= 0 in the fit (friction opposes the motion), and the offset, free."""
    t, v = ctx.motion.time, ctx.motion.v
    speed = np.abs(v[usable])
    knots = np.r_[0.0, np.geomspace(max(np.quantile(speed, 0.01), 1e-12 * speed.max()),
                                    speed.max(), ODD_KNOTS)]
    hysteresis = PreslidingHysteresis()
    dahl = np.column_stack([hysteresis.columns(ctx, dict.fromkeys(hysteresis.keys, float(d)))
                            for d in hysteresis.distances(ctx)])
    nodes = np.linspace(0.0, ctx.distance[-1], LEVEL_KNOTS)

    def columns(when):
        moved = np.interp(when, t, v)
        direction = np.sign(moved)
        hats = [np.interp(np.abs(moved), knots, hat) * direction for hat in np.eye(knots.size)]
        slip = [np.interp(when, t, column) for column in dahl.T]
        distance = np.interp(when, t, ctx.distance)
        levels = [np.interp(distance, nodes, hat) * direction for hat in np.eye(LEVEL_KNOTS)]
        return np.column_stack([BASELINE.coulomb_column(ctx, moved), *hats, *slip, *levels,
                                np.ones(moved.size)])

    return columns


def decide(run_dir) -> Naming:
    """Load (``run_dir``: a folder, or a MeasuredRun already read), calibrate, locate and name
    (steps 1-5) without co-simulating. Raises
    FileNotFoundError or ValueError (one message naming the file and the row, column, section
    or key) for a run that cannot be used, the motion's checks (record_checks.py: one way only,
    sampled too slowly for its strokes, a position of a handful of levels) included; their
    warnings join the run's."""
    run = run_dir if isinstance(run_dir, MeasuredRun) else load_run(run_dir)
    source = run.path / "rig.toml"
    if run.kind != "horizontal_drive":
        raise ValueError(f"{source}: [rig] key 'kind': decide handles 'horizontal_drive' rigs; "
                         f"{run.kind!r} runs are decided by vertical.decide_vertical "
                         f"(guideway-fmu diagnose takes either)")
    if run.model["friction"] != "coulomb":
        raise ValueError(f"{source}: [model] key 'friction': diagnose calibrates a 'coulomb' "
                         f"baseline; {run.model['friction']!r} is not supported as a baseline yet")
    motion = motion_of(run)
    run.orient_friction(motion.v)
    usable = _splits(run, motion)[0]
    run.warnings.extend(record_checks.check(run, motion, usable))
    ctx = Context.of(run, motion)
    shift, taken = channel_delay(ctx, usable)
    still = None if taken else _name(ctx)
    if not shift or (still is not None and shift < 0.0):  # a force leading the motion by less
        return still  # than the rules ask is what damped pre-sliding (LuGre's sigma_1) shows
    try:  # the models driven by the motion the channel responds to
        moved = _name(Context.of(run, motion_of(run, shift)))
    except ValueError:
        if still is None:
            raise
        return still
    if still is not None:  # a shift the search left open: the better best model decides
        common = moved.usable & still.usable
        fits = [bic(float(np.sum(naming.best_residual[common] ** 2)), int(common.sum()),
                    naming.best_parameters + extra) for naming, extra in ((still, 0), (moved, 1))]
        if fits[0] - fits[1] <= SCORE_MIN:
            return still
    run.channel_delay = shift
    return moved


def _rms(values, mask) -> float:
    return float(np.sqrt(np.mean(values[mask] ** 2)))


def _splits(run: MeasuredRun, motion) -> tuple[np.ndarray, list]:
    """(usable samples, locate.folds) of ``motion``; ValueError naming data.csv where too few
    samples have a clear direction."""
    usable = ~motion.standstill & ~motion.ends
    splits = locate.folds(run.time.size, usable)
    if min(splits[0][1].sum(), splits[0][0].sum()) < 20:
        raise ValueError(f"{run.path / 'data.csv'}: only {int(usable.sum())} samples with a clear "
                         f"direction of motion; at least 60 are needed")
    return usable, splits


def corrected_mass(ctx: Context, splits, usable, best: float) -> dict | None:
    """The moving mass [kg] a drive-force record shows where it contradicts the stated one
    downward (baseline_corrections of docs/measured-run.md: {"parameter", "stated", "fitted",
    "interval"}), else None. The baseline refitted with the mass free (its Coulomb level, m a and
    the offset) is scored against the stated one as a candidate is (the out-of-fold BIC gain),
    and its mass is taken where it scores above SCORE_MIN and above ``best``, the best
    candidate's score (the mass is then the record's main discrepancy: a gap of another effect
    correlated with the acceleration moves a free mass too), and lies below the stated one with
    the whole interval (scoring.jackknife_intervals): no missing effect takes inertia away, so a
    smaller mass is a wrong baseline parameter, never an effect, while a larger one is the
    candidate unmodeled_mass. ValueError naming rig.toml where even the refitted mass is not
    positive: the force and the acceleration disagree in sign or unit."""
    run, y = ctx.run, ctx.y
    if run.channel != "drive_force" or ctx.mass <= 0.0:
        return None
    design = np.column_stack([BASELINE.coulomb_column(ctx, ctx.motion.v), ctx.motion.a,
                              np.ones(y.size)])
    target = y - ctx.fixed
    free = [np.linalg.lstsq(design[f], target[f], rcond=None)[0] for f, _ in splits]
    stated = [np.linalg.lstsq(design[f][:, ::2], target[f], rcond=None)[0] for f, _ in splits]
    n = int(usable.sum())
    score = (bic(float(np.sum((target - locate.out_of_fold(
                 splits, [design[:, ::2] @ c for c in stated]))[usable] ** 2)), n, 2)
             - bic(float(np.sum((target - locate.out_of_fold(splits, [design @ c for c in free]))
                                [usable] ** 2)), n, 3))
    masses = [{"mass": ctx.mass + float(c[1])} for c in free]
    fitted = masses[0]["mass"]
    low, high = jackknife_intervals(masses, {"mass": fitted})["mass"]
    if score <= max(SCORE_MIN, best) or high >= ctx.mass:
        return None
    if fitted <= 0.0:
        raise ValueError(f"{run.path / 'rig.toml'}: [rig] key 'moving_mass': the drive force "
                         f"shows a mass of {fitted:.4g} kg ({low:.4g} to {high:.4g}), not the "
                         f"stated {ctx.mass:.4g} kg nor any positive one: '{run.channel}' and "
                         f"the acceleration disagree in sign or unit")
    return {"parameter": "moving_mass", "stated": ctx.mass, "fitted": fitted,
            "interval": [low, high], "score": score}


def _name(ctx: Context, correction: dict | None = None) -> Naming:
    """Steps 2-4 of :func:`decide` on the motion of ``ctx``; where the record contradicts the
    baseline's moving mass (:func:`corrected_mass`), again on the corrected baseline, the
    ``correction`` reported."""
    run, motion = ctx.run, ctx.motion
    usable, splits = _splits(run, motion)
    fit_mask, held = splits[0]

    y = ctx.y

    def calibrated(mask):
        fitted = BASELINE.fit(ctx, mask)
        if fitted is None:
            raise ValueError(f"{run.path / 'data.csv'}: column '{run.channel}': the Coulomb level "
                             f"fits negative; {run.channel} must be the force the drive applies, "
                             f"along its own positive axis")
        return fitted

    def out_of_fold(predictions):
        return locate.out_of_fold(splits, predictions)

    bases = [calibrated(f) for f, _ in splits]
    baseline = bases[0]
    residual = y - baseline.prediction
    # the white floor, with the noise the acceleration derived from a noisy channel brings
    carried = ctx.mass * (motion.how["feed_acceleration"].output_noise or 0.0)
    noise = float(np.hypot(locate.noise_floor(y, residual, held), carried / np.ptp(y[held])))
    gap_base = locate.gap(y, baseline.prediction, held)
    white = locate.whiteness(residual, held)
    where = locate.locate(ctx, residual, usable)

    # the decision: cross-validated over the folds (every usable sample held out once)
    base_cv = out_of_fold([b.prediction for b in bases])
    noise_cv = float(np.hypot(locate.noise_floor(y, residual, usable),
                              carried / np.ptp(y[usable])))
    span = float(np.ptp(y[usable]))
    gap_cv = locate.gap(y, base_cv, usable)
    significant = significant_gap(gap_cv, noise_cv, int(usable.sum()))
    n_usable = int(usable.sum())

    def held_out_bic(prediction, parameters):  # scoring.bic of the out-of-fold residual
        return bic(float(np.sum((y - prediction)[usable] ** 2)), n_usable, parameters)

    bic_base = held_out_bic(base_cv, baseline.n_parameters)
    ranked, cv_gaps, folds_of = [], {}, {}
    best_residual, best_parameters, best_score = y - base_cv, baseline.n_parameters, 0.0
    for candidate in candidates_for(run):
        fitted = [candidate.fit(ctx, f) for f, _ in splits]
        if any(f is None for f in fitted):
            continue
        prediction = out_of_fold([f.prediction for f in fitted])
        score = bic_base - held_out_bic(prediction, fitted[0].n_parameters)
        ranked.append((score, fitted[0], locate.gap(y, fitted[0].prediction, held)))
        cv_gaps[candidate.effect] = locate.gap(y, prediction, usable)
        folds_of[candidate.effect] = fitted
        if score > best_score:
            best_residual, best_parameters, best_score = (y - prediction,
                                                          fitted[0].n_parameters, score)
    ranked.sort(key=lambda item: -item[0])
    if correction is None:
        found = corrected_mass(ctx, splits, usable, ranked[0][0] if ranked else 0.0)
        if found is not None:
            return _name(Context.of(run, motion, found["fitted"]), found)

    def share(gap_model, gap=gap_cv):  # of the gap's excess variance over the noise
        return (gap**2 - gap_model**2) / max(gap**2 - noise_cv**2, 1e-300)

    def law(foreign):  # (fold-1 law, its cross-validated score, its out-of-fold prediction)
        frequencies = where["foreign_frequencies" if foreign else "frequencies"]
        laws = [regression.propose(ctx, y - b.prediction, f, frequencies, foreign=foreign)
                for b, (f, _) in zip(bases, splits)]
        prediction = out_of_fold([b.prediction + values for b, (_, values, _) in zip(bases, laws)])
        terms = max(n for _, _, n in laws)
        score = bic_base - held_out_bic(prediction, baseline.n_parameters + terms)
        return laws[0], score, prediction

    def unexplained(mask, laws, whole):  # a gap on mask a law explains, or too large for noise
        gap = _rms(y - base_cv, mask) / span
        return (any(score > SCORE_MIN
                    and share(_rms(y - prediction, mask) / span, gap) >= LAW_EXPLAINED
                    for score, prediction in laws)
                or gap > UNRESOLVED * max(noise_cv, whole))

    # a law from signals no candidate uses (normal force, residual peak frequencies) competes
    _, foreign_score, foreign_prediction = law(foreign=True)
    effect, winner, equation, values = "none", None, None, None
    chosen, twins = _same_path_choice(ctx, usable, ranked)
    # residuals correlated over tau samples count each sample tau times in the BIC: the richer
    # model must beat the nested one by SCORE_MIN in independent samples (a free table fits
    # the shape of correlated noise, which the BIC of correlated samples overrates tau times)
    chosen = _nested_choice(ranked, chosen, SCORE_MIN * (locate.correlation_time(
        y - ranked[chosen][1].prediction, usable) if ranked else 1.0))
    steps = []
    if significant:
        score, best, _ = ranked[chosen] if ranked else (-np.inf, None, gap_base)
        if score > SCORE_MIN:  # the effects named in turn from the best (step 5)
            steps = more_effects.further_effects(ctx, splits, usable, noise_cv,
                                                 folds_of[best.effect], score)
        # the best alone, or with the effects named after it where it explains too little
        # alone (two effects of about equal size: each leaves the other's gap)
        together = sum(step.score for step in steps)
        if (score > SCORE_MIN and (share(cv_gaps[best.effect]) >= EXPLAINED
                                   and score > foreign_score
                                   or len(steps) > 1 and share(steps[-1].cross_gap) >= EXPLAINED
                                   and together > foreign_score)):
            effect, winner = best.effect, best
        else:
            steps = []
            (equation, values, _), law_score, law_prediction = law(foreign=False)
            laws = [(law_score, law_prediction), (foreign_score, foreign_prediction)]
            whole = locate.incoherent_noise(ctx.motion, y - base_cv, usable) / span
            # the same on the samples whose acceleration is resolved: a gap that lives only
            # where it is not is the derived input's error times the mass, not an effect
            resolved = usable & ~motion.unresolved
            n_resolved = int(resolved.sum())
            beyond_inputs = n_resolved < MIN_RESOLVED or (
                significant_gap(_rms(y - base_cv, resolved) / span, noise_cv, n_resolved)
                and unexplained(resolved, laws, whole))
            if unexplained(usable, laws, whole) and beyond_inputs:
                effect = "unknown"
            else:  # small structure no model or law accounts for: the inputs' own errors
                equation, values = None, None
    if winner is not None:
        winner.parameters.update(CANDIDATES[winner.effect]().interpret(ctx, winner))
    reported = (winner.prediction if winner is not None else
                baseline.prediction + (values if values is not None else 0.0))
    floor = max(noise, locate.incoherent_noise(ctx.motion, y - reported, usable)
                / float(np.ptp(y[held])))
    scores = {"none": 0.0, **{f.effect: s for s, f, _ in ranked}}
    twins = twins if winner is not None else []
    for twin in twins:  # the record holds no evidence between them: they share the pair's best
        scores[twin] = scores[effect] = max(scores[twin], scores[effect])
    weight, doubts = confidence(scores, effect), []
    stated = calibration.confidence(effect, gap_base / floor, weight)
    if winner is not None:
        if capped(stated, gap_base, floor) < stated:
            doubts.append(f"the gap before any fit is {gap_base / floor:.3g} noise floors, within "
                          f"{NEAR_NOISE:g} of it: as likely noise of another colour as an effect")
        for key, end in winner.at_bound.items():
            doubts.append(f"{key} = {end:.4g} lies at the end of its search, widened once: the "
                          f"record does not fix it")
        stated = min(stated, DOUBT) if doubts else stated
    intervals = (jackknife_intervals([f.parameters for f in folds_of[winner.effect]],
                                     winner.parameters) if winner is not None else {})
    return Naming(run, ctx, fit_mask, held, usable, baseline, floor, noise, gap_base,
                  gap_cv / noise_cv,
                  white, significant, where, ranked, foreign_score, effect, winner, equation,
                  values, stated, twins, best_residual, best_parameters,
                  [correction] if correction is not None else [], intervals,
                  jackknife_intervals([b.parameters for b in bases], baseline.parameters), doubts,
                  weight, steps)
