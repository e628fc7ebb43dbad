"""Truth-model generator: synthetic measured runs with one hidden effect, for testing the workflow.

A run is a directory with rig.toml and data.csv in the measured-run format, version 1
(docs/measured-run.md). The rig is a ``horizontal_drive`` positioning axis under
closed-loop position control; the user's baseline is ``[model] friction = "coulomb"``,
``contact = "dry_hertz"`` with the moving mass stated in ``[rig]``. The recorded drive force is

    drive_force = m a + F_c s(v) + H(t) + F_0 + e(t)                                     [N]

m [kg] the stated moving mass, a [m/s^2] and v [m/s] the true acceleration and velocity,
F_c [N] the true Coulomb level, s(v) = tanh(v / v_tol) with v_tol = 1e-4 m/s (the project's
regularised sign), H [N] the hidden effect, F_0 [N] a constant sensor offset and e [N] white
Gaussian noise. Friction is written here as the force the drive must supply (positive along v).

Hidden effects H (their forms differ on purpose from the usual candidate models; S [m] is the
accumulated running distance, the integral of |v| dt; random draws are listed in brackets):

``none``: H = 0.

``lubrication`` (exponential-plus-power Stribeck curve, power-law viscous term):
    H = s(v) [dF_s exp(-(|v| / v_s)^delta) + c_v |v|^beta]
    dF_s [N] scaled to ``size``; v_s [m/s] in [2, 20] mm/s; delta [-] in [0.6, 1.4];
    beta [-] in [0.5, 0.8]; c_v = k_v dF_s / V_max^beta [N (s/m)^beta], k_v [-] in [0.5, 2],
    V_max [m/s] the rig's top speed.

``presliding_hysteresis`` (blend of two generalised Dahl elements, exponent alpha != 1):
    F = F_1 + F_2,  dF_i/dx = (F_ci / x_i) (1 - F_i sgn(dx) / F_ci)^alpha,  H = F - F_c s(v)
    F_c1 = w F_c, F_c2 = (1 - w) F_c, w [-] in [0.3, 0.7]; x_1 [m] scaled to ``size``;
    x_2 = r x_1 [m], r [-] in [3, 10]; alpha [-] in [1.2, 1.8]. Dahl's law is rate independent, so it is
    solved exactly in displacement, per stroke of constant direction, in closed form:
    y = 1 - F_i sgn(dx) / F_ci obeys y(D) = (y_0^(1 - alpha) + (alpha - 1) D / x_i)^(-1/(alpha - 1))
    with D [m] the displacement since the stroke began (no time integration, no step error).
    At standstill F keeps its last value (the drive holds it) while the baseline's s(v) is 0.

``position_dependent_friction`` (a few sinusoids plus a localised raised-cosine bump):
    H = s(v) A [sum_j c_j sin(2 pi x / lambda_j + phi_j) + b (1 + cos(pi (x - x_b) / w_b)) / 2]
    x [m] the true position, the bump only for |x - x_b| < w_b; A [N] scaled to ``size``; three
    wavelengths lambda_j [m] log-uniform in [4 mm, travel / 2]; c_j [-] in [0.3, 1]; b [-] in
    [1, 2]; half-width w_b [m] in [2, 8] mm; centre x_b [m] in [0.2, 0.8] travel.

``unmodeled_mass``: H = dm a, dm [kg] scaled to ``size`` (true mass m + dm).

``preload_loss`` (exponential decay of the friction level with running distance):
    H = -L F_c (1 - exp(-S / s_0)) s(v); L [-] scaled to ``size`` (must stay below 0.95);
    decay distance s_0 [m] in [0.2, 0.6] times the run's total running distance.

``ball_to_ball_contact`` (ball guides; mean rise plus irregular, log-normal variation along S):
    H = s(v) B exp(sigma xi(S) - sigma^2 / 2); B [N] scaled to ``size``; xi a unit Gaussian
    process in S (white noise smoothed by a Gaussian of width l = k 2 R_ball [m], k in [1, 5],
    R_ball the ball radius of [guideway]); sigma [-] in [0.5, 1].

Outside the vocabulary (the workflow must answer ``unknown``):

``normal_load_friction``: friction follows a varying external load N(t) [N] recorded in a
``normal_force`` channel: N = N_0 + dN sum_j c_j sin(2 pi f_j t + phi_j), sum c_j = 1,
f_j [Hz] log-uniform in [0.05, 1] Hz, dN [N] in [0.2, 0.6] N_0, N_0 [N] the [load] normal_force;
H = s(v) mu_N (N - N_0), mu_N [-] scaled to ``size``.

``mains_disturbance``: pick-up on the force sensor, H = A_h [sin(2 pi f t + phi_1)
+ h_3 sin(6 pi f t + phi_3)], t [s], f [Hz] in 50 +- 0.05 Hz, h_3 [-] in [0, 0.3], A_h [N] scaled
to ``size``.

Effect size: the amplitude parameter of H is set so that the part of H that the baseline's free
parameters (Coulomb level and offset) cannot absorb, i.e. the residual of the least-squares fit of
H on {s(v), 1} over the moving samples (|v| > 1 mm/s), has the RMS ``size`` * 0.03 * R, with R [N]
the range of the noise-free baseline force m a + F_c s(v). Noise: e has the standard deviation
``noise`` times the range of the noise-free recorded drive force.

Motion: strokes back and forth with cosine-blended velocity ramps (continuous acceleration),
dwells at standstill before every stroke, several stroke lengths and four speed levels, plus short
jogs (0.1 to 1 mm). The rig quantises the position to the encoder step and computes velocity and
acceleration by centred differences over +- ``derivative_half_window`` samples of the quantised
position, so they carry quantisation noise as a real record does.

Random streams: ``rng`` is split (``Generator.spawn``) into rig, motion, timing, effect and noise
streams, so runs from equally seeded generators share rig, motion and noise whatever the effect.
"""
from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Callable

