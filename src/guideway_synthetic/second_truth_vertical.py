"""A second, independent generator of synthetic VERTICAL measured runs with known hidden effects.

It writes ``vertical_response`` records in the measured-run format (rig.toml + data.csv,
version 1) whose vertical channel hides one effect the stated model lacks, and returns a
:class:`VerticalTruth`. It was written from the format and the roller-guide literature only (not
from the workflow's own vertical model), to test the workflow's assumptions on records it was
not built from.

Plant (SI units throughout)
---------------------------
One moving mass ``m`` [kg] (the part whose vertical motion is measured) rides on a roller guide
of ``rows`` rows of ``n`` rollers each. As in the rig of Soleimanian et al. (2020, Fig. 2), half
of the rows ("upper") are pressed further by gravity and the external load ``N(t)`` [N], the
other half ("lower") are unloaded by them. ``y`` [m] is the displacement along ``N`` from the
unloaded preloaded position; a roller's approach along its contact normal (at ``theta`` from the
horizontal) is::

    delta_up  = delta_0 + y sin(theta) + h_up        delta_low = delta_0 - y sin(theta) + h_low

Geometry: a rigid displacement ``y`` moves each raceway by ``y sin(theta)`` along the contact
normal, and a roller's load acts on the mass with its vertical component ``Q sin(theta)``
(virtual work). The paper's eq. 3 writes ``y / (2 sin(theta))`` instead, which equals
``y sin(theta)`` only at 45 deg; this generator uses the consistent form at every angle.
``h`` [m] is the lubricant film (zero without a film): a film occupying space between roller and
raceway adds to the solids' approach, as eq. 3 of the paper has it. Equation of motion (the
paper's eq. 1b with ``rows / 2`` rows per side)::

    m y'' = m g + N(t) - (rows / 2) n sin(theta) [Q(delta_up) - Q(delta_low)]

Each roller touches two raceways (rail and carriage): two Palmgren line contacts in series
along its normal (Palmgren 1959, as given by Harris, Rolling Bearing Analysis: each contact's
``delta[mm] = 3.84e-5 Q[N]^0.9 / l[mm]^0.8``, steel), so the roller's approach is twice one
contact's; unloaded (``Q = 0``) where ``delta <= 0``. ``delta_0`` is the approach at
``preload / (rows n)``, the load the format gives each element at rest. (The format says only
"Palmgren's law with roller_length"; one contact per roller would make the guide twice as
stiff.)

Film (``lubricant_film``, the format's ``ehl``): eqs. 4-5 of the paper per row::

    h = h_s (1 - 0.75 exp(132 h' / u)),   h_s = R 13.924 F^-0.045 U^0.647 G^0.46,
    F = Q / (E' R l),  U = eta |u| / (E' R),  G = alpha E'

with ``R`` the roller radius, ``u`` the feed velocity (its magnitude, the entrainment speed, in
``U`` and in the squeeze exponent), ``Q`` the row's current roller load. Solved for ``h'`` it is the state equation ``h' = (|u| / 132) ln(4 (h_s - h) / (3 h_s))``: the
steady film (``h' = 0``) is ``h_s / 4``, a film above it squeezes out, one below it grows. Two
regularisations, both only where the law itself is singular: the exact law forbids ``h >= h_s``
(infinite squeeze rate); below ``1 - h/h_s = SQUEEZE_KNEE`` the logarithm is continued by its
tangent, and ``h_s`` is floored at FILM_FLOOR (standstill, where ``h_s = 0``); the rate's speed
is floored at SQUEEZE_SPEED so a film left at a standstill still squeezes out.

Hidden effects (``EFFECTS`` gives the expected answers)
-------------------------------------------------------
``none``: the truth is the stated model (dry Palmgren rollers, no damping: the format's
``dry_hertz`` names none). ``lubricant_film``: rig.toml states ``dry_hertz``, the truth has the
film above with the stated ``[lubricant]``. ``preload_loss``: the truth preload is a drawn 40-90 %
of the stated one. ``unmodeled_mass``: the truth mass is 8-60 % above ``moving_mass``.
``contact_damping`` (expected ``unknown``): Hunt-Crossley contact damping (Hunt & Crossley 1975,
J Appl Mech 42: the dissipative force proportional to the elastic force), each roller's load
``Q(delta) (1 + beta delta')`` (never below 0) with ``beta`` [s/m] giving damping ratios of about
0.3-5 % (the order of a rolling guide's joint damping). It is load dependent (the upper rows damp
more) and takes energy out of the ringing at the natural frequency; the vocabulary's
``lubricant_film`` adds feed-speed content (its squeeze term dissipates only through the film's
weak load dependence, ``F^-0.045``), ``unmodeled_mass`` and ``preload_loss`` shift the inertia
or stiffness; none of them is a damping that grows with the contact load.

Strength: ``size`` sets the sensor noise against the effect's visible part, the truth's channel
less the stated model's (same inputs) less its mean (a sensor offset, which the workflow
calibrates): noise RMS = visible RMS / (8 size). The effect's own parameters stay in their
physical ranges. For ``none`` the noise is a drawn 0.03-0.3 % of the channel's range.

Record variety (seeded; rig, timing, feed, load and noise colour depend on the seed only)
-----------------------------------------------------------------------------------------
Guide: 4 rows (2 in a fifth of the records), 12-40 rollers per row, radius 1.5-4 mm, length
1.6-3.2 radii, contact angle 45 deg (40-50 deg in 40 % of records), preload 2-12 kN, mass
1-10 kg. Sampling 50-200 kHz, 5,000-20,000 samples unless ``n_samples`` is given, timestamp
jitter in half of the records. Feed (top speed 0.05-0.4 m/s, acceleration at most 5-30 m/s^2):
sinusoidal with a third harmonic (the paper's eq. 1a / 32 fit), triangular strokes with cosine
blends, S-curve moves with dwells, or a multi-sine. Load: a constant 0-50 % of the preload plus
1-3 harmonics, a linear sweep or a random band of 20-60 sines, at 0.15-0.65 or 1.3-2 times the
stated model's natural frequency (the undamped model would grow without bound at resonance).
Channel: ``vertical_displacement`` with a sensor offset of up to 20 um or
``vertical_acceleration`` with a bias of up to 0.5 % of its range; noise white, AR(1) or 1/f,
ADC steps in half of the records, 0-5 outliers. ``feed_position`` as encoder counts,
``feed_velocity`` in half of the records, ``normal_force`` from a load cell with 0.05-0.5 %
noise.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .second_truth import (DWELL, FORMAT, NOISE_COLOURS, VISIBLE_PER_SIZE,
                                                _is_int, _is_real, _log_uniform, _move, _rms,
                                                _schedule_motion, _sine_motion, _stream,
                                                _toml_value, _unit_noise, _write_csv)
from guideway_fmu.diagnose.run_io import REDUCED_MODULUS as STEEL_MODULUS

#: hidden effect -> the answer the workflow should give
EFFECTS = {
    "none": "none",
    "lubricant_film": "lubricant_film",
    "preload_loss": "preload_loss",
    "unmodeled_mass": "unmodeled_mass",
    "contact_damping": "unknown",
}
PROFILES = ("sinusoidal", "triangular", "s_curve", "multi_sine")
LOADS = ("harmonics", "sweep", "random_band")
CHANNELS = ("vertical_displacement", "vertical_acceleration")
GRAVITY = 9.81  # m/s^2
#: Palmgren's roller constant [mm N^-0.9 mm^0.8] and exponents (Harris, Rolling Bearing
#: Analysis, line contact of steel rollers)
PALMGREN = 3.84e-5
PALMGREN_LOAD_EXPONENT = 0.9
PALMGREN_LENGTH_EXPONENT = 0.8
CONTACTS_PER_ROLLER = 2  # raceway contacts in series: rail and carriage
#: eq. 4 of Soleimanian et al. (2020): coefficient, exponents of F, U, G, squeeze factors
FILM_COEFFICIENT = 13.924
FILM_LOAD_EXPONENT = -0.045
FILM_SPEED_EXPONENT = 0.647
FILM_MATERIAL_EXPONENT = 0.46
SQUEEZE_DEPTH = 0.75
SQUEEZE_FACTOR = 132.0
#: regularisations of the squeeze law where it is singular (see the module docstring):
#: smallest unsqueezed film [m] (a tenth of a nanometre, below any real film), the value of
#: 1 - h/h_s below which ln is continued by its tangent, and the slowest squeeze speed [m/s]
FILM_FLOOR = 1e-10
SQUEEZE_KNEE = 1e-2
SQUEEZE_SPEED = 1e-3
#: relative and absolute (per state scale) tolerances of the integration: the integration error
#: is checked in the tests to be far below the noise
RTOL = 1e-11
ATOL_SCALE = 1e-11
#: the noise of a record is at least this fraction of its channel's range (no sensor is better),
#: which bounds ``size``
FINEST_NOISE = 1e-5
MIN_SAMPLES = 500
DEFAULT_SAMPLES = (5000, 20000)


@dataclass(frozen=True)
class VerticalTruth:
    """What a record hides: ``parameters`` (SI floats) holds the hidden effect's parameters and
    the record's true conditions; ``noise_rms`` is the standard deviation of everything the
    sensor adds (noise, ADC steps, outliers; not its offset) and ``effect_rms`` the RMS of the
    effect's visible part, both in the channel's unit (m or m/s^2); ``conditions`` names the
    feed profile, load kind, noise colour and whether timestamps jitter."""

    effect: str
    expected: str
    seed: int
    parameters: dict
    noise_rms: float
    effect_rms: float
    channel: str
    conditions: dict = field(default_factory=dict)


# ----------------------------------------------------------------------------- contact laws


def palmgren_deflection(load, length):
    """Approach [m] of one roller (its CONTACTS_PER_ROLLER line contacts in series) under
    ``load`` [N] (length [m]), Palmgren."""
    q = np.maximum(np.asarray(load, dtype=float), 0.0)
    scale = CONTACTS_PER_ROLLER * 1e-3 * PALMGREN / (1e3 * length) ** PALMGREN_LENGTH_EXPONENT
    return scale * q ** PALMGREN_LOAD_EXPONENT


def palmgren_load(deflection, length):
    """Load [N] of one roller at approach ``deflection`` [m] (:func:`palmgren_deflection`
    inverted); 0 where it is not positive (the contacts open)."""
    d = np.maximum(np.asarray(deflection, dtype=float), 0.0)
    scale = CONTACTS_PER_ROLLER * 1e-3 * PALMGREN / (1e3 * length) ** PALMGREN_LENGTH_EXPONENT
    return (d / scale) ** (1.0 / PALMGREN_LOAD_EXPONENT)


@dataclass(frozen=True)
class Film:
    """Lubricant film of eqs. 4-5 (Soleimanian et al. 2020) for rollers of radius ``radius``
    [m] and length ``length`` [m]: ``viscosity`` [Pa s], ``pressure_viscosity`` [1/Pa],
    ``modulus`` E' [Pa]."""

    viscosity: float
    pressure_viscosity: float
    radius: float
    length: float
    modulus: float

    def unsqueezed(self, load, speed):
        """The law's film without squeeze, ``h_s`` [m], at roller ``load`` [N] and feed
        ``speed`` [m/s] (its magnitude counts); 0 at standstill."""
        e, r = self.modulus, self.radius
        f = np.maximum(np.asarray(load, dtype=float), 1e-9) / (e * r * self.length)
        u = self.viscosity * np.abs(np.asarray(speed, dtype=float)) / (e * r)
        g = self.pressure_viscosity * e
        return (r * FILM_COEFFICIENT * f ** FILM_LOAD_EXPONENT * u ** FILM_SPEED_EXPONENT
                * g ** FILM_MATERIAL_EXPONENT)

    def steady(self, load, speed):
        """Steady film [m] (no squeeze, ``h' = 0``): a quarter of :meth:`unsqueezed`."""
        return (1.0 - SQUEEZE_DEPTH) * self.unsqueezed(load, speed)

    @staticmethod
    def rate(film, unsqueezed, speed):
        """Film rate ``h'`` [m/s] from eq. 4 solved for it, with the regularisations of the
        module docstring."""
        h_s = np.maximum(unsqueezed, FILM_FLOOR)
        gap = (h_s - film) / h_s
        knee = SQUEEZE_KNEE
        log = np.where(gap >= knee, np.log(np.maximum(gap, knee) / SQUEEZE_DEPTH),
                       math.log(knee / SQUEEZE_DEPTH) + (gap - knee) / knee)
        return np.maximum(np.abs(speed), SQUEEZE_SPEED) / SQUEEZE_FACTOR * log


