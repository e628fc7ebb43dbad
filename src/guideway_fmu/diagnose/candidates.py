"""The baseline model of a horizontal drive rig and the candidate extensions, one per effect.

Every subclass of :class:`Candidate` that names an ``effect`` registers itself in CANDIDATES, the
one list the workflow, the truth generator and the report read: a new effect is a law in
physics/rigs/friction_laws.py, a friction FMU in components/rigs/friction_effects.py and one class here
(effect name, residual signal, FMU name, law, running-distance flag, columns and physical
parameters).

Every model predicts the compared channel as a fixed part (m a for drive_force, 0 for
friction_force) plus a linear combination of columns built from the physics laws
(physics/rigs/friction_laws.py) plus a constant offset (the sensor zero). A candidate may have a few
nonlinear settings (a Stribeck velocity, a pre-sliding distance, a wear distance, a number of
position knots); for each setting the linear coefficients are a least-squares fit on the fit
samples, and the setting with the lowest BIC on the fit samples is kept. :meth:`Candidate.fmu`
turns the fitted coefficients into the friction FMU and parameters that carry the same law.

Sign convention: the columns are the drive-force contributions -F_friction of unit parameters.
"""
from __future__ import annotations

from copy import copy
from dataclasses import dataclass, field, replace
from itertools import combinations_with_replacement

import numpy as np
from scipy import sparse
from scipy.optimize import lsq_linear, minimize_scalar

from ..numerics.spectrum import spectrum
from ..physics.ball_guides import ball_row
from ..physics.rigs import friction_laws
from ..physics.ball_guides import ball_to_ball as b2b
from ..physics.roller_guide.friction import CoulombParams, coulomb_friction
from ..physics.dynamics import regularised_sign
from .run_io import REDUCED_MODULUS, MeasuredRun
from . import scoring
from .signals import SIGN_WIDTH, Derivation, Motion, smooth_channel

SMOOTHING = 1e-3  # weight of the smoothness penalty of the table candidates


@dataclass
class Context:
    """What the models need over all samples of a run."""

    run: MeasuredRun
    motion: Motion
    y: np.ndarray  # the compared channel
    fixed: np.ndarray  # part of it the baseline knows without fitting (m a or 0)
    velocity_tolerance: float  # m/s, of the regularised sign
    normal_load: float  # N, total load the Coulomb coefficient refers to
    elements: int  # rolling elements per row (1 without [guideway])
    mass: float  # kg, the baseline's moving mass: the stated one, or as the record corrects it
    sign: np.ndarray = field(init=False)
    distance: np.ndarray = field(init=False)
    path: tuple = field(init=False)  # (position [m] along Motion.path, the samples' indices)
    load: np.ndarray | None = field(init=False)  # N, the normal_force channel, smoothed
    load_how: Derivation | None = field(init=False)  # None: not recorded

    def __post_init__(self):
        self.sign = regularised_sign(self.motion.v, self.velocity_tolerance)
        _, x, _, _, at = self.motion.path()
        self.path = (x, at)
        self.distance = friction_laws.running_distance(x)[at]
        self.load, self.load_how = (smooth_channel(self.motion.time, self.run.columns["normal_force"])
                                    if "normal_force" in self.run.columns else (None, None))

    @classmethod
    def of(cls, run: MeasuredRun, motion: Motion, mass: float | None = None) -> "Context":
        """The context of ``run`` driven by ``motion``, its baseline's moving mass ``mass`` [kg]
        (None: the stated one)."""
        guideway = run.sections.get("guideway", {})
        load = run.normal_load()
        mass = run.moving_mass if mass is None else float(mass)
        fixed = mass * motion.a if run.channel == "drive_force" else np.zeros_like(motion.a)
        limit = np.max(np.abs(motion.v)) * SIGN_WIDTH
        return cls(run, motion, np.asarray(run.columns[run.channel], dtype=float), fixed,
                   float(limit), float(max(load, 1.0)), int(guideway.get("elements_per_row", 1)),
                   mass)

    def coulomb_parameters(self, level: float) -> dict:
        """FrictionCoulomb-interface parameters giving the Coulomb level ``level`` [N]."""
        per_element = self.normal_load / (4 * self.elements)
        return {"coefficient": level / self.normal_load, "rollers_per_groove": self.elements,
                "velocity_tolerance": self.velocity_tolerance, "F_upper": per_element,
                "F_lower": per_element}


