"""The discrepancy workflow for vertical responses (docs/measured-run.md, "For vertical runs").

**The model** is the vertical rig of FMUs (scenarios.vertical_rig), coupled as the paper
scenarios: FeedKinematics (the measured motion replayed) -> the contact's feed velocity;
ForceTable (the measured normal force) -> VerticalDynamics.F_ext; VerticalDynamics <-> the
contact named in [model] (dry_hertz: ContactDryHertz, ehl: ContactEHL, whose film follows eq. 4
with its squeeze term), with the contact's tangent and force law handed to the carriage. What
the format fixes, mapped to it:

* the moving mass is VerticalDynamics' mass, gravity along y (along normal_force);
* rows / 2 rows of elements_per_row rollers above the moving part and as many below, each
  element carrying preload / (rows x elements_per_row) along its normal at rest: the contact
  FMUs have two grooves of N rollers on each side sharing their F0 among 4 N rollers, so
  N = rows x elements_per_row / 4 and F0 = preload (:func:`contact_geometry`; the rig's
  stiffness rows x elements_per_row x sin^2(theta) x (10/9) Q0 / delta0, eq. 14 for 4 rows;
  an odd count of rollers per side is taken as twice as many half rollers);
* rollers follow Palmgren's law with roller_length; the lubricant's viscosity and
  pressure-viscosity coefficient come from [lubricant], E' from reduced_modulus;
* the record starts at rest in static equilibrium under gravity and the first normal force, the
  film steady at the first feed velocity (VerticalDynamics.y_start);
* the compared channel is the carriage's y (vertical_displacement) or its kinematic y''
  (vertical_acceleration), plus a constant offset: the baseline's calibration;
* a noisy normal force is denoised before it drives the model (signals.denoise_spectrum: the
  model has no damping, and the load cell's white noise would ring it at its natural frequency
  for the whole record), and where the first sample's noise alone would start a free vibration
  above a tenth of the channel's noise, every model is also calibrated in the start's force
  (Setting.start_force, :func:`calibrate`): the record starts in equilibrium under the true
  first force, of which the sample is only a noisy reading.

Ball guides are refused: the contact FMUs model roller rows.

**The decision** (steps 1-4) simulates each model on the sample times with the monolithic
reference's models fused into one right-hand side and integrated by DOP853 from sample to sample
(reference/vertical.py: a few times faster and closer to the exact solution than the generic
assembly's LSODA). Every candidate changes one physical parameter, fitted on the fit samples by
Gauss-Newton steps with a secant slope (a handful of simulations) with the offset solved alongside:

* ``lubricant_film`` (a dry baseline only): the EHL contact, its film law scaled through the
  lubricant's viscosity (the film grows as its 0.7th power);
* ``preload_loss``: the preload times a factor in (0, 1];
* ``unmodeled_mass``: an extra mass.

Scores are BIC improvements on the held-out samples, and the naming follows the horizontal
workflow's rules (decide.py: significance, SCORE_MIN, EXPLAINED, UNRESOLVED), with a sparse law
in the feed velocity, the normal force and the residual's peak frequencies for ``unknown``.
**Realisation** co-simulates the named model (or the baseline) through the FMUs with the
stabilised coupling at a macro step of at most COSIM_STEP, halved up to REFINEMENTS times until
its RMS deviation from the decision's model is within REALISED noise floors (an undamped
response near resonance can need a finer step than the paper scenarios' coarsest to follow the
decision's model to the noise).
"""
from __future__ import annotations

import csv
import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..fmu_build import build
from ..cosim import master, system as cosim_system
from ..numerics.spectrum import spectrum, uniform_grid
from ..physics.roller_guide import four_rows as gw
from ..physics.roller_guide import contact_model
from ..physics.roller_guide.carriage import LENGTH_SCALE, STANDARD_GRAVITY
from ..physics.roller_guide.film import LineContact
from ..physics.rigs.force_table import ForceTable
from ..physics.roller_guide.roller_law import EXPONENT, MICRON, palmgren_stiffness
from ..reference.vertical import FusedVertical
from ..scenarios import vertical_rig
from . import locate, regression
from .decide import LAW_EXPLAINED, UNRESOLVED
from .more_effects import Step
from .realise import write_replay
from .run_io import REDUCED_MODULUS, MeasuredRun
from .scoring import (DOUBT, EXPLAINED, NEAR_NOISE, SCORE_MIN, bic, capped, confidence,
                      significant_gap)
from .signals import channel_noise, denoise_spectrum, derive_motion

CONTACT_FMUS = {"dry_hertz": "ContactDryHertz", "ehl": "ContactEHL"}
FMUS = ("FeedKinematics", "ForceTable", "VerticalDynamics", *CONTACT_FMUS.values())
CHANNELS = {"vertical_displacement": ("Carriage.y", "m"),
            "vertical_acceleration": ("Carriage.y_ddot", "m/s2")}