# ----------------------------------------------------------------------------- the plant


@dataclass(frozen=True)
class Guide:
    """A roller guide: ``rows`` (even: half above, half below), ``elements`` rollers per row,
    roller ``radius`` and ``length`` [m], contact angle ``angle_deg``, total ``preload`` [N]."""

    rows: int
    elements: int
    radius: float
    length: float
    angle_deg: float
    preload: float

    @property
    def sine(self) -> float:
        return math.sin(math.radians(self.angle_deg))

    @property
    def rollers_per_side(self) -> int:
        return self.rows // 2 * self.elements

    @property
    def preload_approach(self) -> float:
        """Approach [m] of each roller at rest: Palmgren at ``preload / (rows elements)``."""
        return float(palmgren_deflection(self.preload / (self.rows * self.elements), self.length))

    def approaches(self, y, film_up=0.0, film_low=0.0):
        """Roller approaches [m] of the upper and lower rows at displacement ``y`` [m]."""
        d0, s = self.preload_approach, self.sine
        return d0 + y * s + film_up, d0 - y * s + film_low

    def vertical_force(self, y, film_up=0.0, film_low=0.0):
        """Net upward force [N] of all rollers on the mass at displacement ``y`` (dry loads)."""
        up, low = self.approaches(y, film_up, film_low)
        return self.rollers_per_side * self.sine * (palmgren_load(up, self.length)
                                                    - palmgren_load(low, self.length))