@dataclass
class Fit:
    """A fitted model: prediction over all samples, physical parameters and its FMU form."""

    effect: str
    setting: dict
    coefficients: np.ndarray
    prediction: np.ndarray
    n_parameters: int
    parameters: dict
    fmu: str  # friction FMU name
    fmu_parameters: dict
    rig_mass: float
    offset: float
    uses_position: bool  # the friction FMU takes the feed position x
    #: setting keys whose fitted value lies at an end of the search that is not a physical limit,
    #: after the search was widened once: key -> the end [the key's unit]
    at_bound: dict = field(default_factory=dict)
    #: the part of the prediction known before the fit: its context's ``fixed`` (m a, and the
    #: extensions of effects it was fitted beside)
    known: np.ndarray | None = None

    def bic(self, y: np.ndarray, fit_mask: np.ndarray) -> float:
        """BIC [-] of the prediction against ``y`` on the fit samples."""
        rss = float(np.sum((y - self.prediction)[fit_mask] ** 2))
        return scoring.bic(rss, int(fit_mask.sum()), self.n_parameters)


def extension(ctx: Context, fit: Fit) -> np.ndarray:
    """The part [unit of ctx.y] of ``fit``'s prediction (made on the motion of ``ctx``) beyond
    the baseline's form: less what was known before the fit (Fit.known), its Coulomb level over
    the baseline's column and its offset. What a named effect adds to the model, held fixed while
    another effect is fitted beside it (more_effects.py); every candidate reports its level as
    the parameter "coulomb"."""
    level = float(fit.parameters["coulomb"]) * BASELINE.coulomb_column(ctx, ctx.motion.v)
    return fit.prediction - fit.known - level - fit.offset


def with_fixed(ctx: Context, fixed: np.ndarray) -> Context:
    """``ctx`` with the known part ``fixed`` [unit of ctx.y] in place of its own (the motion's
    derived quantities shared, not computed again)."""
    out = copy(ctx)
    out.fixed = fixed
    return out


def with_offset(columns):
    """The design: ``columns`` (dense, or sparse for a table) and a column of ones (the offset)."""
    ones = np.ones((columns.shape[0], 1))
    if sparse.issparse(columns):
        return sparse.hstack([columns, ones], format="csr")
    return np.column_stack([columns, ones])


def least_squares(rows, rhs, penalty) -> np.ndarray:
    """Coefficients c minimising |rows c - rhs|^2 + |penalty c|^2: by numpy's lstsq, or where
    ``rows`` is sparse (a table's hat columns, two nonzeros a row) by its normal equations, whose
    Gram matrix (k x k) is formed without the dense n x k matrix (1e6 samples x 400 nodes:
    3.2 GB); the table's smoothness penalty keeps it well conditioned."""
    if sparse.issparse(rows):
        gram = (rows.T @ rows).toarray() + penalty.T @ penalty
        return np.linalg.lstsq(gram, rows.T @ rhs, rcond=None)[0]
    return np.linalg.lstsq(np.vstack([rows, penalty]), np.r_[rhs, np.zeros(len(penalty))],
                           rcond=None)[0]


#: effect name -> candidate class, in the order of definition (the order of ties in the ranking)
CANDIDATES: dict[str, type["Candidate"]] = {}