COSIM_STEP = 4e-6  # s, largest macro step of the realisation (the paper scenarios' coarsest)
REFINEMENTS = 2  # halvings of the realisation's macro step at most
#: the realisation's RMS deviation from the decision's model, in noise floors: uncorrelated
#: with the residual, it adds 4.4 % to a gap at the noise (sqrt(1 + 0.3^2))
REALISED = 0.3
INPUT_NOISE_SEED = 0  # of the white noise VerticalRig.input_noise drives the model with
SIMULATIONS = 6  # most simulations a candidate's fit takes
START_STEP = 3.0  # load noise RMS of the start's secant in calibrate
START_MATTERS = 0.1  # free vibration of one load noise RMS at the start, in channel noise RMS
STEP, TRUST = 0.05, 0.7  # the fit's first step and its largest, in its parameter (fit_candidate)
TUNED_SPAN = 0.003  # half-width of the search around the value matching the natural frequency
FREQUENCY_STEPS = 4  # secant steps matching the simulated free-vibration frequency
BRENT_STEPS = 20  # Brent steps of the same match over the candidate's whole range, at most
RESOLUTION = 1e-4  # the reference resolves the compared channel to this share of its range ...
MAX_RTOL = 1e-7  # ... and keeps the phase of an undamped vibration over hundreds of periods


@dataclass(frozen=True)
class Setting:
    """A vertical model's physical parameters: moving mass [kg], contact, the contact FMU's F0
    [N], lubricant viscosity [Pa s] and pressure-viscosity coefficient [1/Pa]; ``start_force``
    [N]: the first normal-force sample's error, which the start's equilibrium corrects."""

    mass: float
    contact: str
    preload: float
    viscosity: float
    pressure_viscosity: float
    start_force: float = 0.0


@dataclass(frozen=True)
class Candidate:
    """One effect: the parameter it fits (its start and bounds, on a log scale or not), how it
    changes a setting, and whether it applies to the baseline."""

    effect: str
    parameter: str
    start: float
    bounds: tuple
    log: bool
    change: object  # (Setting, value) -> Setting

    def applies(self, base: Setting) -> bool:
        return self.effect != "lubricant_film" or base.contact == "dry_hertz"


def candidates(base: Setting) -> list[Candidate]:
    """The vertical candidates for the baseline setting."""
    return [c for c in (
        Candidate("lubricant_film", "viscosity_factor", 1.0, (1e-3, 1e3), True,
                  lambda s, v: dataclasses.replace(s, contact="ehl",
                                                   viscosity=base.viscosity * v)),
        Candidate("preload_loss", "preload_factor", 1.0, (0.02, 1.0), True,
                  lambda s, v: dataclasses.replace(s, preload=base.preload * v)),
        Candidate("unmodeled_mass", "extra_mass", 0.0,
                  (-0.5 * base.mass, 5.0 * base.mass), False,
                  lambda s, v: dataclasses.replace(s, mass=base.mass + v)),
    ) if c.applies(base)]


def contact_geometry(rows: int, elements_per_row: int, roller_length: float) -> dict:
    """The contact FMUs' rollers_per_groove, roller_length [m] and roller_load_1um [N] for
    ``rows`` (even) rows of ``elements_per_row`` rollers, rows / 2 of them on each side.

    The FMUs put 2 grooves of rollers_per_groove rollers on each side and share F0 among all
    4 of them, so rollers_per_groove = rows x elements_per_row / 4 with F0 = preload gives each
    roller preload / (rows x elements_per_row), as the format states. Where that count is not
    whole (an odd number of rollers per side), each roller is taken as two half rollers: twice
    the count, half the roller's Palmgren k (at the same approach each carries half the load)
    and half its length (the film's dimensionless load F / (E' R l), hence the film and its
    load floor, unchanged): the same net force and films; the FMU's F_upper and F_lower are
    then half a roller's load. Palmgren's k (roller_load_1um 0) otherwise."""
    per_side = rows * elements_per_row // 2
    split = 1 if per_side % 2 == 0 else 2
    k = palmgren_stiffness(roller_length) / split
    return {"rollers_per_groove": per_side * split // 2, "roller_length": roller_length / split,
            "roller_load_1um": 0.0 if split == 1 else k * MICRON ** EXPONENT}