@dataclass(frozen=True)
class Plant:
    """Mass ``mass`` [kg] on ``guide``, with an optional ``film`` and Hunt-Crossley
    ``damping`` beta [s/m]; ``force(t)`` the external load [N], ``speed(t)`` the feed
    velocity [m/s]."""

    guide: Guide
    mass: float
    film: Film | None = None
    damping: float = 0.0

    def loads(self, state):
        """Roller loads [N] (upper, lower) for states [y, v(, h_up, h_low)] (columns)."""
        g = self.guide
        y, v = state[0], state[1]
        h_up, h_low = (state[2], state[3]) if self.film else (0.0, 0.0)
        up, low = g.approaches(y, h_up, h_low)
        q_up, q_low = palmgren_load(up, g.length), palmgren_load(low, g.length)
        if self.damping:
            q_up = np.maximum(q_up * (1 + self.damping * v * g.sine), 0.0)
            q_low = np.maximum(q_low * (1 - self.damping * v * g.sine), 0.0)
        return q_up, q_low

    def derivative(self, t, state, force, speed):
        """d/dt [y, v(, h_up, h_low)]; works on columns of states (vectorised)."""
        g = self.guide
        q_up, q_low = self.loads(state)
        accel = (self.mass * GRAVITY + force(t)
                 - g.rollers_per_side * g.sine * (q_up - q_low)) / self.mass
        if not self.film:
            return np.array([state[1], accel])
        u = speed(t)
        return np.array([state[1], accel,
                         Film.rate(state[2], self.film.unsqueezed(q_up, u), u),
                         Film.rate(state[3], self.film.unsqueezed(q_low, u), u)])

    def equilibrium(self, force0, speed0) -> np.ndarray:
        """State at rest in static equilibrium under gravity and ``force0`` [N], the film
        steady at feed velocity ``speed0`` [m/s] (the format's start of a record)."""
        g = self.guide
        load = self.mass * GRAVITY + force0

        def films(y):
            if not self.film:
                return 0.0, 0.0
            h = [0.0, 0.0]
            for _ in range(60):  # fixed point: h depends on its own load through F^-0.045
                up, low = g.approaches(y, *h)
                new = [float(self.film.steady(palmgren_load(a, g.length), speed0))
                       for a in (up, low)]
                if max(abs(n - o) for n, o in zip(new, h)) <= 1e-15 + 1e-13 * max(new):
                    return tuple(new)
                h = new
            raise RuntimeError("the steady film did not converge")

        def imbalance(y):
            return float(g.vertical_force(y, *films(y))) - load

        reach = 10 * g.preload_approach / g.sine + abs(load) / 1e7
        y0 = brentq(imbalance, -reach, reach, xtol=1e-18, rtol=1e-15, maxiter=400)
        return np.array([y0, 0.0, *films(y0)]) if self.film else np.array([y0, 0.0])

    def simulate(self, times, force, speed, max_step=np.inf):
        """States [y, v(, h...)] (rows) and acceleration [m/s^2] at ``times`` [s], from
        :meth:`equilibrium` at ``times[0]``. LSODA (stiff where the film collapses) with
        RTOL and absolute tolerances ATOL_SCALE times each state's natural scale."""
        start = self.equilibrium(float(force(times[0])), float(speed(times[0])))
        d0 = self.guide.preload_approach
        omega = math.sqrt(self.stiffness() / self.mass)
        scales = [d0, d0 * omega] + ([d0, d0] if self.film else [])
        solution = solve_ivp(self.derivative, (times[0], times[-1]), start, method="LSODA",
                             t_eval=times, rtol=RTOL, atol=ATOL_SCALE * np.array(scales),
                             args=(force, speed), max_step=max_step)
        if not solution.success:
            raise RuntimeError(f"integration failed: {solution.message}")
        states = solution.y
        return states, self.derivative(times, states, force, speed)[1]

    def stiffness(self, y=0.0) -> float:
        """Dry vertical stiffness [N/m] at ``y``: central difference of the roller force."""
        step = 1e-4 * self.guide.preload_approach
        return float(self.guide.vertical_force(y + step) - self.guide.vertical_force(y - step)) \
            / (2 * step)