class Candidate:
    """Baseline (effect "none") or one effect: settings, columns and the FMU form."""

    effect = "none"
    signal = "time"  # the signal its residual shows against (plots)
    fmu_name = "FrictionCoulomb"
    law = staticmethod(coulomb_friction)  # the physics law its columns and its FMU evaluate
    uses_position = False  # the friction FMU takes the feed position x
    running_distance = False  # the effect follows the running distance (not the position)
    guide_types: tuple | None = None  # [guideway] types it applies to (None: every rig)
    #: effects whose models this one's contains: named instead where they score within
    #: SCORE_MIN of it (the data do not need the richer model)
    nests: tuple = ()
    continuous: tuple = ()  # setting keys refined between grid values after the grid search
    #: ends of the continuous keys' search that are physical limits, not search bounds:
    #: (key, "low" or "high") pairs (a fit there is not reported as at a bound)
    physical_ends: tuple = ()
    #: factor the search's open ends move out by where a fit lies at one (settings read it)
    WIDER = 10.0

    def __init__(self, reach: float = 1.0):
        self.reach = reach  # 1, or WIDER once the search was widened

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "effect" in cls.__dict__:
            CANDIDATES[cls.effect] = cls

    @classmethod
    def applies(cls, run: MeasuredRun) -> bool:
        """Whether the effect can occur on the rig of ``run``."""
        return (cls.guide_types is None
                or run.sections.get("guideway", {}).get("type") in cls.guide_types)

    def settings(self, ctx: Context) -> list[dict]:
        return [{}]

    def columns(self, ctx: Context, setting: dict) -> np.ndarray:
        """Columns (n, k) of the drive-force contribution of the law's linear parameters."""
        return self.coulomb_column(ctx, ctx.motion.v)[:, None]

    def coulomb_column(self, ctx: Context, v) -> np.ndarray:
        """The drive-force contribution [N] of the law at unit Coulomb level for the feed
        velocity ``v`` [m/s] (the motion's, or the motion moved in time by the delay search)."""
        unit = CoulombParams(coefficient=1.0, rollers_per_groove=1,
                             velocity_tolerance=ctx.velocity_tolerance)  # level 2 (0.25 + 0.25) = 1
        return -self.law(0.25, 0.25, np.asarray(v, dtype=float), unit)

    def physical(self, ctx: Context, setting: dict, coef: np.ndarray) -> tuple[dict, dict] | None:
        """(parameters, friction FMU parameters) of the fitted coefficients, None if unphysical."""
        return self._coulomb(ctx, coef[0])

    def rig_mass(self, ctx: Context, coef: np.ndarray) -> float:
        return ctx.mass

    def interpret(self, ctx: Context, fit: "Fit") -> dict:
        """Physical parameters of a fit too costly to compute for every fold (a model run along
        the record); the workflow adds them to the named effect's parameters."""
        return {}

    def penalty(self, columns) -> np.ndarray:
        """Rows appended to the least-squares system with a zero right-hand side
        (regularisation); none by default."""
        return np.zeros((0, columns.shape[1]))

    @staticmethod
    def _coulomb(ctx, level):
        if level < 0.0:
            return None
        return {"coulomb": float(level)}, ctx.coulomb_parameters(float(level))

    def _evaluate(self, ctx: Context, fit_mask: np.ndarray, setting: dict):
        """(BIC on the fit samples, coefficients, design) of one setting."""
        target = ctx.y - ctx.fixed
        design = with_offset(self.columns(ctx, setting))
        rows, rhs = design[fit_mask], target[fit_mask]
        penalty = self.penalty(rows[:, :-1])
        coef = least_squares(rows, rhs, np.column_stack([penalty, np.zeros(len(penalty))]))
        rss = float(np.sum((rows @ coef - rhs) ** 2))
        return scoring.bic(rss, int(fit_mask.sum()), self.dof(coef, setting)), coef, design

    def dof(self, coef: np.ndarray, setting: dict) -> int:
        """Parameters a fit with these coefficients (offset last) and setting counts."""
        return coef.size + len(setting)

    def _refine(self, ctx, fit_mask, grid, best):
        """Each key of ``continuous`` of the best grid setting, in turn, to the BIC minimum on
        the fit samples between its grid neighbours among the settings that share its other
        keys outside ``continuous`` (bounded Brent search in its logarithm)."""
        fixed = [k for k in best[1] if k not in self.continuous]
        grid = [s for s in grid if all(s.get(k) == best[1][k] for k in fixed)]
        for key in self.continuous:
            values = sorted({s[key] for s in grid})
            i = values.index(best[1][key])
            lo, hi = values[max(i - 1, 0)], values[min(i + 1, len(values) - 1)]
            if lo == hi:
                continue

            def bic(log_value, key=key):
                return self._evaluate(ctx, fit_mask, {**best[1], key: float(np.exp(log_value))})[0]

            found = minimize_scalar(bic, bounds=(np.log(lo), np.log(hi)), method="bounded",
                                    options={"xatol": 1e-3})
            setting = {**best[1], key: float(np.exp(found.x))}
            bic, coef, design = self._evaluate(ctx, fit_mask, setting)
            phys = self.physical(ctx, setting, coef[:-1]) if bic < best[0] else None
            if phys is not None:
                best = (bic, setting, coef, design, phys)
        return best

    def family(self, setting: dict):
        """The law a setting belongs to: the grid's best setting of each law is refined (a law
        whose grid misses its optimum must not lose to another's grid point)."""
        return None

    def at_bound(self, grid: list[dict], setting: dict) -> dict:
        """Keys of ``setting`` at an end of their values over ``grid`` that is not one of
        ``physical_ends``: key -> the end."""
        out = {}
        for key in self.continuous:
            values = [g[key] for g in grid if key in g]
            if key not in setting or len(set(values)) < 2:
                continue
            for end, value in (("low", min(values)), ("high", max(values))):
                if (key, end) not in self.physical_ends and np.isclose(setting[key], value,
                                                                        rtol=1e-6, atol=0.0):
                    out[key] = float(value)
        return out

    def fit(self, ctx: Context, fit_mask: np.ndarray) -> Fit | None:
        """Best setting by BIC on the fit samples (grid, then ``continuous`` keys refined, per
        :meth:`family`); None if every setting is unphysical. A best setting at an open end of
        the search (:meth:`at_bound`) is sought again over a search WIDER at its open ends, and
        the better of the two fits by BIC kept; a fit still at an open end says so in
        Fit.at_bound."""
        fitted = self._fit(ctx, fit_mask)
        if fitted is None or not fitted.at_bound or self.reach != 1.0:
            return fitted
        wider = type(self)(self.WIDER)._fit(ctx, fit_mask)
        if wider is None:
            return fitted
        if fitted.bic(ctx.y, fit_mask) < wider.bic(ctx.y, fit_mask):
            # the two grids are not nested: the wider search looked beyond the first one's end
            # and found nothing better there, so that end did not bind
            return replace(fitted, at_bound={})
        return wider

    def _fit(self, ctx: Context, fit_mask: np.ndarray) -> Fit | None:
        grid = self.settings(ctx)
        bests = {}
        for setting in grid:
            bic, coef, design = self._evaluate(ctx, fit_mask, setting)
            key = self.family(setting)
            if key in bests and bic >= bests[key][0]:
                continue
            phys = self.physical(ctx, setting, coef[:-1])
            if phys is not None:
                bests[key] = (bic, setting, coef, design, phys)
        if not bests:
            return None
        _, setting, coef, design, (params, fmu_params) = min(
            (self._refine(ctx, fit_mask, grid, best) for best in bests.values()),
            key=lambda refined: refined[0])
        params = {**params, **{key: value for key, value in setting.items()},
                  "offset": float(coef[-1])}
        k = self.dof(coef, setting)
        return Fit(self.effect, setting, coef, ctx.fixed + design @ coef, k, params,
                   self.fmu_name, fmu_params, self.rig_mass(ctx, coef), float(coef[-1]),
                   self.uses_position, self.at_bound(grid, setting), ctx.fixed)


