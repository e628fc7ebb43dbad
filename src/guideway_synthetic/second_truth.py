"""A second, independent generator of synthetic measured runs with known hidden effects.

It writes records in the measured-run format (rig.toml + data.csv, version 1) whose force channel
hides one effect the user's baseline model lacks, and returns a :class:`Truth` saying what was
hidden. It was written from the format and the friction literature only, to measure the
discrepancy workflow on records it was not tuned on.

Baseline and strength
---------------------
The user's model is Coulomb friction ``F_c sgn(v)`` (plus ``m a`` with the stated ``moving_mass``
on drive-force rigs; the spec takes that mass as known, so it is not fitted). Every friction
force below is written along the motion (Coulomb: ``F_c sgn(v)``), as a drive feels it:
``drive_force = m a + F``; a rig reporting the force that opposes the motion writes ``-F``.
``sgn(0) = 0``: at standstill the Coulomb term is zero.

A hidden effect adds a contribution ``e(t)`` to the force channel. Its *visible* part is what is
left of ``e`` after a least-squares fit of ``c1 sgn(v) + c0`` (what the baseline's level and the
sensor zero absorb), computed with the true velocity at the force channel's instants, on the
samples whose direction of motion is unambiguous (``|v|`` at least 2 % of the top speed: the
format lets the workflow leave standstill and reversals out).
``draw(..., size=s)`` scales the effect so that the RMS of the visible part is ``8 s`` times the
record's noise RMS.

Hidden effects (v, x, a: true velocity [m/s], position [m], acceleration [m/s^2]; s: running
distance [m], the integral of |v| from the record's start)
------------------------------------------------------------------------------------------------
``none``
    ``e = 0``.
``lubrication``
    Rational (Hess-Soom type) Stribeck curve with viscous rise:
    ``F = sgn(v) [F_c + (F_s - F_c) / (1 + |v / v_s|^d)] + b v``, exponent ``d`` in [1, 2.5],
    ``v_s`` 3-25 % of the top speed, ``b`` such that ``b v_max`` is 0.3-1.5 times ``F_s - F_c``.
``presliding_hysteresis``
    LuGre bristle model in parallel with rigid Coulomb friction:
    ``F = (1 - f) F_c sgn(v) + f (sigma0 z + sigma1 dz/dt + sigma2 v)``,
    ``dz/dt = v - sigma0 |v| z / g(v)``, ``g(v) = F_c + (F_s - F_c) exp(-|v| / v_s)`` (Tustin).
    In records ``F_s = F_c`` and ``sigma2 = 0``, so sliding friction equals the baseline and only
    the build-up after each reversal shows, over the pre-sliding distance ``F_c / sigma0``
    (drawn in 1-10 um, doubled up to a tenth of the amplitude where ``size`` asks for more).
    ``z`` is integrated on 8 substeps per sample with the exact solution of the linear bristle
    equation over each substep's displacement.
``position_dependent_friction``
    ``F = sgn(v) F_c [1 + k p(x)]``, ``p(x) = sum_i w_i sin(2 pi x / lambda_i + phi_i)
    + h exp(-((x - x_d) / w_d)^2)``: 2-4 random waves (wavelengths 0.2-1.5 of the travelled span)
    plus one localised defect.
``unmodeled_mass``
    ``e = dm a``: a mass ``dm`` [kg] moves that ``moving_mass`` omits (drive-force rigs only).
``preload_loss``
    ``F = sgn(v) F_c [1 - D u / (1 + u^p)^(1/p)]``, ``u = s / s_k``: friction falls linearly with
    running distance, then saturates at the loss ``D`` beyond the knee distance ``s_k``
    (sharpness ``p`` in [2, 6]).
``ball_to_ball_contact`` (ball guides; not on tribometer strokes, see :func:`allowed`)
    ``F = sgn(v) [F_c + k F_c P(s)]``: ``P`` is piecewise constant in running distance, a new
    gamma-distributed level (mean 1) every 1.5-4 ball diameters (at least 12 cells per record).
``load_dependent_friction`` (out of vocabulary: expected answer ``unknown``)
    ``F = sgn(v) [F_c + mu (N(t) - N_0)]`` with a slowly varying external load
    ``N(t) = N_0 [1 + q w(t)]`` (``N_0`` 100-2000 N, ``q`` 0.2-0.6, ``w`` three sinusoids of
    0.7-6 cycles per record, peak at most 1) recorded in a ``normal_force`` column (an input).
``periodic_disturbance`` (out of vocabulary: expected answer ``unknown``)
    ``e = A [sin(2 pi f0 t + phi) + r sin(4 pi f0 t + phi2)]``: a force at a fixed frequency in
    time (a fan or pump on the rig frame, mains pick-up), unrelated to position or velocity;
    ``f0`` between 2 Hz (at least 20 periods per record) and an eighth of the sampling rate.

Record classes
--------------
``drive``
    Drive force with a moving mass of 2-25 kg; motion as quantised encoder counts in
    ``feed_position``, and ``feed_velocity`` in about half of the records.
``friction_along`` / ``friction_opposes``
    ``friction_force`` measured directly (``moving_mass = 0``), along or opposing the motion; the
    convention is stated in ``[channels] friction_sign`` in about half of the records. Inputs:
    position, velocity or both. For the same seed the two write exact negatives of each other.
``tribometer``
    Reciprocating micro-tribometer: strokes of 55-480 um amplitude with dwells at the reversals,
    friction measured directly, either convention, noise 1e-4..1e-3 of the force range.
``velocity_only`` / ``position_only``
    Drive-force rigs whose only motion channel is ``feed_velocity`` / ``feed_position``.
``bursty``
    A drive-force rig with uneven timestamps: clusters of samples 0.1-10 us apart, gaps of the
    nominal period and dropouts of several ms.

Per record (seeded, independently of the hidden effect but for the ball guide that ball-to-ball
contact needs): duration 4-20 s; a motion profile (sinusoidal, triangular with cosine blends,
S-curve point-to-point moves with dwells, random multi-sine; tribometer strokes); a Coulomb level
from the preload; a guideway (roller or ball); encoder steps of 50 nm-1 um (tribometer 1-10 nm);
velocity noise of 0.05-0.5 % of the top speed; force noise of 0.2-1.2 % of the Coulomb level
(tribometer: see above), white, AR(1) or 1/f, with, each in about half of the records, ADC steps,
a slow linear drift and a delay of 1-3 samples of the force channel behind the motion channels,
plus 0-6 outliers and a sensor zero.
"""
from __future__ import annotations