# ----------------------------------------------------------------------------- draw


def draw(out_dir, effect: str, seed: int, *, n_samples: int | None = None,
         size: float = 1.0) -> VerticalTruth:
    """Write ``out_dir``/rig.toml and ``out_dir``/data.csv hiding ``effect`` in a vertical
    record and return its :class:`VerticalTruth`. The same arguments give the same bytes.
    ``n_samples`` None draws 5,000-20,000 samples from the seed; ``size`` > 0 sets the visible
    effect to ``8 size`` times the noise RMS (ignored for ``none``).

    Raises ValueError naming the argument that is wrong, or ``size`` where the noise would have
    to be finer than FINEST_NOISE of the channel's range.
    """
    _check_arguments(effect, seed, n_samples, size)
    rig = _draw_rig(seed)
    times, rate, jitter = _draw_times(seed, n_samples)
    feed_profile, feed = _draw_feed(seed, times[-1])

    def speed(t):
        return feed(np.atleast_1d(np.asarray(t, dtype=float)))[1].reshape(np.shape(t))
    stated = Plant(rig.guide, rig.mass)
    resting = stated.equilibrium(0.0, 0.0)[0]
    natural = math.sqrt(stated.stiffness(resting) / rig.mass) / (2 * math.pi)
    load_kind, force, top_frequency = _draw_load(seed, rig, natural, rate, times[-1])
    truth_plant, hidden = _truth_plant(effect, seed, rig)
    channel = CHANNELS[int(_stream(seed, "channel").integers(2))]
    max_step = 0.1 / max(top_frequency, natural)

    def record(plant):
        states, accel = plant.simulate(times, force, speed, max_step)
        return states[0] if channel == "vertical_displacement" else accel

    true_signal = record(truth_plant)
    visible = true_signal - record(stated) if effect != "none" else np.zeros_like(true_signal)
    visible = visible - visible.mean()
    span = float(np.ptp(true_signal))
    noise = _draw_noise(seed, times.size)
    if effect == "none":
        wanted = span * float(_log_uniform(_stream(seed, "noise_level"), 3e-4, 3e-3))
    else:
        wanted = _rms(visible) / (VISIBLE_PER_SIZE * size)
        if wanted < FINEST_NOISE * span:
            raise ValueError(f"size {size} is too large for {effect} on this record: the noise "
                             f"would be {wanted / span:.1e} of the range (at least {FINEST_NOISE})")
    level = wanted / noise.rms_per_level
    offset = _draw_offset(seed, channel, span)
    measured = noise.record(true_signal + offset, level)

    columns = {"time": times, **_feed_columns(seed, feed, times)}
    columns["normal_force"] = _load_cell(seed, force(times))
    columns[channel] = measured
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    _write_csv(out / "data.csv", columns)
    _write_rig(out / "rig.toml", seed, rig, effect, channel, [c for c in columns
                                                              if c not in ("time", channel)],
               feed_profile, load_kind)
    truth_guide = truth_plant.guide
    parameters = {"size": size, "mass": truth_plant.mass, "preload": truth_guide.preload,
                  "natural_frequency_stated": natural, "sampling_rate": rate,
                  "sensor_offset": offset, "noise_level": level, "channel_range": span,
                  **hidden}
    return VerticalTruth(
        effect=effect, expected=EFFECTS[effect], seed=int(seed),
        parameters={k: float(v) + 0.0 for k, v in parameters.items()},
        noise_rms=float(np.std(measured - true_signal - offset)),
        effect_rms=_rms(visible), channel=channel,
        conditions={"feed_profile": feed_profile, "load": load_kind, "noise_colour": noise.colour,
                    "jitter": str(jitter).lower()})