class VerticalRig:
    """A vertical run's rig: the motion and load tables its models are driven with (written
    into ``folder``), the baseline setting, and the models' systems and predictions."""

    def __init__(self, run: MeasuredRun, folder: Path, fmu_dir: Path):
        source = run.path / "rig.toml"
        guideway = run.sections.get("guideway", {})
        if guideway.get("type") == "ball":
            raise ValueError(f"{source}: [guideway] key 'type': vertical runs of ball guides are "
                             f"not supported yet (the contact FMUs model roller rows)")
        if "contact" not in run.model:
            raise ValueError(f"{source}: [model] key 'contact' is missing: a vertical_response "
                             f"rig names its contact ('dry_hertz' or 'ehl')")
        motion_channels = {c: run.columns[c] for c in ("feed_position", "feed_velocity")
                           if c in run.inputs}
        self.run, self.fmu_dir = run, Path(fmu_dir)
        self.motion = derive_motion(run.time, motion_channels, None)
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)
        self.replay = write_replay(self.motion, self.folder / "replay.csv")
        if "normal_force" in run.columns:  # its white noise would ring the undamped model
            self.normal, self.load_noise, self.load_kept = denoise_spectrum(
                run.time, run.columns["normal_force"])
        else:
            self.normal = np.full(run.time.size, run.normal_force())
            self.load_noise, self.load_kept = 0.0, 1.0
        self.load = self.folder / "load.csv"
        with self.load.open("w", newline="") as handle:
            writer = csv.writer(handle)
            writer.writerow(["time", "normal_force"])
            writer.writerows(np.column_stack([run.time, self.normal]).tolist())
        lubricant = run.sections.get("lubricant", {})
        rows = int(guideway.get("rows", 4))
        if rows % 2:
            raise ValueError(f"{source}: [guideway] key 'rows': a vertical run needs an even "
                             f"number of rows (half above the moving part, half below), "
                             f"got {rows}")
        self.geometry = {
            **contact_geometry(rows, int(guideway["elements_per_row"]),
                               float(guideway["roller_length"])),
            "contact_angle": math.radians(float(guideway["contact_angle_deg"])),
            "roller_radius": float(guideway["element_radius"])}
        self.e_reduced = float(guideway.get("reduced_modulus", REDUCED_MODULUS))
        self.base = Setting(
            run.moving_mass, run.model["contact"], float(guideway["preload"]),
            float(lubricant.get("viscosity", LineContact.viscosity)),
            float(lubricant.get("pressure_viscosity", LineContact.pressure_viscosity)))
        self.column, self.unit = CHANNELS[run.channel]
        y = np.asarray(run.columns[run.channel], dtype=float)
        span = float(np.ptp(y)) if run.channel == "vertical_displacement" else (
            float(np.ptp(y)) / (2 * math.pi * 5e3) ** 2)  # an acceleration's displacement scale
        self.rtol = float(np.clip(RESOLUTION * span / LENGTH_SCALE, 1e-10, MAX_RTOL))
        self.cache: dict = {}
        self.fused: FusedVertical | None = None  # the last model simulated (its tables reused)
        self._start_matters: bool | None = None

    def contact_parameters(self, setting: Setting) -> dict:
        parameters = {**self.geometry, "preload": setting.preload}
        if setting.contact == "ehl":
            parameters.update(viscosity=setting.viscosity, e_reduced=self.e_reduced,
                              pressure_viscosity=setting.pressure_viscosity)
        return parameters

    def start(self, setting: Setting) -> float:
        """y [m] of the static equilibrium under gravity and the first normal force, the film
        steady at the first feed velocity."""
        return gw.static_displacement(self.guideway(setting), setting.mass * STANDARD_GRAVITY
                                      + float(self.normal[0]) + setting.start_force,
                                      float(self.motion.v[0]), setting.contact == "ehl")

    def guideway(self, setting: Setting) -> gw.Guideway:
        return contact_model.from_parameters(
            **self.contact_parameters(setting), damping=0.0,
            lubricated=setting.contact == "ehl").guideway

    def natural_frequency(self, setting: Setting) -> float:
        """f_n [Hz] of the model linearised at its start: sqrt(K / M) / 2 pi, K the rows'
        quasi-static stiffness there (the film's compliance included)."""
        k = gw.quasi_static_stiffness(self.guideway(setting), self.start(setting),
                                      float(self.motion.v[0]), setting.contact == "ehl")
        return float(np.sqrt(k / setting.mass) / (2 * math.pi))

    def spectrum(self, values, pad: int = 1) -> tuple[np.ndarray, np.ndarray]:
        """numerics.spectrum (f [Hz], amplitude) of ``values`` at the samples, resampled onto
        numerics.uniform_grid of their times, the transform zero-padded ``pad`` times."""
        grid = uniform_grid(self.run.time)
        return spectrum(grid, np.interp(grid, self.run.time, values), pad=pad)

    def measured_natural_frequency(self, y) -> float | None:
        """The record's free-vibration peak [Hz]: the largest of the measured channel's spectrum
        (zero-padded 16 times, the peak's log amplitude fitted by a parabola) within a factor 3
        of the baseline's f_n, away (2 %, at least twice the window's main lobe) from the normal
        force's dominant frequency and its multiples of a half (the rows' nonlinearity makes
        harmonics and half-harmonics of it), and 10 times above the window's leakage of the
        response's load line there (the normal force's spectrum scaled to that line);
        None where no peak stands out (10 times the median there)."""
        f_base = self.natural_frequency(self.base)
        f, amplitude = self.spectrum(y, 16)
        _, load = self.spectrum(self.normal, 16)
        near = (f > f_base / 3) & (f < 3 * f_base)
        line = np.argmax(load[1:]) + 1
        f_load = f[line]
        lobe = 4.0 / (self.run.time[-1] - self.run.time[0])  # twice a Hann window's main lobe
        for k in range(1, 13):
            near &= np.abs(f - 0.5 * k * f_load) > max(0.02 * 0.5 * k * f_load, lobe)
        near &= amplitude > 10 * amplitude[line] / load[line] * load
        if not np.any(near):
            return None
        best = np.flatnonzero(near)[np.argmax(amplitude[near])]
        if not amplitude[best] > 10 * np.median(amplitude[near]) or best in (0, f.size - 1):
            return None
        a, b, c = np.log(amplitude[best - 1: best + 2])
        return float(f[best] + 0.5 * (a - c) / (a - 2 * b + c) * (f[1] - f[0]))

    def system(self, setting: Setting, name: str = "vertical", step: float | None = None):
        """The system of FMUs of ``setting`` (cosim/system.py), at the macro step ``step`` [s]
        (default: at most COSIM_STEP, dividing the median sample interval)."""
        t = self.run.time
        if step is None:
            interval = float(np.median(np.diff(t)))
            step = interval / max(1, math.ceil(interval / COSIM_STEP))
        b = cosim_system.Builder(name, f"{self.run.path.name}: {name}").experiment(
            start=float(t[0]), stop=float(t[-1]), step=float(step), algorithm="stabilised")
        vertical_rig(b, self.fmu_dir.resolve(), CONTACT_FMUS[setting.contact],
                     self.replay.resolve(), self.load.resolve(),
                     {"mass": setting.mass, "y_start": self.start(setting)},
                     self.contact_parameters(setting))
        b.record([self.column, "Carriage.y", "Contact.F_upper", "Contact.h_upper", "Feed.u"])
        b.plots(time=[self.column, "Contact.F_upper"], spectrum=[self.column])
        return b.system()

    def input_noise(self, setting: Setting) -> float:
        """RMS [channel units] of what the normal force channel's noise, left by
        signals.denoise_spectrum, puts into the response of ``setting``: the model driven twice
        with the denoised channel plus independent white noise of the channel's RMS, each
        denoised again, the RMS of the difference over sqrt 2. The model is undamped near its
        natural frequency, where the noise's share piles up over the record's periods. 0 where
        the channel is not recorded or is exact (its noise under signals.NOISY of its range)."""
        if self.load_noise == 0.0:
            return 0.0
        rng = np.random.default_rng(INPUT_NOISE_SEED)
        fused = FusedVertical(self.system(setting), self.fused)
        responses = []
        for _ in range(2):
            noisy = self.normal + self.load_noise * rng.standard_normal(self.normal.size)
            fused.load = ForceTable(self.run.time, denoise_spectrum(self.run.time, noisy)[0])
            responses.append(fused.simulate(self.run.time, self.rtol, [self.column])[self.column])
        return float(np.sqrt(np.mean((responses[0] - responses[1]) ** 2) / 2.0))

    def start_matters(self, y) -> bool:
        """Whether the first normal-force sample's noise starts a free vibration of the baseline
        above START_MATTERS of the channel's noise (``y``'s, signals.channel_noise): the record
        starts at rest in equilibrium under the true first force, which that sample misses by
        its noise, and the model has no damping to forget it. Decided once per rig."""
        if self._start_matters is None:
            self._start_matters = False
            if self.load_noise > 0.0:
                shifted = dataclasses.replace(self.base, start_force=self.load_noise)
                ringing = float(np.std(self.predict(shifted) - self.predict(self.base)))
                self._start_matters = ringing > START_MATTERS * channel_noise(y, (2, 4, 6))
        return self._start_matters

    def predict(self, setting: Setting) -> np.ndarray:
        """The compared channel of ``setting`` at the sample times, without offset (the
        reference's models in one fused right-hand side, reference/vertical.py; cached)."""
        if setting not in self.cache:
            self.fused = FusedVertical(self.system(setting), self.fused)
            self.cache[setting] = self.fused.simulate(self.run.time, self.rtol, [self.column])[
                self.column]
        return self.cache[setting]