import numpy as np
from scipy.ndimage import gaussian_filter1d
from scipy.optimize import brentq

from guideway_fmu.physics.papers import soleimanian2020
from guideway_fmu.diagnose.candidates import CANDIDATES

__all__ = [
    "EFFECTS", "EXPECTED", "VISIBLE_FRACTION", "TruthInfo", "SyntheticRun",
    "simulate", "write_run", "make_run", "make_suite", "write_example",
]

FORMAT = "guideway-measured-run/1"
#: RMS of the visible part of a size-1 effect, as a fraction of the baseline force range [-]
VISIBLE_FRACTION = 0.03
VELOCITY_TOLERANCE = 1e-4  # v_tol of s(v) = tanh(v / v_tol) [m/s]
MOVING_SPEED = 1e-3  # samples faster than this [m/s] count as moving
SPEED_LEVELS = (1.0, 0.5, 0.25, 0.1)  # stroke speeds as fractions of the rig's top speed [-]
MAX_LOSS = 0.95  # largest preload (friction) loss fraction allowed [-]
MAX_NOISE = 0.1
MAX_SIZE = 3.0
#: column -> number format in data.csv (fixed point: plain decimal numbers)
_FORMATS = {
    "time": "%.7f", "feed_position": "%.9f", "feed_velocity": "%.8f",
    "feed_acceleration": "%.6f", "normal_force": "%.5f", "drive_force": "%.6f",
    "friction_force": "%.6f",
}


@dataclass(frozen=True)
class TruthInfo:
    """What a synthetic run hides.

    effect: the hidden effect (a key of EXPECTED); expected: the answer the workflow should give;
    parameters: true values (SI units, names in the module docstring: moving_mass [kg] as stated,
    moving_mass_true [kg], coulomb_level [N], offset [N], and the effect's parameters);
    size: requested effect size [-]; noise: noise RMS over the noise-free drive-force range [-];
    noise_rms [N]; effect_rms: RMS over the moving samples of the effect's part the baseline
    cannot absorb [N];
    force_range: range of the noise-free baseline force [N]; channels: data.csv columns after time;
    n_samples; seed: the integer seed where known (``make_suite``), else None.
    """

    effect: str
    expected: str
    parameters: dict
    size: float
    noise: float
    noise_rms: float
    effect_rms: float
    force_range: float
    channels: tuple
    n_samples: int
    seed: int | None = None


@dataclass(frozen=True)
class SyntheticRun:
    """A generated run before writing: info, rig.toml tables, data.csv columns, noise-free truth.

    truth holds time [s], position [m], velocity [m/s], acceleration [m/s^2], running_distance [m],
    baseline (m a + F_c s(v)) [N], hidden (H) [N], noise (e) [N], and moving (bool mask).
    """

    info: TruthInfo
    rig: dict
    columns: dict
    truth: dict = field(repr=False)


# ----------------------------------------------------------------------------------- arguments

