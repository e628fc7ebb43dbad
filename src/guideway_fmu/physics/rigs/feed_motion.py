"""Prescribed feed (horizontal) motion of the moving part of a linear guideway.

Each profile is a frozen dataclass whose ``evaluate(t)`` returns position x [m],
velocity u [m/s] and acceleration a [m/s^2] at the time(s) t [s], analytically:
x is the exact integral of u with x(0) = 0 and a is the exact derivative of u.
Arrays in give arrays of the same shape out, a scalar gives floats. ``velocity_at(t)``
is u alone for one float t, in plain floats (0.1 to 4 us against 3 to 60 for ``evaluate``),
for integrators that call it at every step. Profiles check their fields on construction
(``validate``), so an invalid profile cannot exist.

Reference: Soleimanian, Mohammadpour, Ahmadian (2020), eq. (1a), eq. (33), Table 1.
"""
from __future__ import annotations

import bisect
import csv
import inspect
import math
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np
from scipy.integrate import cumulative_trapezoid

from .. import checks
from ..dynamics import ContinuousModel
from ..papers import soleimanian2020 as paper

__all__ = [
    "FeedProfile", "BiHarmonic", "Oscillating", "Constant", "Trapezoid", "Table", "Replay",
    "make_profile", "from_parameters", "PROFILES", "FeedModel", "linear_at", "read_csv_columns",
    "check_csv_columns",
]

#: profile names of the FeedKinematics FMU; "input" takes the velocity from an input instead
PROFILES = ("biharmonic", "oscillating", "constant", "trapezoid", "table", "replay", "input")


class FeedProfile:
    """Base of the profiles: ``evaluate(t) -> (x, u, a)``; checked by ``validate`` when created."""

    def __post_init__(self):
        self.validate()


def _time(t):
    """A float stays a float (math fast path of :func:`_sine`); anything else becomes an array."""
    return t if isinstance(t, float) else np.asarray(t, dtype=float)


def _result(t, *values):
    """Broadcast the values to the shape of ``t``; plain floats for a scalar ``t``."""
    if isinstance(t, float) or t.ndim == 0:
        return tuple(float(v) for v in values)
    return tuple(v + np.zeros(t.shape) for v in values)


def _sine(t: np.ndarray, amplitude: float, omega: float, phase: float):
    """(x, u, a) of u = amplitude sin(omega t + phase), omega [rad/s], x(0) = 0."""
    trig = math if isinstance(t, float) else np
    arg = omega * t + phase
    cos_arg = trig.cos(arg)
    return (
        amplitude / omega * (math.cos(phase) - cos_arg),
        amplitude * trig.sin(arg),
        amplitude * omega * cos_arg,
    )


@dataclass(frozen=True)
class BiHarmonic(FeedProfile):
    """Rig-fitted feed velocity, paper eq. (1a), with the third harmonic:

    u = amplitude1 sin(2 pi f t + phase1) + amplitude2 sin(2 pi (3 f) t + phase2).

    The printed eq. (1a) repeats f_v in both terms, but the text (Experimental rig)
    states the fit uses the first and third multiples of the excitation frequency,
    so the second term runs at 3 f. Amplitudes [m/s], phases [rad], frequency f [Hz].
    """

    amplitude1: float = paper.RIG_AMPLITUDE_1
    amplitude2: float = paper.RIG_AMPLITUDE_2
    phase1: float = paper.RIG_PHASE_1
    phase2: float = paper.RIG_PHASE_2
    frequency: float = paper.FEED_FREQUENCY

    def validate(self) -> None:
        checks.check_fields(self, {
            "amplitude1": checks.finite, "amplitude2": checks.finite,
            "phase1": checks.finite, "phase2": checks.finite,
            "frequency": checks.positive,
        })

    def evaluate(self, t):
        t = _time(t)
        omega = 2.0 * np.pi * self.frequency
        first = _sine(t, self.amplitude1, omega, self.phase1)
        third = _sine(t, self.amplitude2, 3.0 * omega, self.phase2)
        return _result(t, *(p + q for p, q in zip(first, third)))

    def velocity_at(self, t: float) -> float:
        """u [m/s] at the time t [s] (float)."""
        arg = 2.0 * math.pi * self.frequency * t
        return (self.amplitude1 * math.sin(arg + self.phase1)
                + self.amplitude2 * math.sin(3.0 * arg + self.phase2))