@dataclass
class VerticalFit:
    """A fitted vertical model: its setting, prediction (offset included), offset, physical
    parameters and number of fitted numbers."""

    effect: str
    setting: Setting
    prediction: np.ndarray
    offset: float
    parameters: dict
    n_parameters: int


def calibrate(rig: VerticalRig, setting: Setting, y, mask) -> tuple:
    """(setting, prediction, parameters) of ``setting`` calibrated on ``mask``: the
    channel's offset and, where the normal force is noisy (VerticalRig.start_matters), the
    first sample's error (Setting.start_force), both by linear least squares, the start's
    effect by its secant over START_STEP noise RMS of the load (the rows are linear to 1e-4 over
    a few load noise RMS of a preload of kN)."""
    f = rig.predict(setting)
    columns = [np.ones_like(f)]
    if rig.start_matters(y):
        step = START_STEP * rig.load_noise
        columns.append((rig.predict(dataclasses.replace(
            setting, start_force=setting.start_force + step)) - f) / step)
    coefficients, *_ = np.linalg.lstsq(np.column_stack(columns)[mask], (y - f)[mask], rcond=None)
    prediction = f + np.column_stack(columns) @ coefficients
    parameters = {"offset": float(coefficients[0])}
    if len(columns) > 1:
        setting = dataclasses.replace(setting,
                                      start_force=setting.start_force + float(coefficients[1]))
        parameters["start_force"] = setting.start_force
    return setting, prediction, parameters