class Lubrication(Candidate):
    """Stribeck + viscous friction; settings: Stribeck velocity, shape and viscous exponents."""

    effect, signal, fmu_name = "lubrication", "speed", "FrictionStribeck"
    law = staticmethod(friction_laws.stribeck_friction)
    continuous = ("stribeck_velocity",)

    def settings(self, ctx):
        vmax = float(np.max(np.abs(ctx.motion.v)))
        wider = np.log10(self.reach)
        return [{"stribeck_velocity": float(vs), "stribeck_exponent": d, "viscous_exponent": b}
                for vs in vmax * np.logspace(-2.5 - wider, wider, 12 + int(round(8.8 * wider)))
                for d in (0.7, 1.0, 2.0) for b in (0.5, 0.75, 1.0)]

    def columns(self, ctx, setting):
        v, tol = ctx.motion.v, ctx.velocity_tolerance
        shape = (setting["stribeck_velocity"], setting["stribeck_exponent"], setting["viscous_exponent"])
        unit = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]  # coulomb, static, viscous
        return np.column_stack([-self.law(v, c, s, shape[0], cv, tol, shape[1], shape[2])
                                for c, s, cv in unit])

    def physical(self, ctx, setting, coef):
        coulomb, static, viscous = (float(c) for c in coef)
        if coulomb < 0.0 or static < 0.0:
            return None
        params = {"coulomb": coulomb, "static": static, "viscous": viscous}
        fmu = {**ctx.coulomb_parameters(coulomb), "static_coefficient": static / ctx.normal_load,
               **setting, "viscous": viscous}
        return params, fmu