import math
import zlib
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Callable

import numpy as np
from scipy.signal import lfilter

from guideway_fmu.diagnose.run_io import REDUCED_MODULUS

#: hidden effect -> the answer the workflow should give
EFFECTS = {
    "none": "none",
    "lubrication": "lubrication",
    "presliding_hysteresis": "presliding_hysteresis",
    "position_dependent_friction": "position_dependent_friction",
    "unmodeled_mass": "unmodeled_mass",
    "preload_loss": "preload_loss",
    "ball_to_ball_contact": "ball_to_ball_contact",
    "load_dependent_friction": "unknown",
    "periodic_disturbance": "unknown",
}
#: record classes: how the rig writes the record
CLASSES = ("drive", "friction_along", "friction_opposes", "tribometer", "velocity_only",
           "position_only", "bursty")
#: classes whose compared channel is drive_force (the rest measure friction_force directly)
DRIVE_CLASSES = ("drive", "velocity_only", "position_only", "bursty")
PROFILES = ("sinusoidal", "triangular", "s_curve", "multi_sine")
NOISE_COLOURS = ("white", "ar1", "pink")
#: visible effect RMS over noise RMS at size 1
VISIBLE_PER_SIZE = 8.0
#: samples slower than this fraction of the top speed have no clear direction of motion and
#: do not count in an effect's visible strength
AMBIGUOUS_SPEED = 0.02
#: substeps per sample interval of the grid the stateful effects are integrated on
FINE_STEPS = 8
MIN_SAMPLES = 200
FORMAT = "guideway-measured-run/1"

Motion = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class Truth:
    """What a record hides.

    ``parameters`` holds the hidden effect's parameters and the record's hidden conditions
    (SI units, floats); ``noise_rms`` is the standard deviation of everything the force sensor
    adds (noise, ADC steps, outliers, drift) and ``effect_rms`` the RMS of the effect's visible
    part (see the module docstring), both in the units of ``channel`` [N]. ``friction_sign`` is the convention of a
    friction_force channel (stated in rig.toml or not), None for drive-force rigs.
    ``conditions`` names the profile, noise colour and guideway type.
    """

    effect: str
    expected: str
    record_class: str
    seed: int
    parameters: dict
    noise_rms: float
    effect_rms: float
    channel: str
    friction_sign: str | None
    conditions: dict = field(default_factory=dict)
    also: str | None = None  # a second hidden effect, or None
    expected_also: str | None = None  # the answer its step should give


def allowed(effect: str, record_class: str) -> bool:
    """Whether ``effect`` can appear in a record of ``record_class``: a missing mass cannot show
    where friction is measured directly, and ball-to-ball contact not on a tribometer (strokes
    of 50-500 um roll each ball back and forth over a tenth of its diameter or less: no new
    arrangement of balls, so no level changing with the running distance)."""
    return not ((effect == "unmodeled_mass" and record_class not in DRIVE_CLASSES)
                or (effect == "ball_to_ball_contact" and record_class == "tribometer"))


def draw(out_dir, effect: str, record_class: str, seed: int, *, size: float = 1.0,
         n_samples: int = 10000, also: str | None = None) -> Truth:
    """Write ``out_dir``/rig.toml and ``out_dir``/data.csv hiding ``effect`` in a record of
    ``record_class``, and return its :class:`Truth`. The same arguments give the same bytes;
    the rig, timing, motion and noise depend on ``seed`` only (not on ``effect``). ``also``
    hides a second effect beside the first, drawn from a stream of its own and scaled to the
    same visible RMS on its own (its parameters in Truth.parameters prefixed "also_").

    Raises ValueError naming the argument that is wrong, or naming the class for a combination
    that cannot exist (see :func:`allowed`), or naming ``size`` where the effect cannot be made
    that strong within its physical bounds.
    """
    _check_arguments(effect, record_class, seed, size, n_samples)
    if also is not None:
        _check_arguments(also, record_class, seed, size, n_samples)
        if also == effect or "none" in (effect, also):
            raise ValueError(f"also {also!r}: a second effect must be another effect than "
                             f"{effect!r}, and neither 'none'")
    rig = _draw_rig(seed, also if also == "ball_to_ball_contact" else effect, record_class)
    time, step = _draw_times(seed, record_class, n_samples)
    motion, profile, amplitude = _draw_motion(seed, record_class, time[-1])
    noise = _draw_force_noise(seed, record_class, rig.coulomb, time)
    force_time = time - noise.delay_samples * step
    scene = _Scene(motion, time, force_time, rig.coulomb, amplitude,
                   rig.guideway["element_radius"], step,
                   target=VISIBLE_PER_SIZE * size * noise.predicted_rms)
    hidden = _EFFECT_BUILDERS[effect](scene, _stream(seed, "effect"))
    if also is not None:
        second = _EFFECT_BUILDERS[also](scene, _stream(seed, "second effect"))
        hidden = _Hidden(hidden.contribution + second.contribution,
                         {**hidden.parameters,
                          **{f"also_{k}": v for k, v in second.parameters.items()}},
                         {**hidden.columns, **second.columns})
    clean = rig.coulomb * np.sign(scene.velocity) + hidden.contribution
    if record_class in DRIVE_CLASSES:
        clean = clean + rig.stated_mass * scene.acceleration
    recorded = noise.record(clean)
    layout = _draw_layout(seed, record_class)
    columns = {"time": time, **_motion_columns(seed, record_class, layout, motion, time)}
    columns[layout.channel] = -recorded if layout.friction_sign == "opposes_motion" else recorded
    columns.update(hidden.columns)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    _write_csv(out_dir / "data.csv", columns)
    _write_rig_toml(out_dir / "rig.toml", rig, layout, list(hidden.columns), profile)
    parameters = {"size": size, "coulomb_level": rig.coulomb, **noise.parameters(step),
                  **hidden.parameters}
    if record_class in DRIVE_CLASSES:
        parameters["moving_mass_stated"] = rig.stated_mass
    return Truth(effect=effect, expected=EFFECTS[effect], also=also,
                 expected_also=EFFECTS[also] if also is not None else None,
                 record_class=record_class,
                 seed=int(seed), parameters={k: float(v) + 0.0 for k, v in parameters.items()},
                 noise_rms=float(np.std(recorded - clean)),
                 effect_rms=_rms(scene.visible(hidden.contribution)), channel=layout.channel,
                 friction_sign=layout.friction_sign,
                 conditions=_conditions(profile, noise, rig, layout))