def _check_arguments(effect, seed, n_samples, size):
    if effect not in EFFECTS:
        raise ValueError(f"effect {effect!r} is not one of: {', '.join(EFFECTS)}")
    if not _is_int(seed) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    if n_samples is not None and (not _is_int(n_samples) or n_samples < MIN_SAMPLES):
        raise ValueError(f"n_samples must be None or an integer >= {MIN_SAMPLES}, "
                         f"got {n_samples!r}")
    if not _is_real(size) or not math.isfinite(size) or size <= 0:
        raise ValueError(f"size must be a finite number > 0 (it divides the noise), got {size!r}")


# ----------------------------------------------------------------------------- rig and effect


@dataclass(frozen=True)
class _Rig:
    guide: Guide  # the stated guide
    mass: float  # kg, true mass (stated too, but for unmodeled_mass)
    viscosity: float  # Pa s
    pressure_viscosity: float  # 1/Pa
    modulus_written: bool  # whether rig.toml states reduced_modulus
    roughness: float | None  # m, [surface] roughness where written


def _draw_rig(seed) -> _Rig:
    rng = _stream(seed, "rig")
    rows = 2 if rng.random() < 0.2 else 4
    radius = rng.uniform(1.5e-3, 4.0e-3)
    angle = 45.0 if rng.random() < 0.6 else float(rng.uniform(40.0, 50.0))
    guide = Guide(rows=rows, elements=int(rng.integers(12, 41)), radius=radius,
                  length=radius * rng.uniform(1.6, 3.2), angle_deg=angle,
                  preload=float(_log_uniform(rng, 2000.0, 12000.0)))
    roughness = rng.uniform(0.1e-6, 0.5e-6) if rng.random() < 0.5 else None
    return _Rig(guide, float(rng.uniform(1.0, 10.0)), float(_log_uniform(rng, 0.02, 0.3)),
                float(rng.uniform(1.5e-8, 2.5e-8)), bool(rng.random() < 0.4), roughness)