@dataclass(frozen=True)
class Oscillating(FeedProfile):
    """Oscillating feed velocity, paper eq. (33): u = mean - amplitude sin(2 pi f t).

    Defaults from Table 1: mean u_bar = 0.2375 m/s, amplitude a_u = 0.25 m/s, f_v = 5 Hz.
    """

    mean: float = paper.HESS_SOOM_MEAN_SPEED
    amplitude: float = paper.HESS_SOOM_SPEED_AMPLITUDE
    frequency: float = paper.FEED_FREQUENCY

    def validate(self) -> None:
        checks.check_fields(self, {
            "mean": checks.finite, "amplitude": checks.finite,
            "frequency": checks.positive,
        })

    def evaluate(self, t):
        t = _time(t)
        x, u, a = _sine(t, -self.amplitude, 2.0 * np.pi * self.frequency, 0.0)
        return _result(t, self.mean * t + x, self.mean + u, a)

    def velocity_at(self, t: float) -> float:
        """u [m/s] at the time t [s] (float)."""
        return self.mean - self.amplitude * math.sin(2.0 * math.pi * self.frequency * t)


@dataclass(frozen=True)
class Constant(FeedProfile):
    """Constant feed velocity u = velocity [m/s], by default the rig's feed speed."""

    velocity: float = paper.RIG_SPEED

    def validate(self) -> None:
        checks.check_fields(self, {"velocity": checks.finite})

    def evaluate(self, t):
        t = _time(t)
        return _result(t, self.velocity * t, self.velocity, 0.0)

    def velocity_at(self, t: float) -> float:
        """u [m/s] at the time t [s] (float)."""
        return self.velocity


@dataclass(frozen=True)
class Trapezoid(FeedProfile):
    """Point-to-point move of ``distance`` [m] (sign = direction) starting at ``t_start`` [s].

    Accelerates at ``a_max`` [m/s^2] up to ``v_max`` [m/s], cruises, decelerates at
    ``a_max``; triangular (peak sqrt(|distance| a_max)) when v_max cannot be reached.
    At rest before ``t_start`` and after ``t_start + duration``.
    """

    distance: float = 0.1
    v_max: float = 0.3
    a_max: float = 3.0
    t_start: float = 0.0

    def validate(self) -> None:
        checks.check_fields(self, {
            "distance": checks.finite, "v_max": checks.positive,
            "a_max": checks.positive, "t_start": checks.non_negative,
        })

    @property
    def peak_velocity(self) -> float:
        """Highest speed reached [m/s] (magnitude)."""
        return min(self.v_max, math.sqrt(abs(self.distance) * self.a_max))

    @property
    def ramp_time(self) -> float:
        """Duration of the acceleration (and of the deceleration) phase [s]."""
        return self.peak_velocity / self.a_max

    @property
    def duration(self) -> float:
        """Time of the whole move [s]."""
        peak, ramp = self.peak_velocity, self.ramp_time
        cruise = max(abs(self.distance) / peak - ramp, 0.0) if peak > 0.0 else 0.0
        return 2.0 * ramp + cruise

    def evaluate(self, t):
        t = np.asarray(t, dtype=float)
        peak, ramp, end, acc = self.peak_velocity, self.ramp_time, self.duration, self.a_max
        tau = np.clip(t - self.t_start, 0.0, end)
        left = end - tau
        accelerating = tau < ramp
        decelerating = ~accelerating & (tau >= end - ramp)
        x = np.where(accelerating, 0.5 * acc * tau**2,
                     np.where(decelerating, abs(self.distance) - 0.5 * acc * left**2,
                              peak * (tau - 0.5 * ramp)))
        moving = (t >= self.t_start) & (t < self.t_start + end)
        u = np.where(moving, np.minimum(np.minimum(acc * tau, acc * left), peak), 0.0)
        a = np.where(moving & accelerating, acc, np.where(moving & decelerating, -acc, 0.0))
        sign = np.sign(self.distance)
        return _result(t, sign * x, sign * u, sign * a)

    def velocity_at(self, t: float) -> float:
        """u [m/s] at the time t [s] (float)."""
        tau, end = t - self.t_start, self.duration
        if not 0.0 <= tau < end:
            return 0.0
        speed = min(self.a_max * tau, self.a_max * (end - tau), self.peak_velocity)
        return math.copysign(speed, self.distance)