def fit_baseline(rig: VerticalRig, y, mask) -> VerticalFit:
    setting, prediction, parameters = calibrate(rig, rig.base, y, mask)
    return VerticalFit("none", setting, prediction, parameters["offset"], parameters,
                       len(parameters))


def tuned_start(rig: VerticalRig, candidate: Candidate, y) -> float | None:
    """Where the candidate's fit starts: for a mass or a preload, the value that gives the
    model the record's free-vibration frequency (the response is far from linear in them
    near a resonance: a local fit from the stated value falls into the nearest dip); else,
    or without a clear peak, None."""
    measured = rig.measured_natural_frequency(y)
    if measured is None or candidate.effect not in ("unmodeled_mass", "preload_loss"):
        return None
    simulated = rig.measured_natural_frequency(rig.predict(rig.base))
    # the linearised frequency scaled by the baseline's simulated over its linearised one: the
    # rows stiffen and soften over a large vibration, which shifts the free vibration
    shift = 1.0 if simulated is None else simulated / rig.natural_frequency(rig.base)
    lo, hi = candidate.bounds

    def mismatch(value):
        return shift * rig.natural_frequency(candidate.change(rig.base, value)) - measured

    if mismatch(lo) * mismatch(hi) > 0:
        return None
    return float(brentq(mismatch, lo, hi, rtol=1e-6))


def _frequency_match(rig: VerticalRig, evaluate, measured: float, q_lo: float,
                     q_hi: float) -> float | None:
    """The q in [q_lo, q_hi] whose simulation (``evaluate(q)[1]``) vibrates closest to the
    ``measured`` free-vibration frequency [Hz], by Brent's method over the whole range where
    its ends bracket it (the frequency is monotone in a mass or a preload; its estimate moves
    in steps over small changes of q, which the bisection steps tolerate; where a simulation on
    the way shows no clear peak, the closest match met so far); else None. The secant steps
    from the linearised estimate stall where two estimates are equal."""
    errors = {}

    def error(q):
        if q not in errors:
            peak = rig.measured_natural_frequency(evaluate(q)[1])
            errors[q] = np.nan if peak is None else peak - measured
        return errors[q]

    if not error(q_lo) * error(q_hi) < 0.0:
        return None
    try:
        brentq(error, q_lo, q_hi, xtol=1e-5, maxiter=BRENT_STEPS, disp=False)
    except ValueError:  # a simulation on the way shows no clear peak: the closest one met serves
        pass
    return min((q for q in errors if np.isfinite(errors[q])), key=lambda q: abs(errors[q]))