def _truth_plant(effect, seed, rig) -> tuple[Plant, dict]:
    """The plant that makes the record and the hidden effect's parameters."""
    rng = _stream(seed, "effect")
    if effect == "lubricant_film":
        film = Film(rig.viscosity, rig.pressure_viscosity, rig.guide.radius, rig.guide.length,
                    STEEL_MODULUS)
        return Plant(rig.guide, rig.mass, film=film), {}
    if effect == "preload_loss":
        kept = rng.uniform(0.4, 0.9)
        return Plant(replace(rig.guide, preload=rig.guide.preload * kept), rig.mass), \
            {"preload_kept": kept}
    if effect == "unmodeled_mass":
        extra = rng.uniform(0.08, 0.6)
        return Plant(rig.guide, rig.mass * (1 + extra)), {"missing_mass": rig.mass * extra}
    if effect == "contact_damping":
        stated = Plant(rig.guide, rig.mass)
        ratio = float(_log_uniform(rng, 3e-3, 5e-2))
        # linear damping of Q (1 + beta delta') at rest: beta sum(Q0) sin^2 = 2 ratio sqrt(k m)
        g = rig.guide
        beta = 2 * ratio * math.sqrt(stated.stiffness() * rig.mass) / (g.preload * g.sine ** 2)
        return Plant(g, rig.mass, damping=beta), {"hunt_crossley_beta": beta,
                                                  "damping_ratio_at_rest": ratio}
    return Plant(rig.guide, rig.mass), {}


# ----------------------------------------------------------------------------- timing, feed, load


def _draw_times(seed, n_samples) -> tuple[np.ndarray, float, bool]:
    """Sample instants [s] (from 0), the sampling rate [Hz] and whether they jitter (by up to
    a quarter period, so they stay strictly increasing)."""
    rng = _stream(seed, "timing")
    rate = float(_log_uniform(rng, 50e3, 200e3))
    drawn = int(rng.integers(DEFAULT_SAMPLES[0], DEFAULT_SAMPLES[1] + 1))
    n = drawn if n_samples is None else int(n_samples)
    jitter = bool(rng.random() < 0.5)
    times = np.arange(n) / rate
    if jitter:
        spread = rng.uniform(0.02, 0.25) / rate
        times[1:] += np.clip(spread * rng.standard_normal(n - 1), -0.25 / rate, 0.25 / rate)
    return times, rate, jitter