class PreslidingHysteresis(Candidate):
    """Up to three Dahl elements in parallel (a Maxwell-slip of Dahl elements); settings: their
    pre-sliding distances (equal distances make one element). Two exponential elements miss the
    long, power-law-like build-up of measured pre-sliding; a third takes it."""

    effect, signal, fmu_name, uses_position = ("presliding_hysteresis", "displacement_since_reversal",
                                               "FrictionDahl", True)
    law = staticmethod(friction_laws.dahl_friction)
    continuous = ("presliding_distance", "second_distance", "third_distance")
    keys = continuous
    #: the least distance is the rigid limit (a switch within a sample), and a build-up over a
    #: whole stroke is the longest a record can show
    physical_ends = tuple((k, "low") for k in keys)
    _states: tuple = ()
    _grams: tuple = ()

    def z_start(self, ctx) -> float:
        return float(np.sign(ctx.motion.v[0])) if not ctx.motion.standstill[0] else 0.0

    def distances(self, ctx):
        """12 pre-sliding distances [m]: 11 geometric, from a thousandth of the median motion
        per sample (a distance of a few encoder counts still shows in the samples right after a
        reversal) to a tenth of the stroke (13 to the whole stroke in a widened search: a
        build-up longer than a stroke is what no record can show), and a thousandth of the
        least of them, a rigid element: it switches within the first sample that moves at all, as the Coulomb part of
        friction does where a rig starts from a dwell at a few nm per sample."""
        step = np.median(np.abs(np.diff(ctx.motion.x)))
        stroke = np.ptp(ctx.motion.x)
        lowest = max(1e-3 * step, 1e-7 * stroke, 1e-10)
        highest = max(min(0.1 * self.reach, 1.0) * stroke, 1e-8)
        count = 11 if self.reach == 1.0 else 13  # a widened search adds about the grid's ratio
        return np.r_[1e-3 * lowest, np.geomspace(lowest, highest, count)]

    def settings(self, ctx):
        d = self.distances(ctx)
        return [dict(zip(self.keys, map(float, d[list(ijk)])))
                for ijk in combinations_with_replacement(range(d.size), 3)]

    def state(self, ctx, distance):
        if not self._states or self._states[0] is not ctx:
            d = self.distances(ctx)
            z = friction_laws.dahl_state(ctx.path[0], d, self.z_start(ctx))[ctx.path[1]]
            self._states = (ctx, {float(v): z[:, i] for i, v in enumerate(d)})
        cache = self._states[1]
        if distance not in cache:  # off the grid (refinement)
            cache[distance] = friction_laws.dahl_state(ctx.path[0], distance,
                                                          self.z_start(ctx))[ctx.path[1]]
        return cache[distance]

    def _evaluate(self, ctx, fit_mask, setting):
        """As :meth:`Candidate._evaluate`, but from the Gram matrix of the grid's states on the
        fit samples where every distance of ``setting`` lies on the grid (the 364 settings of the
        grid search cost a 4 x 4 solve each, not a least-squares pass over the samples)."""
        elements = self._elements(setting)
        if not self._grams or self._grams[0] is not ctx or self._grams[1] is not fit_mask:
            d = [float(v) for v in self.distances(ctx)]
            rows = np.column_stack([self.state(ctx, v)[fit_mask] for v in d]
                                   + [np.ones(int(fit_mask.sum()))])
            target = (ctx.y - ctx.fixed)[fit_mask]
            self._grams = (ctx, fit_mask, {v: i for i, v in enumerate(d)}, rows.T @ rows,
                           rows.T @ target, float(target @ target))
        _, _, where, gram, rhs, power = self._grams
        if any(d not in where for d in elements):  # off the grid (refinement)
            return super()._evaluate(ctx, fit_mask, setting)
        pick = [where[d] for d in elements] + [len(where)]
        g, b = gram[np.ix_(pick, pick)], rhs[pick]
        coef = np.linalg.lstsq(g, b, rcond=None)[0]  # a state may repeat another or the ones
        rss = float(power - 2.0 * coef @ b + coef @ g @ coef)
        design = with_offset(self.columns(ctx, setting))
        return scoring.bic(rss, int(fit_mask.sum()), design.shape[1] + len(setting)), coef, design

    @staticmethod
    def _elements(setting) -> list:
        """The distinct distances of ``setting`` in key order: one column, one level each."""
        return list(dict.fromkeys(setting[k] for k in PreslidingHysteresis.keys))

    def columns(self, ctx, setting):
        return np.column_stack([-self.law(self.state(ctx, d), 1.0)
                                for d in self._elements(setting)])

    def physical(self, ctx, setting, coef):
        levels = dict(zip(self._elements(setting), (float(c) for c in coef)))
        if min(levels.values()) < 0.0 or sum(levels.values()) <= 0.0:
            return None
        level = sum(levels.values())
        d_1, d_2, d_3 = (setting[k] for k in self.keys)  # a level goes to its first key
        second = levels[d_2] / level if d_2 != d_1 else 0.0
        third = min(levels[d_3] / level, 1.0 - second) if d_3 not in (d_1, d_2) else 0.0
        params = {"coulomb": level, "second_share": second, "third_share": third}
        fmu = {**ctx.coulomb_parameters(level), **setting, "second_share": second,
               "third_share": third, "z_start": self.z_start(ctx)}
        return params, fmu