def linear_at(time, values, t: float) -> float:
    """values interpolated linearly at the time t [s] in the sequence ``time`` (increasing),
    held at the end values outside it: one float in plain Python, a few microseconds against
    np.interp's tens on long tables, for integrators that ask at every step."""
    if t <= time[0]:
        return values[0]
    if t >= time[-1]:
        return values[-1]
    k = bisect.bisect_right(time, t) - 1
    return values[k] + (values[k + 1] - values[k]) * (t - time[k]) / (time[k + 1] - time[k])


def _table_problem(time: np.ndarray, velocity: np.ndarray):
    """First defect of a velocity table as (field, index, text), or None."""
    for field, values in (("time", time), ("velocity", velocity)):
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            return field, int(bad[0]), f"must be finite, got {values[bad[0]]}"
    bad = np.flatnonzero(np.diff(time) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        return "time", i, f"must increase strictly, got {time[i]} after {time[i - 1]}"
    return None


def _check_samples(owner: str, time: np.ndarray, columns: dict) -> None:
    """Raise ValueError naming ``owner``.field[index] unless ``time`` [s] holds at least 2
    samples and every column is as long, finite, and sampled at strictly increasing times."""
    if time.size < 2:
        raise ValueError(f"{owner}.time must hold at least 2 samples, got {time.size}")
    for name, values in columns.items():
        if values.size != time.size:
            raise ValueError(f"{owner}.{name} must have as many samples as {owner}.time "
                             f"({time.size}), got {values.size}")
        problem = _table_problem(time, values)
        if problem:
            field, index, text = problem
            raise ValueError(f"{owner}.{'time' if field == 'time' else name}[{index}] {text}")


def read_csv_columns(path, columns):
    """Data of a comma-separated file with a header row: {column: numbers} and the file's line
    number of every data row (header = row 1; blank lines are skipped).

    ``columns`` lists what to read; an entry that is a tuple of alternative names reads the
    first of them the header has. Errors name the file, the row and the column. The rows are
    read one at a time into a float array (a replay of 1e6 samples held as lists of cells
    took a third of a gigabyte).
    """
    path = Path(path)
    with path.open("rb") as handle:
        lines = sum(chunk.count(b"\n") for chunk in iter(lambda: handle.read(1 << 20), b"")) + 1
    with path.open(newline="") as handle:
        rows = ((n, cells) for n, cells in enumerate(csv.reader(handle), start=1)
                if any(cell.strip() for cell in cells))
        header_row, header = next(rows, (1, []))
        header = [c.strip() for c in header]
        chosen = []
        for entry in columns:
            names = entry if isinstance(entry, tuple) else (entry,)
            name = next((n for n in names if n in header), None)
            if name is None:
                wanted = " or ".join(repr(n) for n in names)
                raise ValueError(f"{path}: row {header_row}: header {header} has no column {wanted}")
            chosen.append(name)
        values = np.empty((lines, len(chosen)))
        numbers = np.empty(lines, dtype=int)
        count = 0
        for row, cells in rows:
            for j, name in enumerate(chosen):
                k = header.index(name)
                cell = cells[k].strip() if k < len(cells) else ""
                try:
                    values[count, j] = float(cell)
                except ValueError:
                    raise ValueError(f"{path}: row {row}, column '{name}': "
                                     f"cannot read a number from {cell!r}") from None
            numbers[count] = row
            count += 1
    if count < 2:
        raise ValueError(f"{path}: needs at least 2 data rows, got {count}")
    return dict(zip(chosen, values[:count].T.copy())), numbers[:count]


def check_csv_columns(path, columns: dict, rows: list, time: str):
    """Raise ValueError naming file, row and column at the first defect (:func:`_table_problem`)
    of any column of ``columns`` against the ``time`` column."""
    for name, values in columns.items():
        problem = _table_problem(columns[time], values)
        if problem:
            field, index, text = problem
            raise ValueError(f"{path}: row {rows[index]}, column "
                             f"'{time if field == 'time' else name}': {text}")


@dataclass(frozen=True)
class Table(FeedProfile):
    """Replay of a measured velocity table: ``time`` [s] and ``velocity`` [m/s].

    u is linearly interpolated and held at the end values outside the table (a = 0
    there); a is the slope of the current segment. x is the exact integral of u from
    time[0]: x = 0 for t <= time[0], constant-velocity extrapolation after time[-1].
    The columns are stored as tuples of floats.
    """

    time: tuple
    velocity: tuple

    def __post_init__(self):
        super().__post_init__()
        object.__setattr__(self, "time", tuple(np.asarray(self.time, dtype=float).tolist()))
        object.__setattr__(self, "velocity", tuple(np.asarray(self.velocity, dtype=float).tolist()))

    def validate(self) -> None:
        columns = {}
        for field in ("time", "velocity"):
            try:
                columns[field] = np.asarray(getattr(self, field), dtype=float)
            except (TypeError, ValueError):
                raise ValueError(f"Table.{field} must be a sequence of numbers") from None
            if columns[field].ndim != 1:
                raise ValueError(f"Table.{field} must be one-dimensional, "
                                 f"got shape {columns[field].shape}")
        _check_samples("Table", columns.pop("time"), columns)

    @cached_property
    def _nodes(self):
        """Node times, velocities, positions (cumulative trapezoid) and segment slopes."""
        time, velocity = np.array(self.time), np.array(self.velocity)
        position = cumulative_trapezoid(velocity, time, initial=0.0)
        return time, velocity, position, np.diff(velocity) / np.diff(time)

    def evaluate(self, t):
        t = np.asarray(t, dtype=float)
        time, velocity, position, slope = self._nodes
        inside = np.clip(t, time[0], time[-1])
        k = np.clip(np.searchsorted(time, inside, side="right") - 1, 0, time.size - 2)
        u = np.interp(t, time, velocity)
        x = (position[k] + 0.5 * (velocity[k] + u) * (inside - time[k])
             + u * np.maximum(t - inside, 0.0))
        a = np.where((t >= time[0]) & (t < time[-1]), slope[k], 0.0)
        return _result(t, x, u, a)

    def velocity_at(self, t: float) -> float:
        """u [m/s] at the time t [s] (float)."""
        return linear_at(self.time, self.velocity, t)

    @classmethod
    def from_csv(cls, path) -> "Table":
        """Read a comma-separated file whose header names ``time`` [s] and
        ``feed_velocity`` or ``u`` [m/s] (``feed_velocity`` wins if both are present).

        Rows are numbered as lines of the file, the header being row 1; blank lines
        are skipped. Errors name the file, the row and the column.
        """
        columns, rows = read_csv_columns(path, ["time", ("feed_velocity", "u")])
        check_csv_columns(path, columns, rows, "time")
        time, velocity = columns.values()
        return cls(time=tuple(time), velocity=tuple(velocity))


@dataclass(frozen=True)
class Replay(FeedProfile):
    """Replay of a measured motion: ``time`` [s] with ``position`` [m], ``velocity`` [m/s] and
    ``acceleration`` [m/s^2] given at every sample, each interpolated linearly and held at the
    end values outside the table. The columns need not be consistent with each other: a replay
    reproduces the samples as measured (or as derived from the measurement).
    """

    time: tuple
    position: tuple
    velocity: tuple
    acceleration: tuple

    COLUMNS = ("time", "feed_position", "feed_velocity", "feed_acceleration")

    def __post_init__(self):
        for field in ("time", "position", "velocity", "acceleration"):
            values = np.asarray(getattr(self, field), dtype=float)
            if values.ndim != 1:
                raise ValueError(f"Replay.{field} must be one-dimensional, got shape {values.shape}")
            object.__setattr__(self, field, tuple(values.tolist()))
        super().__post_init__()

    def validate(self) -> None:
        _check_samples("Replay", np.array(self.time),
                       {f: np.array(getattr(self, f)) for f in ("position", "velocity", "acceleration")})

    @cached_property
    def _columns(self):
        return tuple(np.array(c) for c in (self.time, self.position, self.velocity, self.acceleration))

    def evaluate(self, t):
        time, *columns = self._columns
        return _result(_time(t), *(np.interp(t, time, c) for c in columns))

    def velocity_at(self, t: float) -> float:
        """u [m/s] at the time t [s] (float)."""
        return linear_at(self.time, self.velocity, t)

    @classmethod
    def from_csv(cls, path) -> "Replay":
        """Read a comma-separated file whose header names the columns ``time``,
        ``feed_position``, ``feed_velocity`` and ``feed_acceleration`` (others are ignored).

        Rows are numbered as lines of the file, the header being row 1; blank lines are
        skipped. Errors name the file, the row and the column.
        """
        columns, rows = read_csv_columns(path, cls.COLUMNS)
        check_csv_columns(path, columns, rows, "time")
        return cls(*columns.values())


_FACTORIES = {
    "biharmonic": BiHarmonic,
    "oscillating": Oscillating,
    "constant": Constant,
    "trapezoid": Trapezoid,
    "table": Table.from_csv,
    "replay": Replay.from_csv,
}


def make_profile(name: str, **params) -> FeedProfile:
    """Profile selected by name (case-insensitive), e.g. from an FMU string parameter.

    "biharmonic", "oscillating", "constant" and "trapezoid" take the fields of their
    class as keywords; "table" and "replay" take ``path`` and call ``Table.from_csv`` or
    ``Replay.from_csv``.
    """
    key = name.strip().lower()
    if key not in _FACTORIES:
        raise ValueError(f"unknown feed profile {name!r}; valid names: {', '.join(_FACTORIES)}")
    factory = _FACTORIES[key]
    allowed = list(inspect.signature(factory).parameters)
    unknown = [p for p in params if p not in allowed]
    if unknown:
        raise ValueError(f"unknown parameter {unknown[0]!r} for feed profile {key!r}; "
                         f"valid parameters: {', '.join(allowed)}")
    return factory(**params)


def from_parameters(profile, frequency, amplitude1, amplitude2, phase1, phase2, mean_velocity,
                    oscillation_amplitude, velocity, distance, v_max, a_max, t_start, table_file):
    """The profile that the FeedKinematics FMU's parameters select (names and units:
    fmus/README.md), or None for "input" (no profile: the velocity is an input).

    Raises ValueError naming the parameter that is wrong.
    """
    name = profile.strip().lower()
    if name == "input":
        return None
    if name in ("table", "replay"):
        if not table_file:
            raise ValueError(f"parameter table_file must name a CSV file when profile is '{name}'")
        try:
            return _FACTORIES[name](table_file)
        except OSError as exc:
            raise ValueError(f"parameter table_file: cannot read {table_file!r}: "
                             f"{exc.strerror or exc}") from exc
    params = {
        "biharmonic": dict(amplitude1=amplitude1, amplitude2=amplitude2, phase1=phase1,
                           phase2=phase2, frequency=frequency),
        "oscillating": dict(mean=mean_velocity, amplitude=oscillation_amplitude,
                            frequency=frequency),
        "constant": dict(velocity=velocity),
        "trapezoid": dict(distance=distance, v_max=v_max, a_max=a_max, t_start=t_start),
    }.get(name)
    if params is None:
        raise ValueError(f"parameter profile must be one of {PROFILES}, got {profile!r}")
    return _FACTORIES[name](**params)


class FeedModel(ContinuousModel):
    """A profile as a stateless continuous-time model: outputs x [m], u [m/s], a [m/s^2] at t."""

    def __init__(self, profile: FeedProfile):
        self.profile = profile

    def outputs(self, t, state, inputs, wanted=None):
        if wanted == ("u",):
            return {"u": self.profile.velocity_at(float(t))}
        x, u, a = self.profile.evaluate(float(t))
        return {"x": x, "u": u, "a": a}