def _conditions(profile, noise, rig, layout) -> dict:
    conditions = {"profile": profile, "noise_colour": noise.colour,
                  "guideway": rig.guideway["type"]}
    if layout.friction_sign is not None:
        conditions["friction_sign_stated"] = str(layout.sign_stated).lower()
    return conditions


# ----------------------------------------------------------------------------- friction laws


def stribeck_rational(velocity, coulomb, static, stribeck_velocity, exponent=2.0, viscous=0.0):
    """Rational Stribeck curve with viscous rise [N]:
    ``sgn(v) [F_c + (F_s - F_c) / (1 + |v / v_s|^d)] + b v`` (velocity [m/s], levels [N],
    ``v_s`` [m/s], ``b`` [N s/m]); ``d = 2`` is Hess and Soom's form."""
    v = np.asarray(velocity, dtype=float)
    fall = 1.0 / (1.0 + np.abs(v / stribeck_velocity) ** exponent)
    return np.sign(v) * (coulomb + (static - coulomb) * fall) + viscous * v


@dataclass(frozen=True)
class LuGre:
    """LuGre friction (Canudas de Wit et al. 1995) with Tustin's Stribeck curve.

    ``sigma0`` [N/m] bristle stiffness, ``sigma1`` [N s/m] bristle damping, ``sigma2`` [N s/m]
    viscous coefficient, ``coulomb`` and ``static`` [N] levels, ``stribeck_velocity`` [m/s].
    """

    sigma0: float
    sigma1: float
    sigma2: float
    coulomb: float
    static: float
    stribeck_velocity: float

    def stribeck(self, velocity):
        """Steady sliding level ``g(v) = F_c + (F_s - F_c) exp(-|v| / v_s)`` [N]."""
        speed = np.abs(np.asarray(velocity, dtype=float))
        return self.coulomb + (self.static - self.coulomb) * np.exp(-speed / self.stribeck_velocity)

    def steady_bristle(self, velocity) -> float:
        """Bristle deflection [m] in steady sliding at ``velocity`` (0 at rest)."""
        return float(np.sign(velocity) * self.stribeck(velocity) / self.sigma0)

    def bristle(self, position, velocity, z0=0.0) -> np.ndarray:
        """Bristle deflection ``z`` [m] along a path sampled finely (position [m], velocity
        [m/s]). Over each step ``dz/dx = sgn(dx) - sigma0 z / g``, linear in ``z``, is solved
        exactly with ``g`` at the step's mean velocity (exact wherever ``g`` is constant)."""
        position = np.asarray(position, dtype=float)
        velocity = np.asarray(velocity, dtype=float)
        dx = np.diff(position)
        level = self.stribeck(0.5 * (velocity[1:] + velocity[:-1]))
        decay = np.exp(-self.sigma0 * np.abs(dx) / level)
        pull = ((1.0 - decay) * np.sign(dx) * level / self.sigma0).tolist()
        z = np.empty(position.size)
        z[0] = state = z0
        for i, keep in enumerate(decay.tolist()):
            state = keep * state + pull[i]
            z[i + 1] = state
        return z

    def force(self, z, velocity):
        """Friction force along the motion [N]: ``sigma0 z + sigma1 dz/dt + sigma2 v``."""
        v = np.asarray(velocity, dtype=float)
        z_rate = v - self.sigma0 * np.abs(v) * z / self.stribeck(v)
        return self.sigma0 * z + self.sigma1 * z_rate + self.sigma2 * v


# ----------------------------------------------------------------------------- arguments, streams


def _check_arguments(effect, record_class, seed, size, n_samples):
    if effect not in EFFECTS:
        raise ValueError(f"effect {effect!r} is not one of: {', '.join(EFFECTS)}")
    if record_class not in CLASSES:
        raise ValueError(f"record_class {record_class!r} is not one of: {', '.join(CLASSES)}")
    if not allowed(effect, record_class):
        why = ("its strokes are far shorter than a ball" if record_class == "tribometer"
               and effect == "ball_to_ball_contact" else
               "it measures friction directly (moving_mass 0)")
        raise ValueError(f"record_class {record_class!r}: effect {effect!r} cannot appear in "
                         f"it: {why}")
    if not _is_int(seed) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    if not _is_real(size) or not math.isfinite(size) or size < 0:
        raise ValueError(f"size must be a finite number >= 0, got {size!r}")
    if not _is_int(n_samples) or n_samples < MIN_SAMPLES:
        raise ValueError(f"n_samples must be an integer >= {MIN_SAMPLES}, got {n_samples!r}")