def fit_candidate(rig: VerticalRig, candidate: Candidate, y, mask) -> VerticalFit:
    """The candidate's parameter q (its log where ``log``, else the extra mass over the stated
    one) with the offset. Where :func:`tuned_start` finds the record's free-vibration frequency,
    a bounded scalar search within TUNED_SPAN of it (the residual's basin around the true value
    is narrow: a free vibration of hundreds of periods dephases within a fraction of a per
    cent of frequency), and again around the value whose simulation vibrates at the measured
    frequency (:func:`_frequency_match`), the least residual kept; else Gauss-Newton,
    y - f(q) ~ J dq + c with J the secant slope of the two best simulations, each step at most
    TRUST. At most SIMULATIONS simulations."""
    lo, hi = candidate.bounds
    to_q = (lambda v: math.log(v)) if candidate.log else (lambda v: v / rig.base.mass)
    from_q = (lambda q: math.exp(q)) if candidate.log else (lambda q: q * rig.base.mass)
    q_lo, q_hi = to_q(lo), to_q(hi)
    seen = {}

    def evaluate(q):  # (q, prediction, sum of squares, calibrated setting, its calibration)
        if q not in seen:
            setting, f, calibration = calibrate(rig, candidate.change(rig.base, from_q(q)),
                                                y, mask)
            seen[q] = (q, f, float(np.sum((y - f)[mask] ** 2)), setting, calibration)
        return seen[q]

    tuned = tuned_start(rig, candidate, y)
    measured = rig.measured_natural_frequency(y)
    if tuned is not None:
        # the simulated free-vibration frequency matched to the measured one (smooth in q,
        # where the residual is not), by secant steps from the linearised estimate
        q_a = float(np.clip(to_q(tuned), q_lo, q_hi))
        q_b = q_a - 0.01 if q_a + 0.01 > q_hi else q_a + 0.01
        pairs = []
        for q in (q_a, q_b):
            peak = rig.measured_natural_frequency(evaluate(q)[1])
            if peak is not None:
                pairs.append((q, peak))
        for _ in range(FREQUENCY_STEPS):
            if len(pairs) < 2 or pairs[-1][1] == pairs[-2][1]:
                break
            (qa, fa), (qb, fb) = pairs[-2:]
            q = float(np.clip(qb + (measured - fb) * (qb - qa) / (fb - fa), q_lo, q_hi))
            if abs(q - qb) < 1e-5:
                break
            peak = rig.measured_natural_frequency(evaluate(q)[1])
            if peak is None:
                break
            pairs.append((q, peak))
        q0 = min(seen.values(), key=lambda p: p[2])[0]
        minimize_scalar(lambda q: evaluate(q)[2], method="bounded",
                        bounds=(max(q0 - TUNED_SPAN, q_lo), min(q0 + TUNED_SPAN, q_hi)),
                        options={"maxiter": SIMULATIONS, "xatol": 1e-5})
        matched = _frequency_match(rig, evaluate, measured, q_lo, q_hi)
        if matched is not None:  # a second basin to look in: the fit keeps the least residual
            minimize_scalar(lambda q: evaluate(q)[2], method="bounded",
                            bounds=(max(matched - TUNED_SPAN, q_lo),
                                    min(matched + TUNED_SPAN, q_hi)),
                            options={"maxiter": SIMULATIONS, "xatol": 1e-5})
    else:
        start = float(np.clip(to_q(candidate.start), q_lo, q_hi))
        points = sorted([evaluate(start),
                         evaluate(start + STEP if start + STEP <= q_hi else start - STEP)],
                        key=lambda p: p[2])
        for _ in range(SIMULATIONS - 2):
            (q1, f1, *_), (q0, f0, *_) = points
            design = np.column_stack([((f1 - f0) / (q1 - q0))[mask], np.ones(int(mask.sum()))])
            (dq, _), *_ = np.linalg.lstsq(design, (y - f1)[mask], rcond=None)
            q = float(np.clip(q1 + np.clip(dq, -TRUST, TRUST), q_lo, q_hi))
            if abs(q - q1) < 1e-3 or abs(q - q0) < 1e-9:
                break
            points = sorted(points + [evaluate(q)], key=lambda p: p[2])[:2]
    q, f, _, setting, calibration = min(seen.values(), key=lambda p: p[2])
    value = from_q(q)
    parameters = {candidate.parameter: value, **calibration}
    if candidate.effect == "preload_loss":  # as the rig file states it, over all elements
        parameters["preload"] = float(rig.run.sections["guideway"]["preload"]) * value
    elif candidate.effect == "lubricant_film":
        parameters["viscosity"] = setting.viscosity
    return VerticalFit(candidate.effect, setting, f, calibration["offset"], parameters,
                       1 + len(calibration))


@dataclass
class VerticalNaming:
    """Steps 1-4 on a vertical run: the data, the models and the decision."""

    run: MeasuredRun
    rig: VerticalRig
    y: np.ndarray
    fit_mask: np.ndarray
    held: np.ndarray
    baseline: VerticalFit
    noise: float
    gap_base: float
    significant: bool
    ranked: list  # (score, VerticalFit, held-out gap), best first
    effect: str
    winner: VerticalFit | None
    equation: str | None
    confidence: float
    frequencies: list
    not_told_apart: list  # effects that explain the record as well as the named one
    doubts: list  # why the confidence was held at scoring.DOUBT (plain sentences)
    #: where ``not_told_apart`` is not empty, the further record that separates the named effect
    #: from the first of them (:func:`separating_experiment`), else None
    experiment: dict | None = None
    corrections: list = dataclasses.field(default_factory=list)  # none refitted yet
    intervals: dict = dataclasses.field(default_factory=dict)  # not computed yet
    steps: list = dataclasses.field(default_factory=list)  # more_effects.Step of the named one


def law_terms(rig: VerticalRig, frequencies) -> dict:
    """Terms of a sparse law for an unexplained vertical residual, by expression over the channel
    names: the feed velocity and speed, the normal force, sinusoids at the residual's peaks."""
    values = {"feed_velocity": rig.motion.v, "normal_force": rig.normal, "time": rig.run.time,
              "sign": np.sign, "sin": np.sin, "cos": np.cos, "pi": np.pi}
    terms = ["1", "feed_velocity", "feed_velocity*sign(feed_velocity)", "normal_force"]
    for f in frequencies:
        terms += [f"sin(2*pi*{f:.6g}*time)", f"cos(2*pi*{f:.6g}*time)"]
    return {t: np.broadcast_to(np.asarray(eval(t, {"__builtins__": {}}, values), dtype=float),
                               rig.run.time.shape) for t in terms}