class _Table(Candidate):
    """Coulomb level times a factor interpolated between equally spaced nodes of a signal;
    settings: the number of nodes."""

    law = staticmethod(friction_laws.position_dependent_friction)

    def along(self, ctx) -> np.ndarray:
        """The signal the table is over, at the samples."""
        return ctx.motion.x

    def node_counts(self, ctx):
        return (3, 5, 9, 17, 33, 65, 129)

    def settings(self, ctx):
        return [{"nodes": k} for k in self.node_counts(ctx)]

    def columns(self, ctx, setting):
        """Sparse (n, nodes): the law at the unit factor of each node, nonzero between its
        neighbours only (dense, 1e6 samples x 400 nodes would take 3.2 GB)."""
        s = self.along(ctx)
        at, node, value = [], [], []
        for k, row in enumerate(np.eye(setting["nodes"])):
            column = -self.law(ctx.motion.v, s, 1.0, s.min(), s.max(), row,
                               ctx.velocity_tolerance)
            nonzero = np.flatnonzero(column)
            at.append(nonzero)
            node.append(np.full(nonzero.size, k))
            value.append(column[nonzero])
        return sparse.csr_matrix((np.concatenate(value), (np.concatenate(at),
                                                          np.concatenate(node))),
                                 shape=(s.size, setting["nodes"]))

    def penalty(self, columns):
        """Second differences of the node values, weighted by SMOOTHING of the columns' mean
        square: nodes the fit samples do not reach follow their neighbours linearly."""
        weight = np.sqrt(SMOOTHING * float(columns.multiply(columns).sum()) / columns.shape[1])
        return weight * np.diff(np.eye(columns.shape[1]), 2, axis=0)

    def physical(self, ctx, setting, coef):
        level = float(np.mean(coef))
        if level <= 0.0:
            return None
        s, factors = self.along(ctx), coef / level
        params = {"coulomb": level, "factor_min": float(factors.min()),
                  "factor_max": float(factors.max())}
        fmu = {**ctx.coulomb_parameters(level), "table_start": float(s.min()),
               "table_end": float(s.max()), "factors": " ".join(repr(float(f)) for f in factors)}
        return params, fmu


class PositionDependent(_Table):
    """Coulomb level varying along the rail (table over the position)."""

    effect, signal, fmu_name, uses_position = ("position_dependent_friction", "position",
                                               "FrictionPositionDependent", True)


class UnmodeledMass(Candidate):
    """A mass term missing from the rig: extra_mass * a."""

    effect, signal = "unmodeled_mass", "acceleration"

    def columns(self, ctx, setting):
        return np.column_stack([super().columns(ctx, setting)[:, 0], ctx.motion.a])

    def physical(self, ctx, setting, coef):
        if coef[1] <= 0.0:  # no missing effect takes inertia away: a stated mass too large is
            return None  # a baseline error (decide.corrected_mass)
        params, fmu = self._coulomb(ctx, float(coef[0])) or (None, None)
        return None if params is None else ({**params, "extra_mass": float(coef[1])}, fmu)

    def rig_mass(self, ctx, coef):
        return ctx.mass + float(coef[1])