def _check(name: str, ok: bool, want: str, value) -> None:
    if not ok:
        raise ValueError(f"{name} must be {want}, got {value!r}")


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _check_arguments(effect, rng, size, noise, n_samples, rate, with_position, with_velocity,
                     encoder_step, offset, derivative_half_window):
    _check("effect", effect in EXPECTED, f"one of {', '.join(EFFECTS)}", effect)
    _check("rng", isinstance(rng, np.random.Generator), "a numpy.random.Generator", rng)
    _check("size", _is_number(size) and 0.0 < size <= MAX_SIZE, f"a number in (0, {MAX_SIZE}]",
           size)
    _check("noise", _is_number(noise) and 0.0 <= noise <= MAX_NOISE,
           f"a number in [0, {MAX_NOISE}]", noise)
    _check("n_samples", isinstance(n_samples, (int, np.integer)) and not isinstance(n_samples, bool)
           and n_samples >= 1000, "an integer >= 1000", n_samples)
    _check("rate", _is_number(rate) and 100.0 <= rate <= 20000.0, "a number in [100, 20000] Hz",
           rate)
    _check("with_position", with_position or with_velocity,
           "True when with_velocity is False (the run needs feed_position or feed_velocity)",
           with_position)
    _check("encoder_step", _is_number(encoder_step) and 0.0 <= encoder_step <= 1e-4,
           "a number in [0, 1e-4] m", encoder_step)
    _check("offset", offset is None or _is_number(offset), "None or a finite number [N]", offset)
    _check("derivative_half_window", isinstance(derivative_half_window, (int, np.integer))
           and not isinstance(derivative_half_window, bool) and 1 <= derivative_half_window <= 50,
           "an integer in [1, 50]", derivative_half_window)


# -------------------------------------------------------------------------------------- motion

@dataclass(frozen=True)
class _Motion:
    """Piecewise cosine blends v(t) from v0 to v1 over T, and strokes of constant direction."""

    t0: np.ndarray  # segment start [s]
    duration: np.ndarray  # T [s]
    v0: np.ndarray  # [m/s]
    v1: np.ndarray  # [m/s]
    x0: np.ndarray  # position at segment start [m]
    stroke_t0: np.ndarray  # stroke start (its leading dwell) [s]
    stroke_dir: np.ndarray  # +1 / -1
    stroke_x0: np.ndarray  # position at stroke start [m]
    stroke_length: np.ndarray  # [m]
    stroke_s0: np.ndarray  # running distance at stroke start [m]

    def evaluate(self, t):
        """Exact x [m], v [m/s], a [m/s^2] at the times t [s] (array)."""
        k = np.searchsorted(self.t0, t, side="right") - 1
        T, v0, dv = self.duration[k], self.v0[k], self.v1[k] - self.v0[k]
        tau = t - self.t0[k]
        s = np.clip(tau / T, 0.0, 1.0)
        x = self.x0[k] + v0 * tau + 0.5 * dv * T * (s - np.sin(np.pi * s) / np.pi)
        v = v0 + 0.5 * dv * (1.0 - np.cos(np.pi * s))
        a = 0.5 * np.pi * dv / T * np.sin(np.pi * s)
        return x, v, a