def decide_vertical(run: MeasuredRun, folder: Path, fmu_dir: Path) -> VerticalNaming:
    """Steps 1-4 on a vertical_response run (module doc). Raises ValueError naming the file and
    key for a run it cannot model."""
    build.ensure(fmu_dir, list(FMUS))
    rig = VerticalRig(run, folder, fmu_dir)
    y = np.asarray(run.columns[run.channel], dtype=float)
    usable = np.ones(y.size, dtype=bool)
    fit_mask, held = locate.split(y.size, usable)
    baseline = fit_baseline(rig, y, fit_mask)
    residual = y - baseline.prediction
    gap_base = locate.gap(y, baseline.prediction, held)
    n_held = int(held.sum())

    def held_out_bic(r, parameters):  # scoring.bic of the residual r on the held-out samples
        return bic(float(np.sum(r[held] ** 2)), n_held, parameters)

    bic_base = held_out_bic(residual, baseline.n_parameters)
    ranked = []
    for candidate in candidates(rig.base):
        fitted = fit_candidate(rig, candidate, y, fit_mask)
        score = bic_base - held_out_bic(y - fitted.prediction, fitted.n_parameters)
        ranked.append((score, fitted, locate.gap(y, fitted.prediction, held)))
    ranked.sort(key=lambda item: -item[0])
    # the noise from the best model's residual: a baseline that misses a vibration near the
    # sampling rate leaves second differences far above the noise (the vibration's own)
    noise = min(locate.noise_floor(y, y - model.prediction, held)
                for model in [baseline] + [fitted for _, fitted, _ in ranked[:1]])
    # with the response to what noise of the load cell the denoised column still holds
    noise = float(np.hypot(noise, rig.input_noise(baseline.setting) / np.ptp(y[held])))
    significant = significant_gap(gap_base, noise, int(held.sum()))

    def share(gap_model):
        return (gap_base**2 - gap_model**2) / max(gap_base**2 - noise**2, 1e-300)

    frequencies = locate.peak_frequencies(run.time, residual, held)
    effect, winner, equation = "none", None, None
    if significant:
        score, best, best_gap = ranked[0] if ranked else (-np.inf, None, gap_base)
        if score > SCORE_MIN and share(best_gap) >= EXPLAINED:
            effect, winner = best.effect, best
        else:
            terms = law_terms(rig, frequencies)
            coefficients = regression.stlsq(terms, residual, fit_mask)
            law = sum((c * terms[t] for t, c in coefficients.items()), np.zeros_like(y))
            law_score = bic_base - held_out_bic(residual - law, 1 + len(coefficients))
            explains = law_score > SCORE_MIN and share(
                locate.gap(y, baseline.prediction + law, held)) >= LAW_EXPLAINED
            if explains or gap_base > UNRESOLVED * noise:
                effect = "unknown"
                equation = " + ".join(f"{c:.6g}*{t}" if t != "1" else f"{c:.6g}"
                                      for t, c in coefficients.items()) or "0"
    scores = {"none": 0.0, **{f.effect: s for s, f, _ in ranked}}
    twins = _not_told_apart(ranked, winner, y, held, share) if winner is not None else []
    for twin in twins:  # the record holds no evidence between them: they share the best score
        scores[twin] = scores[effect]
    stated = confidence(scores, effect)
    doubts = ([f"the gap before any fit is {gap_base / noise:.3g} noise floors, within "
               f"{NEAR_NOISE:g} of it: as likely noise of another colour as an effect"]
              if winner is not None and capped(stated, gap_base, noise) < stated else [])
    fits = {f.effect: f for _, f, _ in ranked}
    experiment = (separating_experiment(rig, winner, fits[twins[0]], noise * float(np.ptp(y)))
                  if twins else None)
    # a second effect is not looked for on vertical runs yet: the named one is the only step
    steps = ([Step(effect, winner, [winner], best_gap, score, best_gap)] if winner is not None
             else [])
    return VerticalNaming(run, rig, y, fit_mask, held, baseline, noise, gap_base, significant,
                          ranked, effect, winner, equation, min(stated, DOUBT) if doubts else stated,
                          frequencies, twins, doubts, experiment, steps=steps)


#: least second static load of the separating experiment, over the preload: a load of the
#: preload's order moves the rows by about as much as the preload did
EXTRA_LOAD = 0.1


def static_response(rig: VerticalRig, setting: Setting, extra: float) -> dict:
    """What ``setting`` predicts for a static test with ``extra`` [N] more normal force than
    the record's start: the displacement's change [m] and the natural frequency [Hz] there
    (sqrt(K / M) / 2 pi, K the rows' quasi-static stiffness, the film's compliance included)."""
    guideway, u, ehl = rig.guideway(setting), float(rig.motion.v[0]), setting.contact == "ehl"
    start = rig.start(setting)
    loaded = gw.static_displacement(guideway, setting.mass * STANDARD_GRAVITY
                                    + float(rig.normal[0]) + setting.start_force + extra, u, ehl)
    k = gw.quasi_static_stiffness(guideway, loaded, u, ehl)
    return {"displacement_change": float(loaded - start),
            "natural_frequency": float(np.sqrt(k / setting.mass) / (2 * math.pi))}