def _is_int(value) -> bool:
    return isinstance(value, (int, np.integer)) and not isinstance(value, bool)


def _is_real(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)


def _stream(seed: int, topic: str) -> np.random.Generator:
    """An independent random stream per seed and topic, so one aspect of a record does not
    shift when another draws more or fewer numbers."""
    return np.random.default_rng([int(seed), zlib.crc32(topic.encode())])


def _log_uniform(rng, low, high, size=None):
    return np.exp(rng.uniform(math.log(low), math.log(high), size))


def _rms(values) -> float:
    return float(np.sqrt(np.mean(np.square(values))))


# ----------------------------------------------------------------------------- rig and channels


@dataclass(frozen=True)
class _Rig:
    guideway: dict  # the [guideway] table as written
    coulomb: float  # N, the true Coulomb level
    stated_mass: float  # kg, moving_mass of drive-force rigs (0 where friction is measured)


def _draw_rig(seed, effect, record_class) -> _Rig:
    """A guideway (ball guides for ball-to-ball contact) and a Coulomb level: 0.2-0.8 % of the
    preload (rolling) plus 2-15 N (seals)."""
    rng = _stream(seed, "rig")
    guide_type = "ball" if rng.random() < 0.5 else "roller"
    if effect == "ball_to_ball_contact":
        guide_type = "ball"
    radius = rng.uniform(1.5e-3, 4.0e-3)
    table = {"type": guide_type, "rows": 4, "elements_per_row": int(rng.integers(10, 31)),
             "element_radius": radius}
    roller_length = radius * rng.uniform(2.0, 3.5)
    if guide_type == "roller":
        table["roller_length"] = roller_length
    table["contact_angle_deg"] = 45.0
    table["preload"] = float(_log_uniform(rng, 300.0, 5000.0))
    if rng.random() < 0.3:
        table["reduced_modulus"] = REDUCED_MODULUS
    coulomb = table["preload"] * rng.uniform(0.002, 0.008) + rng.uniform(2.0, 15.0)
    mass = rng.uniform(2.0, 25.0)
    return _Rig(table, float(coulomb), float(mass) if record_class in DRIVE_CLASSES else 0.0)


@dataclass(frozen=True)
class _Layout:
    inputs: tuple  # motion channels, in column order
    channel: str  # compared channel
    friction_sign: str | None
    sign_stated: bool


def _draw_layout(seed, record_class) -> _Layout:
    """Which channels the class's rig records, and the friction sign convention."""
    rng = _stream(seed, "channels")
    with_velocity = bool(rng.random() < 0.5)
    friction_inputs = (("feed_position",), ("feed_velocity",),
                       ("feed_position", "feed_velocity"))[int(rng.integers(3))]
    sign_stated = bool(rng.random() < 0.5)
    tribometer_sign = "opposes_motion" if rng.random() < 0.5 else "along_motion"
    drive_inputs = ("feed_position", "feed_velocity") if with_velocity else ("feed_position",)
    if record_class in ("drive", "bursty"):
        return _Layout(drive_inputs, "drive_force", None, False)
    if record_class == "velocity_only":
        return _Layout(("feed_velocity",), "drive_force", None, False)
    if record_class == "position_only":
        return _Layout(("feed_position",), "drive_force", None, False)
    if record_class == "tribometer":
        return _Layout(drive_inputs, "friction_force", tribometer_sign, sign_stated)
    sign = "along_motion" if record_class == "friction_along" else "opposes_motion"
    return _Layout(friction_inputs, "friction_force", sign, sign_stated)


def _motion_columns(seed, record_class, layout, motion, time) -> dict:
    """feed_position as quantised encoder counts (with an arbitrary zero) and feed_velocity with
    white sensor noise, as the layout asks."""
    x, v, _ = motion(time)
    encoder, tacho = _stream(seed, "encoder"), _stream(seed, "velocity_noise")
    tribometer = record_class == "tribometer"
    resolution = _log_uniform(encoder, *((1e-9, 1e-8) if tribometer else (5e-8, 1e-6)))
    zero = encoder.uniform(-1e-3, 1e-3) if tribometer else encoder.uniform(-0.1, 0.1)
    velocity_noise = np.max(np.abs(v)) * _log_uniform(tacho, 5e-4, 5e-3)
    columns = {}
    if "feed_position" in layout.inputs:
        columns["feed_position"] = resolution * np.round((x + zero) / resolution)
    if "feed_velocity" in layout.inputs:
        columns["feed_velocity"] = v + velocity_noise * tacho.standard_normal(v.size)
    return columns


# ----------------------------------------------------------------------------- timing


def _draw_times(seed, record_class, n_samples) -> tuple[np.ndarray, float]:
    """Sample instants [s] and the nominal sampling period [s]."""
    rng = _stream(seed, "timing")
    step = rng.uniform(4.0, 20.0) / n_samples
    if record_class == "bursty":
        return _bursty_times(rng, n_samples, step), step
    return np.arange(n_samples) * step, step