def _plan_motion(mrng, end_time, travel, v_max, a_max) -> _Motion:
    """Strokes (dwell, ramp up, cruise, ramp down) alternating in direction until ``end_time``.

    A stroke runs a random fraction of the room left on the rail in its direction, or is a jog of
    0.1 to 1 mm (one in four, or when the room is under 5 mm); strokes cycle through the speed
    levels of v_max [m/s] in a random order, and every speed is lowered where the stroke is too
    short to reach it at the acceleration a_max [m/s^2]. The first stroke is shortened to end
    by half the record, and neither it nor the second is a jog unless the rail leaves no room,
    so that every record moves both ways over a stretch: with a jog there, one long stroke
    could fill the record, with a few dozen backward samples, too few to tell the Coulomb level
    from the force offset (the workflow refuses such records: 3 of 72 draws of 4000 samples).
    """
    segments, strokes = [], []
    t, x, s, direction = 0.0, 0.0, 0.0, 1.0
    levels = [SPEED_LEVELS[i] for i in mrng.permutation(len(SPEED_LEVELS))]
    while t <= end_time:
        dwell = mrng.uniform(0.05, 0.25)
        room = travel - x if direction > 0 else x
        level = 1.0
        jog = room < 5e-3 or mrng.random() < 0.25  # drawn for every stroke: streams stay paired
        if jog and (len(strokes) >= 2 or room < 5e-3):
            length = _loguniform(mrng, 1e-4, 1e-3)
        else:
            length = mrng.uniform(0.3, 1.0) * room
            level = levels[len(strokes) % len(levels)]
        speed = min(v_max * level, math.sqrt(2.0 * a_max * length / math.pi))
        ramp = 0.5 * math.pi * speed / a_max
        if not strokes and dwell + ramp + length / speed > 0.5 * end_time:
            length = max((0.5 * end_time - dwell - ramp) * speed, 1e-4)
            speed = min(speed, math.sqrt(2.0 * a_max * length / math.pi))
            ramp = 0.5 * math.pi * speed / a_max
        cruise = length / speed - ramp
        strokes.append((t, direction, x, length, s))
        segments.append((dwell, 0.0, 0.0))
        segments.append((ramp, 0.0, direction * speed))
        if cruise > 1e-9:
            segments.append((cruise, direction * speed, direction * speed))
        segments.append((ramp, direction * speed, 0.0))
        t += dwell + 2.0 * ramp + max(cruise, 0.0)
        x += direction * length
        s += length
        direction = -direction
    T, v0, v1 = (np.array(c) for c in zip(*segments))
    t0 = np.concatenate(([0.0], np.cumsum(T)[:-1]))
    x0 = np.concatenate(([0.0], np.cumsum(0.5 * (v0 + v1) * T)[:-1]))
    st0, sdir, sx0, slen, ss0 = (np.array(c) for c in zip(*strokes))
    return _Motion(t0, T, v0, v1, x0, st0, sdir, sx0, slen, ss0)


def _centred_difference(t, y, half_window):
    """dy/dt by centred differences over +- half_window samples (one-sided at the ends)."""
    k = np.arange(t.size)
    lo = np.clip(k - half_window, 0, t.size - 1)
    hi = np.clip(k + half_window, 0, t.size - 1)
    return (y[hi] - y[lo]) / (t[hi] - t[lo])


# ------------------------------------------------------------------------------ hidden effects