def separating_experiment(rig: VerticalRig, first: VerticalFit, second: VerticalFit,
                          noise: float) -> dict:
    """The further record that tells ``first`` from ``second`` apart, two fits the record
    cannot (they meet in the natural frequency sqrt(k / m) at its load): the same rig at rest
    under a second static load, the record's static load (its weight and mean normal force)
    again on top, at least EXTRA_LOAD of the baseline's preload. A static load deflects the
    rows by about load / k, apart from the mass: twins with k / m alike deflect in the ratio of
    their masses, while their frequencies part only as far as the rows' stiffness grows with
    the load (little for Palmgren's rollers). Both fits' predictions for it
    (:func:`static_response`), and how far apart they are: the displacement change's difference
    over the record's noise ``noise`` [m; None for an acceleration record] and the natural
    frequencies' relative difference. ``record`` says it in words."""
    extra = max(float(abs(first.setting.mass * STANDARD_GRAVITY + np.mean(rig.normal))),
                EXTRA_LOAD * rig.base.preload)
    predicted = {f.effect: static_response(rig, f.setting, extra) for f in (first, second)}
    a, b = predicted[first.effect], predicted[second.effect]
    return {"between": [first.effect, second.effect],
            "record": (f"the same rig at rest under {extra:.4g} N more normal force (the record's "
                       f"static load again on top): its static displacement and the frequency "
                       f"it rings at when tapped"),
            "predictions": predicted,
            "displacement_apart_in_noise": float(abs(a["displacement_change"]
                                                     - b["displacement_change"]) / noise)
            if rig.run.channel == "vertical_displacement" and noise > 0.0 else None,
            "frequency_apart": float(abs(a["natural_frequency"] - b["natural_frequency"])
                                     / max(a["natural_frequency"], b["natural_frequency"]))}


def _not_told_apart(ranked, winner, y, held, share) -> list[str]:
    """Effects besides ``winner`` that explain the record too (share of EXPLAINED) and score
    within SCORE_MIN of it in independent samples (the BIC difference over the integrated
    autocorrelation time of the winner's held-out residual). Stiffness and mass meet in the
    natural frequency sqrt(k / m): a record whose response is dominated by it (ringing, a
    narrow load band) cannot tell a lost preload from an added mass."""
    margin = SCORE_MIN * locate.correlation_time(y - winner.prediction, held)
    top = ranked[0][0]
    return [fitted.effect for score, fitted, gap in ranked
            if fitted is not winner and top - score < margin and share(gap) >= EXPLAINED]


@dataclass
class VerticalRealisation:
    """The named model (or the baseline) co-simulated through the FMUs: the compared channel of
    the baseline and the augmented model at the samples, the scenario and its wall time [s]."""

    baseline: np.ndarray
    augmented: np.ndarray
    scenario: Path
    wall_time: float
    agreement: float  # largest deviation of the co-simulation from the reference / range

    def gaps(self, naming) -> tuple[float, float]:
        y, held = naming.y, naming.held
        return locate.gap(y, self.baseline, held), locate.gap(y, self.augmented, held)


def realise_vertical(naming: VerticalNaming, out: Path) -> VerticalRealisation:
    """Write the named model's scenario (the baseline's for none or unknown) into ``out`` and
    co-simulate it through the FMUs."""
    model = naming.winner or naming.baseline
    name = f"augmented_{naming.effect}" if naming.winner else "baseline"
    path = out / f"{'augmented' if naming.winner else 'baseline'}.toml"
    span, wall, best = float(np.ptp(naming.y)), 0.0, None
    step = naming.rig.system(model.setting, name).experiment.step
    for _ in range(REFINEMENTS + 1):
        cosim_system.dump(naming.rig.system(model.setting, name, step=step), path)
        result = master.simulate(cosim_system.load(path))
        wall += result.wall_time
        rec = result.recording
        cosim = np.interp(naming.run.time, rec.time, rec.columns[naming.rig.column]) + model.offset
        deviation = float(np.sqrt(np.mean((cosim - model.prediction) ** 2))) / span
        if best is None or deviation < best[0]:
            best = (deviation, step, cosim)
        if deviation <= REALISED * naming.noise:
            break
        step /= 2
    deviation, step, cosim = best
    cosim_system.dump(naming.rig.system(model.setting, name, step=step), path)  # the one kept
    agreement = float(np.max(np.abs(cosim - model.prediction)) / span)
    base = naming.baseline.prediction
    return VerticalRealisation(base, cosim if naming.winner else base, path, wall, agreement)