def _bursty_times(rng, n_samples, step) -> np.ndarray:
    """Clusters of samples 0.1-9 us apart, packet gaps around the nominal period and, rarely,
    dropouts of 2-10 ms or 3-20 periods. The first spacing is within a cluster and one spacing
    in the middle is a dropout, so both extremes occur in every record."""
    count = n_samples - 1
    in_cluster = rng.random(count) < 0.6
    cluster = _log_uniform(rng, 1e-7, 9e-6, count)
    packet = step / 0.4 * rng.uniform(0.5, 1.5, count)  # 40 % of spacings carry the time
    dropout = np.maximum(step * rng.uniform(3.0, 20.0, count), rng.uniform(2e-3, 1e-2, count))
    spacing = np.where(in_cluster, cluster, np.where(rng.random(count) < 0.03, dropout, packet))
    spacing[0], spacing[count // 2] = cluster[0], dropout[0]
    return np.concatenate([[0.0], np.cumsum(spacing)])


# ----------------------------------------------------------------------------- motion profiles


def _draw_motion(seed, record_class, duration) -> tuple[Motion, str, float]:
    """A motion ``t -> (x, v, a)`` covering [0, duration], its profile name and its amplitude
    (half the travelled range) [m]."""
    rng = _stream(seed, "motion")
    profile = str(rng.choice(PROFILES))
    amplitude = rng.uniform(5e-3, 50e-3)
    if record_class == "tribometer":
        amplitude = rng.uniform(55e-6, 480e-6)
        return _stroke_motion(rng, amplitude, duration), "strokes", amplitude
    if profile == "sinusoidal":
        cycles = rng.uniform(3.0, 12.0)
        return (_sine_motion([amplitude], [2 * math.pi * cycles / duration],
                             [rng.uniform(0, 2 * math.pi)]), profile, amplitude)
    if profile == "multi_sine":
        return _multi_sine_motion(rng, amplitude, duration), profile, amplitude
    if profile == "triangular":
        return _triangular_motion(rng, amplitude, duration), profile, amplitude
    return _s_curve_motion(rng, amplitude, duration), profile, amplitude


def _sine_motion(amplitudes, omegas, phases) -> Motion:
    """``x = sum_i A_i sin(omega_i t + phi_i)`` (A [m], omega [rad/s])."""
    amplitudes, omegas, phases = (np.asarray(v, dtype=float)[:, None]
                                  for v in (amplitudes, omegas, phases))

    def motion(t):
        angle = omegas * np.asarray(t, dtype=float)[None, :] + phases
        return (np.sum(amplitudes * np.sin(angle), axis=0),
                np.sum(amplitudes * omegas * np.cos(angle), axis=0),
                np.sum(-amplitudes * omegas ** 2 * np.sin(angle), axis=0))
    return motion


def _multi_sine_motion(rng, amplitude, duration) -> Motion:
    """3-5 sinusoids of 2-15 cycles per record, scaled so the largest excursion is
    ``amplitude``."""
    count = int(rng.integers(3, 6))
    cycles = rng.choice(np.arange(2, 16), count, replace=False)
    weights = rng.uniform(0.3, 1.0, count) / np.sqrt(cycles)
    omegas, phases = 2 * math.pi * cycles / duration, rng.uniform(0, 2 * math.pi, count)
    peak = np.max(np.abs(_sine_motion(weights, omegas, phases)(np.linspace(0, duration, 4001))[0]))
    return _sine_motion(weights * amplitude / peak, omegas, phases)


# A move is a cosine ramp up, an optional cruise and a cosine ramp down; each segment is
# (kind, duration [s], peak velocity [m/s]).
DWELL, RAMP_UP, CRUISE, RAMP_DOWN = 0, 1, 2, 3


def _move(distance, ramp, cruise) -> list:
    peak = distance / (ramp + cruise)
    return [(RAMP_UP, ramp, peak), (CRUISE, cruise, peak), (RAMP_DOWN, ramp, peak)]


def _triangular_motion(rng, amplitude, duration) -> Motion:
    """Constant-speed strokes between -amplitude and +amplitude, reversing through short cosine
    blends (3-12 % of a stroke's time), starting from rest."""
    moves = int(rng.integers(6, 21))
    stroke_time = duration / (moves + 0.5)
    ramp = stroke_time * rng.uniform(0.03, 0.12)
    segments = [(DWELL, 0.25 * stroke_time, 0.0)]
    for i in range(moves + 1):
        segments += _move((-1) ** i * 2 * amplitude, ramp, stroke_time - 2 * ramp)
    return _schedule_motion(-amplitude, segments)


def _s_curve_motion(rng, amplitude, duration) -> Motion:
    """Point-to-point moves to random targets in [-amplitude, amplitude] (at least a quarter
    amplitude away) with long cosine ramps (S-curves) and dwells between moves."""
    moves = int(rng.integers(5, 15))
    slot = duration / moves
    position, segments = 0.0, [(DWELL, 0.2 * slot, 0.0)]
    for _ in range(moves + 1):
        target = rng.uniform(-amplitude, amplitude)
        while abs(target - position) < 0.25 * amplitude:
            target = rng.uniform(-amplitude, amplitude)
        move_time = slot * (1 - rng.uniform(0.15, 0.4))
        ramp = move_time * rng.uniform(0.3, 0.5)
        segments += _move(target - position, ramp, move_time - 2 * ramp)
        segments.append((DWELL, slot - move_time, 0.0))
        position = target
    return _schedule_motion(0.0, segments)


def _stroke_motion(rng, amplitude, duration) -> Motion:
    """Tribometer strokes between -amplitude and +amplitude with dwells at each reversal."""
    strokes = int(rng.integers(8, 25))
    slot = duration / strokes
    dwell = slot * rng.uniform(0.1, 0.35)
    ramp = (slot - dwell) * rng.uniform(0.05, 0.2)
    segments = [(DWELL, dwell, 0.0)]
    for i in range(strokes + 1):
        segments += _move((-1) ** i * 2 * amplitude, ramp, slot - dwell - 2 * ramp)
        segments.append((DWELL, dwell, 0.0))
    return _schedule_motion(-amplitude, segments)


def _schedule_motion(start_position, segments) -> Motion:
    """A piecewise analytic motion from a list of segments starting at t = 0; before the first
    segment and after the last the part rests (the last segments end at rest)."""
    kinds = np.array([s[0] for s in segments])
    durations = np.array([s[1] for s in segments], dtype=float)
    peaks = np.array([s[2] for s in segments], dtype=float)
    starts = np.concatenate([[0.0], np.cumsum(durations)[:-1]])
    travel = peaks * durations * np.where(kinds == CRUISE, 1.0, 0.5) * (kinds != DWELL)
    origins = start_position + np.concatenate([[0.0], np.cumsum(travel)[:-1]])

    def motion(t):
        t = np.asarray(t, dtype=float)
        i = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(segments) - 1)
        tau = np.clip(t - starts[i], 0.0, durations[i])
        x, v, a = _segment_state(kinds[i], tau, durations[i], peaks[i])
        return origins[i] + x, v, a
    return motion