@dataclass(frozen=True)
class _Kinematics:
    """True motion at the sample times and what the effects need of the rig."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    a: np.ndarray
    running: np.ndarray  # S [m]
    sign: np.ndarray  # s(v) [-]
    stroke_of: np.ndarray  # stroke index of each sample
    displacement: np.ndarray  # D [m] since the stroke began, >= 0
    motion: _Motion
    coulomb: float  # F_c [N]
    v_max: float  # [m/s]
    travel: float  # [m]
    ball_radius: float  # [m]
    load: float  # N_0 [N]


@dataclass(frozen=True)
class _Hidden:
    """H(scale) [N]; ``linear`` when H is proportional to the scale; ``describe(scale)`` gives
    the true parameters; ``normal_force`` the load signal N(t) [N] where the effect varies it."""

    contribution: Callable[[float], np.ndarray]
    linear: bool
    describe: Callable[[float], dict]
    normal_force: np.ndarray | None = None


def _loguniform(rng, low, high):
    return float(math.exp(rng.uniform(math.log(low), math.log(high))))


def _none(erng, k):
    return _Hidden(lambda scale: np.zeros_like(k.t), True, lambda scale: {})


def _lubrication(erng, k):
    v_s, delta = _loguniform(erng, 2e-3, 2e-2), erng.uniform(0.6, 1.4)
    beta, k_v = erng.uniform(0.5, 0.8), erng.uniform(0.5, 2.0)
    speed = np.abs(k.v)
    unit = k.sign * (np.exp(-(speed / v_s) ** delta) + k_v * (speed / k.v_max) ** beta)
    return _Hidden(lambda scale: scale * unit, True, lambda scale: {
        "stribeck_drop": scale, "stribeck_velocity": v_s, "stribeck_exponent": delta,
        "viscous_coefficient": k_v * scale / k.v_max ** beta, "viscous_exponent": beta})


def _dahl(k, F_c, x_c, alpha):
    """Generalised Dahl element [N] along the strokes, exact per stroke (module docstring)."""
    m = alpha - 1.0
    force = np.empty_like(k.t)
    bounds = np.searchsorted(k.stroke_of, np.arange(k.motion.stroke_t0.size + 1))
    previous = 0.0
    for j, direction in enumerate(k.motion.stroke_dir):
        y0 = 1.0 - direction * previous / F_c
        part = slice(bounds[j], bounds[j + 1])
        y = (y0 ** -m + m * k.displacement[part] / x_c) ** (-1.0 / m)
        force[part] = direction * F_c * (1.0 - y)
        y_end = (y0 ** -m + m * k.motion.stroke_length[j] / x_c) ** (-1.0 / m)
        previous = direction * F_c * (1.0 - y_end)
    return force


def _presliding(erng, k):
    w, ratio, alpha = erng.uniform(0.3, 0.7), erng.uniform(3.0, 10.0), erng.uniform(1.2, 1.8)

    def contribution(x_1):
        blend = _dahl(k, w * k.coulomb, x_1, alpha) + _dahl(k, (1 - w) * k.coulomb, ratio * x_1,
                                                             alpha)
        return blend - k.coulomb * k.sign

    return _Hidden(contribution, False, lambda x_1: {
        "dahl_weight": w, "presliding_distance_1": x_1, "presliding_distance_2": ratio * x_1,
        "dahl_exponent": alpha})


def _position(erng, k):
    wavelengths = [_loguniform(erng, 4e-3, k.travel / 2) for _ in range(3)]
    weights = erng.uniform(0.3, 1.0, 3)
    phases = erng.uniform(0.0, 2 * np.pi, 3)
    height, half_width = erng.uniform(1.0, 2.0), erng.uniform(2e-3, 8e-3)
    centre = erng.uniform(0.2, 0.8) * k.travel
    waves = sum(c * np.sin(2 * np.pi * k.x / lam + p)
                for c, lam, p in zip(weights, wavelengths, phases))
    near = np.abs(k.x - centre) < half_width
    bump = np.where(near, 0.5 * (1 + np.cos(np.pi * (k.x - centre) / half_width)), 0.0)
    unit = k.sign * (waves + height * bump)

    def describe(scale):
        out = {f"wavelength_{j + 1}": lam for j, lam in enumerate(wavelengths)}
        out.update({f"wave_amplitude_{j + 1}": scale * c for j, c in enumerate(weights)})
        out.update({f"wave_phase_{j + 1}": p for j, p in enumerate(phases)})
        out.update({"bump_height": scale * height, "bump_position": centre,
                    "bump_half_width": half_width})
        return out

    return _Hidden(lambda scale: scale * unit, True, describe)


def _mass(erng, k):
    return _Hidden(lambda scale: scale * k.a, True, lambda scale: {"missing_mass": scale})


def _preload(erng, k):
    s_0 = erng.uniform(0.2, 0.6) * k.running[-1]
    unit = -k.coulomb * (1.0 - np.exp(-k.running / s_0)) * k.sign
    return _Hidden(lambda scale: scale * unit, True, lambda scale: {
        "loss_fraction": scale, "decay_distance": s_0})


def _ball_to_ball(erng, k):
    length, sigma = erng.uniform(1.0, 5.0) * 2 * k.ball_radius, erng.uniform(0.5, 1.0)
    step = length / 8
    grid = np.arange(0.0, k.running[-1] + 4 * length, step)
    xi = gaussian_filter1d(erng.standard_normal(grid.size), sigma=8.0)
    xi = np.interp(k.running, grid, xi / xi.std())
    unit = k.sign * np.exp(sigma * xi - 0.5 * sigma ** 2)
    return _Hidden(lambda scale: scale * unit, True, lambda scale: {
        "ball_contact_friction": scale, "correlation_length": length, "log_sigma": sigma})


def _normal_load(erng, k):
    spread = erng.uniform(0.2, 0.6) * k.load
    freqs = np.array([_loguniform(erng, 0.05, 1.0) for _ in range(3)])
    weights = erng.dirichlet(np.ones(3))
    phases = erng.uniform(0.0, 2 * np.pi, 3)
    load = k.load + spread * (weights * np.sin(2 * np.pi * np.outer(k.t, freqs) + phases)).sum(1)
    unit = k.sign * (load - k.load)

    def describe(scale):
        out = {"load_friction_coefficient": scale, "load_spread": spread}
        for j in range(3):
            out.update({f"load_frequency_{j + 1}": freqs[j], f"load_weight_{j + 1}": weights[j],
                        f"load_phase_{j + 1}": phases[j]})
        return out

    return _Hidden(lambda scale: scale * unit, True, describe, normal_force=load)


def _mains(erng, k):
    f, h_3 = 50.0 + erng.uniform(-0.05, 0.05), erng.uniform(0.0, 0.3)
    phi_1, phi_3 = erng.uniform(0.0, 2 * np.pi, 2)
    unit = np.sin(2 * np.pi * f * k.t + phi_1) + h_3 * np.sin(6 * np.pi * f * k.t + phi_3)
    return _Hidden(lambda scale: scale * unit, True, lambda scale: {
        "hum_amplitude": scale, "hum_frequency": f, "third_harmonic": h_3,
        "hum_phase_1": phi_1, "hum_phase_3": phi_3})


_BUILDERS = {
    "none": _none, "lubrication": _lubrication, "presliding_hysteresis": _presliding,
    "position_dependent_friction": _position, "unmodeled_mass": _mass,
    "preload_loss": _preload, "ball_to_ball_contact": _ball_to_ball,
    "normal_load_friction": _normal_load, "mains_disturbance": _mains,
}
#: effects the generator can hide, and the answer the workflow should give for each: the effect
#: itself where it is a registered candidate, else (outside the vocabulary) "unknown"
EXPECTED = {e: e if e in CANDIDATES or e == "none" else "unknown" for e in _BUILDERS}
EFFECTS = tuple(EXPECTED)


def _visible_rms(h, sign, moving):
    """RMS [N] over the moving samples of what a fit of Coulomb level and offset leaves of h."""
    basis = np.column_stack([sign[moving], np.ones(moving.sum())])
    coef = np.linalg.lstsq(basis, h[moving], rcond=None)[0]
    return float(np.sqrt(np.mean((h[moving] - basis @ coef) ** 2)))


def _scale(effect, hidden, target, k, moving):
    """The amplitude of H whose visible RMS equals target [N]; None where none reaches it."""
    if effect == "none":
        return 0.0
    if hidden.linear:
        return target / _visible_rms(hidden.contribution(1.0), k.sign, moving)
    # presliding: the smallest distance x_1 [m] that reaches the target (the RMS is not
    # monotonic for distances beyond the strokes, where the Coulomb fit absorbs a spring)
    gap = lambda log_x: _visible_rms(hidden.contribution(math.exp(log_x)), k.sign, moving) - target
    grid = np.log(np.logspace(-7, -2, 26))
    values = [gap(g) for g in grid]
    for lo, hi, f_lo, f_hi in zip(grid[:-1], grid[1:], values[:-1], values[1:]):
        if f_lo < 0.0 <= f_hi:
            return math.exp(brentq(gap, lo, hi, xtol=1e-6))
    return None


# ---------------------------------------------------------------------------------- generation

def simulate(effect: str, rng: np.random.Generator, *, size: float = 1.0, noise: float = 0.01,
             n_samples: int = 10000, rate: float = 1000.0, uneven: bool = False,
             with_position: bool = True, with_velocity: bool = True,
             with_acceleration: bool = True, encoder_step: float = 1e-6,
             offset: float | None = None, normal_force_channel: bool = False,
             derivative_half_window: int = 3) -> SyntheticRun:
    """Generate a run hiding ``effect`` (a key of EXPECTED), without writing it.

    size: effect size relative to the clearly visible size (module docstring), in (0, 3];
    noise: noise RMS over the noise-free drive-force range, in [0, 0.1]; n_samples >= 1000;
    rate: mean sampling rate [Hz]; uneven: jitter every time stamp by up to 0.6 / rate;
    with_position / with_velocity / with_acceleration: record feed_position / feed_velocity /
    feed_acceleration (position or velocity required); encoder_step: position quantum [m], 0 for
    none; offset: force-sensor zero [N], None draws it within +- 3 % of the force range;
    normal_force_channel: record a normal_force channel also where the load is constant (the
    channel's noise RMS is ``noise`` times the mean load N_0);
    derivative_half_window: samples each side of the rig's centred differences.
    Raises ValueError naming the argument that is invalid, and naming ``size`` where the effect
    cannot reach it on the drawn rig (preload_loss above about size 1.5 needs L >= 0.95).
    """
    _check_arguments(effect, rng, size, noise, n_samples, rate, with_position, with_velocity,
                     encoder_step, offset, derivative_half_window)
    rig_rng, motion_rng, timing_rng, effect_rng, noise_rng = rng.spawn(5)

    # rig, as the user states it and as it is
    mass = round(_loguniform(rig_rng, 5.0, 60.0), 2)
    a_max, v_max = rig_rng.uniform(0.5, 2.0), rig_rng.uniform(0.1, 0.3)
    coulomb = rig_rng.uniform(0.8, 2.0) * mass * a_max
    travel = rig_rng.uniform(0.03, 0.1)
    ball = rig_rng.random() < 0.5 or effect == "ball_to_ball_contact"  # always draw: pairing
    radius = round(rig_rng.uniform(2.0e-3, 4.0e-3), 5)
    per_row = int(rig_rng.integers(14, 31))
    preload = round(coulomb / rig_rng.uniform(0.004, 0.012), -1)
    load = round(rig_rng.uniform(200.0, 1500.0), 1)
    lubricant = {"viscosity": round(rig_rng.uniform(0.05, 0.3), 3),
                 "pressure_viscosity": soleimanian2020.PRESSURE_VISCOSITY}
    roughness = round(rig_rng.uniform(0.1e-6, 0.5e-6), 9)
    offset_fraction = rig_rng.uniform(-0.03, 0.03)

    # sampling and true motion
    jitter = timing_rng.uniform(0.0, 0.6, n_samples) if uneven else np.zeros(n_samples)
    t = np.round((np.arange(n_samples) + jitter) / rate, 7)
    motion = _plan_motion(motion_rng, t[-1], travel, v_max, a_max)
    x, v, a = motion.evaluate(t)
    stroke_of = np.searchsorted(motion.stroke_t0, t, side="right") - 1
    direction = motion.stroke_dir[stroke_of]
    displacement = np.maximum(direction * (x - motion.stroke_x0[stroke_of]), 0.0)
    sign = np.tanh(v / VELOCITY_TOLERANCE)
    k = _Kinematics(t, x, v, a, motion.stroke_s0[stroke_of] + displacement, sign, stroke_of,
                    displacement, motion, coulomb, v_max, travel, radius, load)
    moving = np.abs(v) > MOVING_SPEED

    # forces
    baseline = mass * a + coulomb * sign
    force_range = float(np.ptp(baseline))
    target = size * VISIBLE_FRACTION * force_range
    hidden = _BUILDERS[effect](effect_rng, k)
    scale = _scale(effect, hidden, target, k, moving)
    if scale is None:
        raise ValueError(f"size {size!r} is out of reach of {effect} on this motion; choose a "
                         f"smaller size")
    if effect == "preload_loss" and scale >= MAX_LOSS:
        raise ValueError(f"size {size!r} needs a friction loss of {scale:.2f} on this rig (at "
                         f"most {MAX_LOSS}); choose a smaller size")
    h = hidden.contribution(scale)
    force_offset = offset_fraction * force_range if offset is None else float(offset)
    clean = baseline + h + force_offset
    noise_rms = noise * float(np.ptp(clean))
    e = noise_rms * noise_rng.standard_normal(n_samples)
    load_noise = noise * load * noise_rng.standard_normal(n_samples)

    # what the rig records
    x_q = encoder_step * np.round(x / encoder_step) if encoder_step > 0 else x
    v_q = _centred_difference(t, x_q, derivative_half_window)
    columns = {"time": t}
    if with_position:
        columns["feed_position"] = x_q
    if with_velocity:
        columns["feed_velocity"] = v_q
    if with_acceleration:
        columns["feed_acceleration"] = _centred_difference(t, v_q, derivative_half_window)
    if hidden.normal_force is not None or normal_force_channel:
        true_load = load + np.zeros(n_samples) if hidden.normal_force is None else hidden.normal_force
        columns["normal_force"] = true_load + load_noise
    columns["drive_force"] = clean + e
    channels = tuple(columns)[1:]

    parameters = {
        "moving_mass": mass,
        "moving_mass_true": mass + (scale if effect == "unmodeled_mass" else 0.0),
        "coulomb_level": coulomb, "velocity_tolerance": VELOCITY_TOLERANCE,
        "offset": force_offset, "max_acceleration": a_max, "max_speed": v_max, "travel": travel,
        **hidden.describe(scale),
    }
    info = TruthInfo(effect=effect, expected=EXPECTED[effect],
                     parameters={key: float(value) for key, value in parameters.items()},
                     size=float(size), noise=float(noise), noise_rms=noise_rms,
                     effect_rms=_visible_rms(h, sign, moving), force_range=force_range,
                     channels=channels, n_samples=int(n_samples))

    guideway = {"type": "ball" if ball else "roller", "rows": 4, "elements_per_row": per_row,
                "element_radius": radius}
    if not ball:
        guideway["roller_length"] = soleimanian2020.ROLLER_LENGTH
    guideway.update({"contact_angle_deg": 45.0, "preload": preload})
    rig = {
        "format": FORMAT,
        "rig": {"kind": "horizontal_drive", "moving_mass": mass, "description": (
            f"Synthetic positioning axis on a linear {guideway['type']} guide, closed-loop "
            f"position control, {rate:g} Hz{' with jittered time stamps' if uneven else ''}; "
            f"encoder step {encoder_step * 1e6:g} um; feed_velocity and feed_acceleration are centred "
            f"differences of the encoder position over +-{derivative_half_window} samples.")},
        "guideway": guideway,
        "lubricant": lubricant,
        "surface": {"roughness_rms": roughness},
        "load": {"normal_force": load},
        "model": {"friction": "coulomb", "contact": "dry_hertz"},
        "channels": {"inputs": [c for c in channels if c != "drive_force"],
                     "outputs": ["drive_force"]},
    }
    truth = {"time": t, "position": x, "velocity": v, "acceleration": a,
             "running_distance": k.running, "baseline": baseline, "hidden": h, "noise": e,
             "moving": moving}
    return SyntheticRun(info=info, rig=rig, columns=columns, truth=truth)


# ------------------------------------------------------------------------------------- writing

def _toml_value(value) -> str:
    """A TOML value; floats in plain positional notation."""
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return np.format_float_positional(float(value), trim="0")


def write_run(out_dir: str | Path, run: SyntheticRun) -> Path:
    """Write ``run`` as out_dir/rig.toml and out_dir/data.csv (creating out_dir); return out_dir."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    lines = [f"format = {_toml_value(run.rig['format'])}"]
    for section, table in run.rig.items():
        if section != "format":
            lines += ["", f"[{section}]"] + [f"{key} = {_toml_value(value)}"
                                               for key, value in table.items()]
    (out / "rig.toml").write_text("\n".join(lines) + "\n", encoding="utf-8")
    names = list(run.columns)
    np.savetxt(out / "data.csv", np.column_stack([run.columns[n] for n in names]), delimiter=",",
               fmt=[_FORMATS[n] for n in names], header=",".join(names), comments="",
               encoding="utf-8")
    return out


def make_run(out_dir: str | Path, effect: str, rng: np.random.Generator, **knobs) -> TruthInfo:
    """Generate (``simulate``, same keyword knobs) and write one run to out_dir; its TruthInfo."""
    run = simulate(effect, rng, **knobs)
    write_run(out_dir, run)
    return run.info


def make_suite(root: str | Path, seeds, *, effects=EFFECTS, **knobs) -> list:
    """Write one run per effect and seed to root/<effect>_<seed>/, with root/truth.json.

    Every run of one seed uses ``numpy.random.default_rng(seed)``, so the runs of a seed share rig,
    motion and noise and differ only in the hidden effect. truth.json lists each run's directory
    name and TruthInfo; the run directories hold nothing but rig.toml and data.csv.
    Returns [(run directory, TruthInfo), ...].
    """
    bad = [e for e in effects if e not in EXPECTED]
    _check("effects", not bad and len(effects) > 0, f"a non-empty list of {', '.join(EFFECTS)}",
           effects)
    seeds = list(seeds)
    _check("seeds", len(seeds) > 0 and all(isinstance(s, (int, np.integer)) and s >= 0
                                          for s in seeds), "a non-empty list of integers >= 0",
           seeds)
    root = Path(root)
    out, index = [], []
    for seed in seeds:
        for effect in effects:
            run_dir = root / f"{effect}_{int(seed)}"
            info = replace(make_run(run_dir, effect, np.random.default_rng(int(seed)), **knobs),
                           seed=int(seed))
            out.append((run_dir, info))
            index.append({"run": run_dir.name, **asdict(info)})
    (root / "truth.json").write_text(json.dumps(index, indent=1) + "\n", encoding="utf-8")
    return out


def write_example(out_dir: str | Path) -> TruthInfo:
    """The bundled example: a clearly visible presliding-hysteresis run (seed 2024, size 1.5,
    noise 0.5 %, 10000 samples at 1 kHz) written to out_dir."""
    return make_run(out_dir, "presliding_hysteresis", np.random.default_rng(2024), size=1.5,
                    noise=0.005)