def _draw_feed(seed, duration):
    """A feed profile name and motion ``t -> (x, v, a)`` [m, m/s, m/s^2] over [0, duration],
    top speed 0.05-0.4 m/s, acceleration at most 5-30 m/s^2 (a machine-tool feed drive)."""
    rng = _stream(seed, "feed")
    profile = str(rng.choice(PROFILES))
    top = rng.uniform(0.05, 0.4)
    most_accel = rng.uniform(5.0, 30.0)
    if profile in ("sinusoidal", "multi_sine"):
        if profile == "sinusoidal":  # eq. 1a / 32: a fundamental and its third harmonic
            cycles = np.array([1.0, 3.0]) * rng.uniform(1.0, 4.0)
            weights = np.array([1.0, rng.uniform(0.0, 0.1)])
        else:
            cycles = rng.uniform(0.5, 6.0, int(rng.integers(3, 6)))
            weights = rng.uniform(0.3, 1.0, cycles.size)
        omegas = 2 * np.pi * cycles / duration
        phases = rng.uniform(0, 2 * np.pi, cycles.size)
        grid = np.linspace(0.0, duration, 4001)
        unit = _sine_motion(weights / omegas, omegas, phases)  # unit weights are velocities
        _, v, a = unit(grid)
        k = min(top / np.max(np.abs(v)), most_accel / np.max(np.abs(a)))
        return profile, _sine_motion(k * weights / omegas, omegas, phases)
    if profile == "triangular":
        strokes = int(rng.integers(2, 7))
        stroke_time = duration / (strokes + 0.3)
        ramp = max(stroke_time * rng.uniform(0.05, 0.25), math.pi * top / (2 * most_accel))
        ramp = min(ramp, 0.45 * stroke_time)
        speed = min(top, 2 * ramp * most_accel / math.pi)
        distance = speed * (stroke_time - ramp)
        segments = [(DWELL, 0.15 * stroke_time, 0.0)]
        for i in range(strokes + 1):
            segments += _move((-1) ** i * distance, ramp, stroke_time - 2 * ramp)
        return profile, _schedule_motion(0.0, segments)
    moves = int(rng.integers(1, 5))
    slot = duration / moves
    segments = [(DWELL, 0.1 * slot, 0.0)]
    for _ in range(moves + 1):
        move_time = slot * rng.uniform(0.5, 0.85)
        ramp = move_time * rng.uniform(0.3, 0.5)
        speed = min(top * rng.uniform(0.4, 1.0), 2 * ramp * most_accel / math.pi)
        segments += _move(rng.choice([-1.0, 1.0]) * speed * (move_time - ramp), ramp,
                          move_time - 2 * ramp)
        segments.append((DWELL, slot - move_time, 0.0))
    return profile, _schedule_motion(0.0, segments)


#: bands of the load's dynamic part, in natural frequencies of the stated model: below and
#: above resonance, with room for the truth's shifted resonance (mass up to +60 %: 0.79 f_n).
#: The stated (dry, undamped) model has no damping, so excitation at resonance would grow
#: without bound.
LOAD_BANDS = ((0.15, 0.65), (1.3, 2.0))


def band(ratios, natural, rate) -> tuple[float, float]:
    """The load band [Hz]: ``ratios`` (a LOAD_BANDS entry) times the ``natural`` frequency [Hz],
    cut at a quarter of the sampling ``rate`` [Hz]. A band above resonance that the cut leaves
    narrower than 1.2 : 1 gives way to the one below."""
    low, high = ratios[0] * natural, min(ratios[1] * natural, 0.25 * rate)
    if high < 1.2 * low and ratios[0] > 1.0:
        return band(LOAD_BANDS[0], natural, rate)
    return low, high