def _segment_state(kind, tau, duration, peak):
    """Position change [m], velocity [m/s] and acceleration [m/s^2] ``tau`` into a segment."""
    safe = np.where(duration > 0, duration, 1.0)
    phase = np.pi * tau / safe
    sine, cosine = np.sin(phase), np.cos(phase)
    swing = peak * safe / (2 * np.pi) * sine
    up, down, cruise = kind == RAMP_UP, kind == RAMP_DOWN, kind == CRUISE
    x = np.select([up, down, cruise], [peak * tau / 2 - swing, peak * tau / 2 + swing, peak * tau])
    v = np.select([up, down, cruise], [peak * (1 - cosine) / 2, peak * (1 + cosine) / 2, peak])
    ramp_rate = peak * np.pi / (2 * safe) * sine
    a = np.select([up, down], [ramp_rate, -ramp_rate])
    return x, v, a


# ----------------------------------------------------------------------------- force noise


@dataclass(frozen=True)
class _ForceNoise:
    perturbation: np.ndarray  # N per sample: coloured noise + outliers + drift
    adc_step: float  # N, 0 without ADC quantisation
    offset: float  # N, sensor zero
    delay_samples: int  # force channel behind the motion channels
    colour: str
    outliers: int
    drift: float  # N, drift over the record

    @property
    def predicted_rms(self) -> float:
        """Expected standard deviation of the sensor's error [N] (ADC steps as step^2/12)."""
        return math.sqrt(float(np.var(self.perturbation)) + self.adc_step ** 2 / 12)

    def record(self, clean) -> np.ndarray:
        """What the sensor writes for the ``clean`` force [N]."""
        value = clean + self.offset + self.perturbation
        if self.adc_step > 0:
            value = self.adc_step * np.round(value / self.adc_step)
        return value

    def parameters(self, step) -> dict:
        return {"adc_step": self.adc_step, "sensor_offset": self.offset,
                "force_delay": self.delay_samples * step, "outlier_count": float(self.outliers),
                "drift": self.drift}


def _draw_force_noise(seed, record_class, coulomb, time) -> _ForceNoise:
    """Force noise of a record: 0.2-1.2 % of the Coulomb level (tribometers: 1e-4..1e-3 of the
    range 2 F_c) in a drawn colour, with outliers, drift, ADC steps and delay."""
    rng = _stream(seed, "force_noise")
    n = time.size
    if record_class == "tribometer":
        level = 2 * coulomb * _log_uniform(rng, 1e-4, 1e-3)
    else:
        level = coulomb * _log_uniform(rng, 2e-3, 1.2e-2)
    colour = str(rng.choice(NOISE_COLOURS))
    noise = level * _unit_noise(rng, colour, n)
    outliers = int(rng.integers(0, 7))
    where = rng.choice(n, outliers, replace=False)
    noise[where] += level * rng.uniform(6.0, 15.0, outliers) * rng.choice([-1.0, 1.0], outliers)
    drift = level * rng.uniform(0.5, 1.5) * rng.choice([-1.0, 1.0]) * (rng.random() < 0.5)
    noise += drift * (time - time[0]) / (time[-1] - time[0])
    adc_step = level * rng.uniform(0.3, 1.5) * (rng.random() < 0.5)
    delay = int(rng.integers(1, 4)) * (rng.random() < 0.5)
    offset = coulomb * rng.uniform(-0.05, 0.05)
    return _ForceNoise(noise, float(adc_step), float(offset), delay, colour, outliers, float(drift))


def _unit_noise(rng, colour, n) -> np.ndarray:
    """Zero-mean noise of unit standard deviation: white, AR(1) (pole 0.5-0.95) or 1/f."""
    white = rng.standard_normal(n)
    pole = rng.uniform(0.5, 0.95)  # drawn for every colour, so later draws do not depend on it
    if colour == "ar1":
        white = lfilter([1.0], [1.0, -pole], white)
    elif colour == "pink":
        spectrum = np.fft.rfft(white)
        frequency = np.arange(spectrum.size, dtype=float)
        spectrum[1:] /= np.sqrt(frequency[1:])
        spectrum[0] = 0.0
        white = np.fft.irfft(spectrum, n)
    white = white - white.mean()
    return white / white.std()


# ----------------------------------------------------------------------------- hidden effects