class PreloadLoss(Candidate):
    """Coulomb level drifting down with the running distance, by a law of
    :func:`friction_laws.preload_loss_factor`: the empirical exponential decay, wear taking
    the preload away at a steady rate (its share of the level following Q_0 ~ delta_0^n, n by
    the [guideway] type), or any monotone loss (table: the level piecewise linear over equally
    spaced distances, never rising, fitted by bounded least squares; its parameters counted
    by the nodes at which it falls, the degrees of freedom of a monotone fit). Settings: the
    law and its distance (the decay distance, or the running distance at which the preload is
    gone, which a user can plan maintenance by), or the table's nodes. The monotone table
    tells a preload that drifts down in a shape no law foresees from the irregular variation
    of ball-to-ball contact, which a free table over the same distance also fits."""

    effect, signal, fmu_name, uses_position = ("preload_loss", "running_distance",
                                               "FrictionPreloadLoss", True)
    law = staticmethod(friction_laws.preload_loss_friction)
    running_distance = True
    continuous = ("wear_distance",)
    TABLE_NODES = (3, 4, 5, 7, 9, 12, 17)  # node counts of the monotone table, about sqrt 2 apart

    @staticmethod
    def exponent(ctx) -> float:
        """n of Q_0 ~ delta_0^n: 10/9 for Palmgren's rollers, 1.5 for Hertz balls."""
        return 10 / 9 if ctx.run.sections.get("guideway", {}).get("type") == "roller" else 1.5

    def settings(self, ctx):
        total = max(float(ctx.distance[-1]), 1e-9)
        wider = np.log10(self.reach)
        return ([{"law": "exponential", "wear_distance": float(total * f)}
                 for f in np.logspace(-1.5 - wider, 1.5 + wider, 13 + 8 * int(round(wider)))]
                + [{"law": "wear", "wear_distance": float(total * f)}
                   for f in np.logspace(-0.3, 1.5 + wider, 10 + 5 * int(round(wider)))]
                + [{"law": "table", "wear_distance": total, "nodes": k} for k in self.TABLE_NODES])

    def columns(self, ctx, setting):
        v, d, w, tol = ctx.motion.v, ctx.distance, setting["wear_distance"], ctx.velocity_tolerance
        law, n = setting["law"], self.exponent(ctx)
        kept = -self.law(v, d, 1.0, 0.0, w, tol, law, n)  # level 1 throughout
        if law == "table":  # a drop of the level from each node to the next, linear between
            ramps = np.eye(setting["nodes"])[1:].cumsum(axis=1)  # node j on: 0 .. 0 1 .. 1
            return np.column_stack([kept] + [-self.law(v, d, 1.0, 1.0, w, tol, law, n, ramp) - kept
                                             for ramp in ramps])
        fading = -self.law(v, d, 1.0, 1.0, w, tol, law, n)  # exp(-D / w) or (1 - D / w)_+^n
        return np.column_stack([kept, fading])

    def _evaluate(self, ctx, fit_mask, setting):
        """As :meth:`Candidate._evaluate`; the table's drops bounded at 0 (the level never
        rises), its parameters the level, the offset and the drops that are not 0."""
        if setting["law"] != "table":
            return super()._evaluate(ctx, fit_mask, setting)
        target = ctx.y - ctx.fixed
        design = with_offset(self.columns(ctx, setting))
        lower = np.r_[-np.inf, np.zeros(design.shape[1] - 2), -np.inf]
        coef = lsq_linear(design[fit_mask], target[fit_mask], bounds=(lower, np.inf)).x
        rss = float(np.sum((design[fit_mask] @ coef - target[fit_mask]) ** 2))
        return scoring.bic(rss, int(fit_mask.sum()), self.dof(coef, setting)), coef, design

    def family(self, setting):
        return setting["law"]

    def dof(self, coef, setting):
        if setting["law"] != "table":
            return super().dof(coef, setting)
        # the level, the offset, the drops that are not 0 and the node count (the table's
        # distance is the record's, not fitted)
        return 3 + int(np.sum(coef[1:-1] > 1e-9 * max(abs(coef[0]), 1e-300)))

    def physical(self, ctx, setting, coef):
        """Besides the law's own numbers, what a user can plan by: the initial decay rate of the
        level [1/m]; where the law is wear, the preload's share of the level and the running
        distance at which the preload is gone as fitted; otherwise, where [guideway] gives the
        preload, its share of the rig's load (preload + weight + normal force) and the distance
        at which steady wear at that initial rate would take it (D_loss = share n / rate)."""
        w, n, law = setting["wear_distance"], self.exponent(ctx), setting["law"]
        fmu_extra = {}
        if law == "table":
            drops = np.asarray(coef[1:], dtype=float)
            start, lost = float(coef[0]), float(np.sum(drops))
            if start <= 0.0 or lost <= 0.0 or lost >= start:
                return None
            profile = np.r_[0.0, np.cumsum(drops) / lost]
            profile[-1] = 1.0
            loss, rate = lost / start, float(drops[0]) / (start * w / (setting["nodes"] - 1))
            fmu_extra = {"profile": " ".join(repr(float(p)) for p in profile)}
        else:
            start = float(coef[0] + coef[1])  # level at D = 0
            if start <= 0.0 or coef[0] < 0.0:
                return None
            loss = float(coef[1]) / start
            rate = loss * n / w if law == "wear" else loss / w
        params = {"coulomb": start, "loss": loss, "initial_decay_rate": rate}
        if law == "wear":
            if not 0.0 <= loss <= 1.0:
                return None  # the preload's share of the friction
            params.update(preload_share=loss, distance_to_preload_loss=w)
        else:
            preload = float(ctx.run.sections.get("guideway", {}).get("preload", 0.0))
            if preload > 0.0 and rate > 0.0:
                share = min(preload / ctx.normal_load, 1.0)
                params.update(preload_share=share, distance_to_preload_loss=share * n / rate)
        fmu = {**ctx.coulomb_parameters(start), "loss": loss, "wear_distance": w, "law": law,
               "load_exponent": n, **fmu_extra}
        return params, fmu