def _draw_load(seed, rig, natural, rate, duration):
    """The load kind, ``t -> N(t)`` [N] and the highest frequency it holds [Hz]. A constant
    0-50 % of the preload plus a dynamic part peaking at 1-10 % of it, in one of LOAD_BANDS
    (1-3 harmonics, a linear sweep or a random band of 20-60 sines), below a quarter of the
    sampling rate."""
    rng = _stream(seed, "load")
    kind = str(rng.choice(LOADS))
    preload = rig.guide.preload
    mean = preload * rng.uniform(0.0, 0.5)
    amplitude = preload * rng.uniform(0.01, 0.1)
    low, high = band(LOAD_BANDS[int(rng.random() < 0.35)], natural, rate)
    if kind == "harmonics":
        count = int(rng.integers(1, 4))
        frequencies = rng.uniform(low, high, count)
        weights = rng.uniform(0.3, 1.0, count)
        phases = rng.uniform(0, 2 * np.pi, count)
    elif kind == "random_band":
        count = int(rng.integers(20, 61))
        frequencies = rng.uniform(low, high, count)
        weights = np.ones(count)
        phases = rng.uniform(0, 2 * np.pi, count)
    else:
        start, stop = rng.uniform(low, high, 2)
        phase = rng.uniform(0, 2 * np.pi)

        def force(t):
            t = np.asarray(t, dtype=float)
            return mean + amplitude * np.sin(2 * np.pi * (start * t + (stop - start) * t * t
                                                          / (2 * duration)) + phase)
        return kind, force, float(max(start, stop))

    def shape(t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return np.sum(weights[:, None] * np.sin(2 * np.pi * frequencies[:, None] * t[None, :]
                                                + phases[:, None]), 0)

    peak = np.max(np.abs(shape(np.linspace(0.0, duration, 20001))))

    def force(t):
        return mean + amplitude / peak * shape(t).reshape(np.shape(t))
    return kind, force, float(frequencies.max())


def _feed_columns(seed, feed, times) -> dict:
    """feed_position as encoder counts (50 nm-1 um, arbitrary zero) and, in half of the records,
    feed_velocity with 0.1-0.5 % white noise."""
    rng = _stream(seed, "encoder")
    x, v, _ = feed(times)
    step = float(_log_uniform(rng, 5e-8, 1e-6))
    columns = {"feed_position": step * np.round((x + rng.uniform(-0.1, 0.1)) / step)}
    if rng.random() < 0.5:
        columns["feed_velocity"] = v + np.max(np.abs(v)) * rng.uniform(1e-3, 5e-3) \
            * rng.standard_normal(v.size)
    return columns


def _load_cell(seed, force) -> np.ndarray:
    """The recorded normal force: load-cell noise of 0.05-0.5 % of the load's range."""
    rng = _stream(seed, "load_cell")
    return force + np.ptp(force) * rng.uniform(5e-4, 5e-3) * rng.standard_normal(force.size)


# ----------------------------------------------------------------------------- sensor


@dataclass(frozen=True)
class _Noise:
    unit: np.ndarray  # noise + outliers at level 1
    adc_ratio: float  # ADC step per unit level (0: none)
    colour: str

    @property
    def rms_per_level(self) -> float:
        """The sensor error's standard deviation at level 1 (ADC steps as step^2 / 12)."""
        return math.sqrt(float(np.var(self.unit)) + self.adc_ratio ** 2 / 12)

    def record(self, clean, level) -> np.ndarray:
        value = clean + level * self.unit
        if self.adc_ratio:
            step = self.adc_ratio * level
            value = step * np.round(value / step)
        return value


def _draw_noise(seed, n) -> _Noise:
    rng = _stream(seed, "noise")
    colour = str(rng.choice(NOISE_COLOURS))
    unit = _unit_noise(rng, colour, n)
    outliers = int(rng.integers(0, 6))
    where = rng.choice(n, outliers, replace=False)
    unit[where] += rng.uniform(6.0, 15.0, outliers) * rng.choice([-1.0, 1.0], outliers)
    adc = rng.uniform(0.3, 1.5) if rng.random() < 0.5 else 0.0
    return _Noise(unit, float(adc), colour)


def _draw_offset(seed, channel, span) -> float:
    """A displacement sensor's zero (up to 20 um) or an accelerometer's bias (up to 0.5 % of
    the channel's range)."""
    rng = _stream(seed, "offset")
    if channel == "vertical_displacement":
        return float(rng.uniform(-2e-5, 2e-5))
    return float(span * rng.uniform(-5e-3, 5e-3))


# ----------------------------------------------------------------------------- rig.toml


def _write_rig(path: Path, seed, rig, effect, channel, inputs, feed_profile, load_kind) -> None:
    g = rig.guide
    stated_mass = rig.mass
    guideway = {"type": "roller", "rows": g.rows, "elements_per_row": g.elements,
                "element_radius": g.radius, "roller_length": g.length,
                "contact_angle_deg": g.angle_deg, "preload": g.preload}
    if rig.modulus_written:
        guideway["reduced_modulus"] = STEEL_MODULUS
    tables = {
        "rig": {"kind": "vertical_response",
                "description": f"synthetic vertical record, {feed_profile.replace('_', ' ')} "
                               f"feed, {load_kind.replace('_', ' ')} load",
                "moving_mass": stated_mass},
        "guideway": guideway,
        "lubricant": {"viscosity": rig.viscosity, "pressure_viscosity": rig.pressure_viscosity},
    }
    if rig.roughness is not None:
        tables["surface"] = {"roughness_rms": rig.roughness}
    # the format marks no [model] key optional: a friction component is named although a
    # vertical response does not use it
    tables["model"] = {"friction": "coulomb", "contact": "dry_hertz"}
    tables["channels"] = {"inputs": inputs, "outputs": [channel]}
    lines = [f'format = "{FORMAT}"']
    for name, table in tables.items():
        lines += ["", f"[{name}]"] + [f"{key} = {_toml_value(v)}" for key, v in table.items()]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