@dataclass
class _Scene:
    """The true motion at the force channel's instants and what an effect is scaled to."""

    motion: Motion
    time: np.ndarray  # s, sample instants
    force_time: np.ndarray  # s, instants the force channel sees (delayed)
    coulomb: float  # N
    amplitude: float  # m, half the travelled range
    ball_radius: float  # m
    step: float  # s, nominal sampling period
    target: float  # N, RMS the visible contribution must reach

    def __post_init__(self):
        self.position, self.velocity, self.acceleration = self.motion(self.force_time)

    @property
    def top_speed(self) -> float:
        return float(np.max(np.abs(self.velocity)))

    def visible(self, contribution) -> np.ndarray:
        """``contribution`` less its least-squares fit by ``c1 sgn(v) + c0``, on the samples with
        a clear direction of motion."""
        directed = np.abs(self.velocity) >= AMBIGUOUS_SPEED * self.top_speed
        basis = np.column_stack([np.sign(self.velocity[directed]), np.ones(np.sum(directed))])
        coefficients = np.linalg.lstsq(basis, contribution[directed], rcond=None)[0]
        return contribution[directed] - basis @ coefficients

    def scale(self, shape) -> float:
        """The factor that gives ``shape``'s visible part the target RMS."""
        return self.target / _rms(self.visible(shape))

    @cached_property
    def fine_path(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(time, position, velocity) on FINE_STEPS uniform substeps per sample interval."""
        t = np.linspace(self.force_time[0], self.force_time[-1],
                        FINE_STEPS * (self.force_time.size - 1) + 1)
        x, v, _ = self.motion(t)
        return t, x, v

    @cached_property
    def running_distance(self) -> np.ndarray:
        """Distance run since the record's start [m] at the force channel's instants."""
        t, x, _ = self.fine_path
        travelled = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(x)))])
        return np.interp(self.force_time, t, travelled)


@dataclass(frozen=True)
class _Hidden:
    contribution: np.ndarray  # N, added to the clean force along the motion
    parameters: dict
    columns: dict = field(default_factory=dict)  # extra data.csv columns (inputs)


def _too_strong(effect, why) -> ValueError:
    return ValueError(f"size is too large for {effect} on this record: {why}")


def _none(scene, rng) -> _Hidden:
    return _Hidden(np.zeros_like(scene.velocity), {})


def _lubrication(scene, rng) -> _Hidden:
    v, top = scene.velocity, scene.top_speed
    stribeck_velocity = top * rng.uniform(0.03, 0.25)
    exponent = rng.uniform(1.0, 2.5)
    viscous_share = rng.uniform(0.3, 1.5)
    shape = stribeck_rational(v, 0.0, scene.coulomb, stribeck_velocity, exponent,
                              viscous_share * scene.coulomb / top)
    k = scene.scale(shape)
    return _Hidden(k * shape, {"static_level": scene.coulomb * (1 + k),
                               "stribeck_velocity": stribeck_velocity,
                               "stribeck_exponent": exponent,
                               "viscous_coefficient": k * viscous_share * scene.coulomb / top})


def _presliding(scene, rng) -> _Hidden:
    """LuGre in parallel with rigid Coulomb friction. The pre-sliding distance starts at a drawn
    1-10 um and doubles (up to a tenth of the amplitude) until the LuGre part alone is visible
    enough; its share of the friction then sets the visible RMS to the target."""
    longest = 0.1 * scene.amplitude
    distance = min(float(_log_uniform(rng, 1e-6, 1e-5)), longest)
    damping = rng.uniform(0.01, 0.05) * scene.coulomb / scene.top_speed
    while True:
        lugre = _record_lugre(scene, distance, damping)
        excess = lugre.force(_bristle_at_force_time(scene, lugre), scene.velocity)
        excess -= scene.coulomb * np.sign(scene.velocity)
        reach = _rms(scene.visible(excess))
        if reach >= scene.target:
            break
        if distance >= longest:
            raise _too_strong("presliding_hysteresis", "the pre-sliding distance would exceed "
                              "a tenth of the amplitude")
        distance = min(2 * distance, longest)
    share = scene.target / reach
    return _Hidden(share * excess, {"sigma0": lugre.sigma0, "sigma1": lugre.sigma1,
                                    "presliding_distance": distance, "lugre_share": share})


def _record_lugre(scene, distance, damping) -> LuGre:
    """The records' LuGre: sliding level F_c at every speed (no Stribeck fall, no viscous)."""
    return LuGre(sigma0=scene.coulomb / distance, sigma1=damping, sigma2=0.0,
                 coulomb=scene.coulomb, static=scene.coulomb, stribeck_velocity=scene.top_speed)


def _bristle_at_force_time(scene, lugre) -> np.ndarray:
    """Bristle deflection [m] at the force instants, starting in steady state."""
    t, x, v = scene.fine_path
    z = lugre.bristle(x, v, z0=lugre.steady_bristle(v[0]))
    return np.interp(scene.force_time, t, z)


def _position_dependent(scene, rng) -> _Hidden:
    x = scene.position
    low, span = float(np.min(x)), float(np.ptp(x))
    waves = int(rng.integers(2, 5))
    wavelengths = span * _log_uniform(rng, 0.2, 1.5, waves)
    phases = rng.uniform(0, 2 * math.pi, waves)
    weights = rng.standard_normal(waves)
    defect_at = low + span * rng.uniform(0.1, 0.9)
    defect_width = span * rng.uniform(0.01, 0.05)
    defect_height = rng.uniform(1.0, 3.0) * rng.choice([-1.0, 1.0])

    def pattern(p):
        waves_part = np.sum(weights[:, None] * np.sin(2 * np.pi * p[None, :] / wavelengths[:, None]
                                                       + phases[:, None]), axis=0)
        return waves_part + defect_height * np.exp(-((p - defect_at) / defect_width) ** 2)

    k = scene.scale(scene.coulomb * pattern(x) * np.sign(scene.velocity))
    if 1 + k * np.min(pattern(np.linspace(low, low + span, 4001))) < 0.1:
        raise _too_strong("position_dependent_friction", "friction would fall below a tenth of "
                          "its level somewhere")
    parameters = {"relative_amplitude": k, "defect_position": defect_at,
                  "defect_width": defect_width, "defect_height": k * defect_height * scene.coulomb}
    parameters.update({f"wavelength_{i + 1}": float(w) for i, w in enumerate(wavelengths)})
    return _Hidden(k * scene.coulomb * pattern(x) * np.sign(scene.velocity), parameters)


def _unmodeled_mass(scene, rng) -> _Hidden:
    missing = scene.scale(scene.acceleration)
    return _Hidden(missing * scene.acceleration, {"missing_mass": missing})


def _preload_loss(scene, rng) -> _Hidden:
    s = scene.running_distance
    knee = s[-1] * rng.uniform(0.15, 0.6)
    sharpness = rng.uniform(2.0, 6.0)
    u = s / knee
    shape = -scene.coulomb * u / (1 + u ** sharpness) ** (1 / sharpness) * np.sign(scene.velocity)
    loss = scene.scale(shape)
    if loss > 0.8:
        raise _too_strong("preload_loss", f"the friction loss would be {loss:.0%} (at most 80 %)")
    return _Hidden(loss * shape, {"final_loss": loss, "knee_distance": knee,
                                  "knee_sharpness": sharpness, "running_distance": s[-1]})


def _ball_to_ball(scene, rng) -> _Hidden:
    s = scene.running_distance
    cell = min(2 * scene.ball_radius * rng.uniform(1.5, 4.0), s[-1] / 12)
    cells = int(math.ceil(s[-1] / (0.5 * cell))) + 2
    edges = np.cumsum(cell * rng.uniform(0.5, 1.5, cells))
    levels = rng.gamma(2.0, 0.5, cells + 1)
    shape = scene.coulomb * levels[np.searchsorted(edges, s)] * np.sign(scene.velocity)
    k = scene.scale(shape)
    moving = scene.velocity != 0
    return _Hidden(k * shape, {"mean_rise": float(np.mean(np.abs(k * shape[moving]))),
                               "cell_length": cell, "relative_amplitude": k})


def _load_dependent(scene, rng) -> _Hidden:
    mean_load = float(_log_uniform(rng, 100.0, 2000.0))
    depth = rng.uniform(0.2, 0.6)
    cycles = rng.uniform(0.7, 6.0, 3)
    weights = rng.uniform(0.3, 1.0, 3)
    phases = rng.uniform(0, 2 * math.pi, 3)
    duration = scene.time[-1]

    def load(t):
        angle = 2 * np.pi * cycles[:, None] * t[None, :] / duration + phases[:, None]
        return mean_load * (1 + depth * np.sum(weights[:, None] * np.sin(angle), 0) / weights.sum())

    shape = (load(scene.force_time) - mean_load) * np.sign(scene.velocity)
    mu = scene.scale(shape)
    sensor_noise = mean_load * _log_uniform(rng, 1e-4, 1e-3)
    measured = load(scene.time) + sensor_noise * rng.standard_normal(scene.time.size)
    return _Hidden(mu * shape, {"load_coefficient": mu, "mean_load": mean_load,
                                "load_depth": depth}, {"normal_force": measured})


def _periodic_disturbance(scene, rng) -> _Hidden:
    highest = 1 / (8 * scene.step)
    lowest = min(max(2.0, 20 / scene.time[-1]), highest / 2)
    frequency = float(_log_uniform(rng, lowest, highest))
    harmonic = rng.uniform(0.0, 0.3)
    phase, phase2 = rng.uniform(0, 2 * math.pi, 2)
    angle = 2 * np.pi * frequency * scene.force_time
    shape = np.sin(angle + phase) + harmonic * np.sin(2 * angle + phase2)
    amplitude = scene.scale(shape)
    return _Hidden(amplitude * shape, {"frequency": frequency, "amplitude": amplitude,
                                       "harmonic_ratio": harmonic})


_EFFECT_BUILDERS = {
    "none": _none,
    "lubrication": _lubrication,
    "presliding_hysteresis": _presliding,
    "position_dependent_friction": _position_dependent,
    "unmodeled_mass": _unmodeled_mass,
    "preload_loss": _preload_loss,
    "ball_to_ball_contact": _ball_to_ball,
    "load_dependent_friction": _load_dependent,
    "periodic_disturbance": _periodic_disturbance,
}


# ----------------------------------------------------------------------------- writing


def _decimal(value, digits) -> str:
    """A plain decimal (no exponent) of ``digits`` significant digits; -0 written as 0."""
    return np.format_float_positional(float(value) + 0.0, precision=digits, unique=True,
                                      fractional=False, trim="0")


def _exact_decimal(value) -> str:
    """The shortest plain decimal that reads back as the same float (for strictly increasing
    timestamps)."""
    return np.format_float_positional(float(value), unique=True, trim="0")


def _write_csv(path: Path, columns: dict) -> None:
    texts = [[_exact_decimal(v) for v in columns["time"]]]
    texts += [[_decimal(v, 10) for v in values] for name, values in columns.items()
              if name != "time"]
    rows = [",".join(columns)] + [",".join(cells) for cells in zip(*texts)]
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")


def _toml_value(value) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, int):
        return str(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return _decimal(value, 8)


def _write_rig_toml(path: Path, rig: _Rig, layout: _Layout, extra_inputs, profile) -> None:
    channels = {"inputs": list(layout.inputs) + list(extra_inputs), "outputs": [layout.channel]}
    if layout.sign_stated:
        channels["friction_sign"] = layout.friction_sign
    tables = {
        "rig": {"kind": "horizontal_drive",
                "description": f"synthetic record, {profile.replace('_', ' ')} motion",
                "moving_mass": rig.stated_mass},
        "guideway": rig.guideway,
        "model": {"friction": "coulomb", "contact": "dry_hertz"},
        "channels": channels,
    }
    lines = [f'format = "{FORMAT}"']
    for name, table in tables.items():
        lines += ["", f"[{name}]"] + [f"{key} = {_toml_value(v)}" for key, v in table.items()]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
