"""Whether a measured run's numbers can be in the format's SI units (docs/measured-run.md).

A column in other units (time in ms, a position in mm) passes every check of the format and
yields a confident, wrong diagnosis: a time axis 1000 times too long makes the derived
acceleration 1000 times too small, and the fit calls the inertia a missing mass. The rig file
declares no sampling rate, so the checks rest on what the columns say about each other and on
the physical scale of a linear guideway. :func:`check` refuses (ValueError naming the file, the
column, what is implausible and the likely unit) where the data cannot be right and returns a
warning where they are only unusual.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import cumulative_trapezoid

#: a derivative's channel and the channel it is the derivative of, in the time's units
DERIVATIVES = (("feed_position", "feed_velocity"), ("feed_velocity", "feed_acceleration"))
AGREE = (0.5, 2.0)  # gain of a channel's increments over its derivative's integral: refused outside
ROUGHLY = (0.8, 1.25)  # ... and warned about outside
STRETCHES = 200  # equal stretches of the record the increments are taken over
MAX_SPEED, FAST = 20.0, 5.0  # m/s: refused, warned above (fast linear guides are rated ~10 m/s)
MAX_TRAVEL, LONG = 10.0, 4.0  # m: refused, warned above (a rail is at most a few metres long)
MAX_FRICTION, HIGH_FRICTION = 1.0, 0.3  # friction over normal load: refused, warned above
#: vertical displacement range over the element radius refused above: the contacts deflect by
#: micrometres; a tenth of the radius would crush the rolling elements
MAX_DEFLECTION = 0.1
SLOW_SAMPLING = 0.1  # s: a sampling interval above it is warned about
TOP = 0.99  # quantile of a channel's magnitude taken as its top: robust to a few spikes


def _thousands(factor: float) -> int:
    """k where ``factor`` lies within a factor of 2 of 1000^k, else 0."""
    k = int(round(np.log10(factor) / 3.0))
    return k if abs(np.log10(factor) - 3.0 * k) < np.log10(2.0) else 0


def derivative_gain(time, y, dy) -> float | None:
    """Least-squares gain [-] of the increments of ``y`` over STRETCHES equal stretches of the
    record against the time integral (trapezoid) of ``dy`` over the same stretches: 1 where
    ``dy`` is the time derivative of ``y`` in the same units; the noise of ``y`` enters at the
    stretches' ends only, that of ``dy`` is averaged. None where ``dy`` integrates to nothing."""
    edges = np.unique(np.linspace(0, time.size - 1, STRETCHES + 1).astype(int))
    integral = np.diff(cumulative_trapezoid(dy, time, initial=0.0)[edges])
    power = float(integral @ integral)
    return float(np.diff(y[edges]) @ integral) / power if power > 0.0 else None


def _derivatives(run, source) -> list[str]:
    notes = []
    for name, rate in DERIVATIVES:
        if name not in run.columns or rate not in run.columns:
            continue
        gain = derivative_gain(run.time, run.columns[name], run.columns[rate])
        if gain is None or ROUGHLY[0] <= gain <= ROUGHLY[1]:
            continue
        said = (f"{source}: columns '{name}' and '{rate}' disagree: over the record '{name}' "
                f"changes by {gain:.3g} times the time integral of '{rate}' (1 in SI units)")
        if not AGREE[0] <= gain <= AGREE[1]:
            k = _thousands(gain) if gain > 0.0 else 0
            cause = ("their signs are opposite" if gain < 0.0 else
                     {-1: f"looks like 'time' in milliseconds, or '{rate}' in millimetres",
                      1: f"looks like '{name}' in millimetres"}.get(k)
                     or "one of them is not in the SI units of docs/measured-run.md")
            raise ValueError(f"{said}: {cause}")
        notes.append(f"{said}; the rig may filter one of them")
    return notes


def _feed_scale(run, source) -> list[str]:
    notes = []
    if "feed_velocity" in run.columns:
        speed = float(np.quantile(np.abs(run.columns["feed_velocity"]), TOP))
        said = f"{source}: column 'feed_velocity' reaches {speed:.3g} m/s"
        if speed > MAX_SPEED:
            raise ValueError(f"{said}, faster than any linear guide runs ({MAX_SPEED:g} m/s): "
                             f"looks like mm/s")
        if speed > FAST:
            notes.append(f"{said}, faster than most linear guides are rated")
    if "feed_position" in run.columns:
        travel = float(np.ptp(run.columns["feed_position"]))
        said = f"{source}: column 'feed_position' spans {travel:.3g} m"
        cause = "looks like millimetres"
    elif "feed_velocity" in run.columns:
        travel = float(np.ptp(cumulative_trapezoid(run.columns["feed_velocity"], run.time)))
        said = (f"{source}: columns 'time' and 'feed_velocity': the feed travels {travel:.3g} m "
                f"by the time integral of the velocity")
        cause = "looks like 'time' in milliseconds (or 'feed_velocity' in mm/s)"
    else:
        return notes
    if travel > MAX_TRAVEL:
        raise ValueError(f"{said}, longer than any linear guideway ({MAX_TRAVEL:g} m): {cause}")
    if travel > LONG:
        notes.append(f"{said}, longer than most linear guideways")
    return notes


def _force_scale(run, source) -> list[str]:
    """friction_force against the normal load the rig file gives; a drive_force also carries
    m a, which the file does not bound, so it is not checked."""
    if "friction_force" not in run.columns:
        return []
    force = float(np.quantile(np.abs(run.columns["friction_force"]), TOP))
    load = run.normal_load()
    if load <= 0.0:
        return [f"{source}: the normal load adds up to {load:.3g} N (rig.toml: preload, "
                f"moving_mass x g, normal force): friction is not checked against it, and the "
                f"friction coefficients reported are per newton of a nominal 1 N load"]
    ratio = force / load
    said = (f"{source}: column 'friction_force' reaches {force:.3g} N, {ratio:.3g} times the "
            f"normal load of {load:.3g} N (rig.toml: preload, moving_mass x g, normal force)")
    if ratio > MAX_FRICTION:
        raise ValueError(f"{said}; a rolling guide's friction is a small share of its load: "
                         f"looks like mN, or a force other than friction")
    return [f"{said}; high for a rolling guide"] if ratio > HIGH_FRICTION else []


def _deflection(run, source) -> list[str]:
    radius = run.sections.get("guideway", {}).get("element_radius")
    if "vertical_displacement" not in run.columns or radius is None:
        return []
    span = float(np.ptp(run.columns["vertical_displacement"]))
    if span > MAX_DEFLECTION * radius:
        raise ValueError(f"{source}: column 'vertical_displacement' spans {span:.3g} m, "
                         f"{span / radius:.3g} times [guideway] element_radius = {radius:g} m "
                         f"of rig.toml; the contacts deflect by micrometres: looks like mm or um")
    return []


def check(run) -> list[str]:
    """Warnings on the units of the checked run ``run`` (run_io.MeasuredRun); ValueError where
    a column cannot be in SI units (module docstring)."""
    source = run.path / "data.csv"
    notes = (_derivatives(run, source) + _feed_scale(run, source) + _force_scale(run, source)
             + _deflection(run, source))
    step = float(np.median(np.diff(run.time)))
    if step > SLOW_SAMPLING:
        notes.append(f"{source}: column 'time': samples {step:.3g} s apart, slow for a friction "
                     f"or vibration record: is 'time' in milliseconds?")
    return notes