class BallToBall(_Table):
    """Coulomb level varying irregularly with the running distance, nodes 1 to 4 ball diameters
    apart in steps of sqrt 2 (ball guides only). The fitted rise is read through the physical
    row model as a contact-angle deviation of the grooves (:meth:`deviation`)."""

    effect, signal, fmu_name, uses_position = ("ball_to_ball_contact", "running_distance",
                                               "FrictionBallToBall", True)
    law = staticmethod(friction_laws.ball_to_ball_friction)
    running_distance = True
    guide_types = ("ball",)
    nests = ("preload_loss",)  # a free table over the running distance holds any monotone drift
    #: what a rig file does not state, for the deviation: the grooves' conformity, the
    #: friction between balls, the load zone's clearance (its length over balls x diameter,
    #: minus 1), the probe's deviation amplitude [rad] and the samples the row is run at
    CONFORMITY, CONTACT_FRICTION, CLEARANCE = 0.52, 0.1, 0.02
    PROBE, SIMULATED = float(np.radians(1.0)), 1000

    def along(self, ctx):
        return ctx.distance

    def node_counts(self, ctx):
        diameter = 2.0 * float(ctx.run.sections["guideway"]["element_radius"])
        total = float(ctx.distance[-1])
        return sorted({int(np.clip(total / (k * diameter), 2, 400)) + 1
                       for k in np.geomspace(1.0, 4.0, 5)})

    @staticmethod
    def wavelength(factors, spacing: float) -> float:
        """The groove wave's length [m] the fitted level shows: a ball's rail position advances
        half the carriage's running distance, so the level repeats over twice the wavelength;
        half the period of the factors' strongest Fourier component (nodes ``spacing`` [m]
        apart; the highest line of numerics.spectrum without a window, which keeps the end
        nodes of a short table: only where it lies matters), at least one node spacing."""
        frequency, amplitude = spectrum(spacing * np.arange(factors.size), factors,
                                        window="rectangular")
        return float(max(0.5 / frequency[1 + int(np.argmax(amplitude[1:]))], spacing))

    def interpret(self, ctx, fit) -> dict:
        """The ball-to-ball friction the fit shows (the mean rise of the level over its lowest
        node [N]) and the contact-angle deviation [deg] that gives it in the physical model:
        each of the [guideway] rows a row of balls (physics/ball_guides/ball_row.py), packed against the
        load zone's rear end, whose grooves' contact angles wave (BL sine, BR cosine) with the
        length the level shows (:meth:`wavelength`), run along the record's motion; its friction grows in
        proportion to the amplitude, so one probe amplitude scales to the fitted rise. Empty
        where nothing rose."""
        factors = friction_laws.parse_factors(fit.fmu_parameters["factors"])
        rise = fit.parameters["coulomb"] * float(factors.mean() - factors.min())
        guideway = ctx.run.sections["guideway"]
        if rise <= 0.0:
            return {}
        rows = int(guideway.get("rows", 4))
        balls = int(guideway.get("elements_per_row", 2))
        radius = float(guideway["element_radius"])
        spacing = float(ctx.distance[-1]) / (fit.setting["nodes"] - 1)
        nu = 0.3
        bearing = b2b.Bearing(radius, self.CONFORMITY,
                              float(guideway.get("reduced_modulus", REDUCED_MODULUS)) * (1 - nu**2), nu,
                              self.CONTACT_FRICTION,
                              np.radians(float(guideway.get("contact_angle_deg", 45.0))), 1.0)
        row = ball_row.BallRow(bearing, max(balls, 2), max(balls, 2) * 2 * radius
                               * (1 + self.CLEARANCE), np.zeros(4), self.PROBE,
                               self.wavelength(factors, spacing), ctx.velocity_tolerance)
        pick = np.unique(np.linspace(0, ctx.motion.time.size - 1, self.SIMULATED).astype(int))
        probe = np.abs(ball_row.friction_history(row, ctx.motion.time[pick], ctx.motion.x[pick],
                                                 ctx.motion.v[pick], ctx.normal_load / rows,
                                                 packed=True))
        # the probe's level over the same nodes, its rise measured as the fit's
        nodes = fit.setting["nodes"]
        where = np.clip(np.rint(ctx.distance[pick] / spacing).astype(int), 0, nodes - 1)
        level = np.array([probe[where == k].mean() for k in range(nodes) if np.any(where == k)])
        per_degree = rows * float(level.mean() - level.min()) / np.degrees(self.PROBE)
        out = {"ball_to_ball_friction": rise}
        if per_degree > 0.0:
            out["contact_angle_deviation_deg"] = float(rise / per_degree)
        return out


BASELINE = Candidate()
#: effects that follow the running distance: on a record passing its positions once they look
#: like position dependence
RUNNING_DISTANCE_EFFECTS = tuple(e for e, c in CANDIDATES.items() if c.running_distance)


def candidates_for(run: MeasuredRun) -> list[Candidate]:
    """The registered candidate extensions that apply to the rig of ``run``."""
    return [cls() for cls in CANDIDATES.values() if cls.applies(run)]
