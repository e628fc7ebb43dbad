"""Plots of a :class:`~guideway_fmu.cosim.recording.Recording`: time histories, amplitude
spectra, film thickness and envelopes, one stacked axis per named column, written as PNG.

Generic: it plots whatever columns it is told. Figures are drawn on matplotlib's Agg canvas
directly, without pyplot: the caller's backend is left alone and no figure stays registered
(nothing to close), so plotting many recordings does not accumulate memory.
"""
from __future__ import annotations

import re
import textwrap
from pathlib import Path
from typing import Callable

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..numerics.spectrum import peak_indices, spectrum, uniform_grid
from .recording import Recording

_KINDS = ("time", "spectrum", "film", "envelope")
#: a signal oscillates, and its spectrum says something, when it crosses its straight-line
#: trend this often over the record and swings about it by more than round-off
MIN_CROSSINGS = 6
ROUND_OFF = 1e-9  # swing about the trend, relative to the signal's size, below which it is noise


def envelope(time, values, window: float) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper envelope of ``values``: running min and max over the centred time window
    ``[t - window/2, t + window/2]`` (``window`` [s]; works on any increasing time grid).
    Returns ``(lower, upper)`` in the unit of ``values``. Pick ``window`` of about one period of
    the carrier oscillation: shorter windows follow the carrier, longer ones smear the envelope.
    Within ``window / 2`` of either end the window is cut short, and the envelope less reliable.
    """
    time, values = np.asarray(time, float), np.asarray(values, float)
    if not window > 0:
        raise ValueError(f"window must be > 0 s, got {window}")
    start = np.searchsorted(time, time - window / 2, side="left")
    stop = np.searchsorted(time, time + window / 2, side="right")
    # reduceat over the interleaved bounds reduces values[start:stop] at even positions; the
    # padding sample keeps the index stop == len(values) valid and is never inside a window
    bounds = np.column_stack([start, stop]).ravel()
    padded = np.append(values, values[-1])
    return np.minimum.reduceat(padded, bounds)[::2], np.maximum.reduceat(padded, bounds)[::2]


def _check_names(rec: Recording, names) -> None:
    if not names:
        raise ValueError("no signals named to plot")
    for name in names:
        if name not in rec.columns:
            raise ValueError(f"{name!r} is not in the recording; available: {', '.join(rec.columns)}")


def _unit(rec: Recording, name: str) -> str:
    return rec.units.get(name) or "-"


def axis_label(rec: Recording, name: str, unit: str | None = None, what: str = "{}") -> str:
    """The axis label of the column ``name``: the quantity, its FMU's description of the
    variable (else ``name``) put into ``what``, and ``unit`` (default the column's), e.g. "load
    of one roller in an upper groove [N]"; wrapped to fit beside a stacked axis."""
    quantity = what.format(rec.descriptions.get(name) or name)
    return textwrap.fill(f"{quantity} [{unit or _unit(rec, name)}]", 34)


def _stacked(rec: Recording, names, path, title: str, xlabel: str,
             draw: Callable[[Axes, str], str]) -> Path:
    """Write one figure with an axis per name, stacked over a shared x axis, to ``path``.
    ``draw(ax, name)`` plots the signal ``name`` on ``ax`` and returns its y label."""
    _check_names(rec, names)
    fig = Figure(figsize=(8, 1.0 + 2.0 * len(names)), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(names), 1, sharex=True, squeeze=False)[:, 0]
    for ax, name in zip(axes, names):
        ax.set_ylabel(draw(ax, name), fontsize=8)
        ax.set_title(name, fontsize=9, loc="right")  # the left corner holds the offset (1e-8)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(xlabel)
    fig.suptitle(title)
    path = Path(path)
    fig.savefig(path, dpi=110)
    return path


def plot_time(rec: Recording, names, path) -> Path:
    """Time histories of the columns ``names`` [their units] over time [s], written to ``path``."""
    def draw(ax, name):
        ax.plot(rec.time, rec.columns[name], lw=0.8)
        return axis_label(rec, name)
    return _stacked(rec, names, path, "Time histories", "time [s]", draw)


def plot_spectra(rec: Recording, names, path, skip: float = 0.0, f_max: float | None = None,
                 n_peaks: int = 5) -> Path:
    """Amplitude spectra (see :func:`spectrum`) of the columns ``names`` after the first ``skip``
    seconds: log amplitude [unit of the column] over linear frequency [kHz] up to ``f_max`` [Hz]
    (default: Nyquist), with the ``n_peaks`` highest local maxima marked and their frequencies
    [Hz] listed, highest first.
    A non-uniform recording (adaptive step) is first resampled with ``numpy.interp`` on a uniform
    grid at its median time step.
    """
    time = uniform_grid(rec.time)

    def draw(ax, name):
        freq, amplitude = spectrum(time, np.interp(time, rec.time, rec.columns[name]), skip)
        if f_max is not None:
            freq, amplitude = freq[freq <= f_max], amplitude[freq <= f_max]
        ax.semilogy(freq / 1e3, amplitude, lw=0.8)
        top = peak_indices(amplitude, n_peaks)
        ax.plot(freq[top] / 1e3, amplitude[top], "v", color="C3", ms=5)
        # listed in a corner rather than beside each marker: close peaks (sidebands) stay legible
        ax.text(0.99, 0.95, "peaks: " + ", ".join(f"{freq[i]:.4g}" for i in top) + " Hz",
                transform=ax.transAxes, ha="right", va="top", fontsize=8,
                bbox=dict(facecolor="white", edgecolor="0.8", alpha=0.8))
        if amplitude.max() > 0:
            ax.set_ylim(amplitude.max() * 1e-6, amplitude.max() * 30)
        return axis_label(rec, name, what="amplitude of {}")
    return _stacked(rec, names, path, f"Amplitude spectra (Hann window, first {skip:g} s skipped)",
                    "frequency [kHz]", draw)


def plot_film(rec: Recording, names, path) -> Path:
    """Film thickness: the columns ``names`` (unit "m") plotted in micrometres over time [s]."""
    for name in names:
        if rec.units.get(name, "m") not in ("m", ""):
            raise ValueError(f"film thickness {name!r} must be in m, its unit is {rec.units[name]!r}")

    def draw(ax, name):
        ax.plot(rec.time, rec.columns[name] * 1e6, lw=0.8)
        return axis_label(rec, name, "µm")
    return _stacked(rec, names, path, "Film thickness", "time [s]", draw)


def plot_envelope(rec: Recording, names, path, window: float) -> Path:
    """Signals ``names`` (faint) with their upper and lower envelopes (see :func:`envelope`,
    running max/min over ``window`` seconds) over time [s]."""
    def draw(ax, name):
        lower, upper = envelope(rec.time, rec.columns[name], window)
        ax.plot(rec.time, rec.columns[name], lw=0.5, color="0.7")
        ax.plot(rec.time, upper, lw=1.0, color="C3", label="upper")
        ax.plot(rec.time, lower, lw=1.0, color="C0", label="lower")
        ax.legend(fontsize=7, loc="upper right")
        return axis_label(rec, name)
    return _stacked(rec, names, path, f"Envelope (running max/min over {window:g} s)", "time [s]", draw)


def plot_all(rec: Recording, plots: dict, out_dir, *, skip: float = 0.0, f_max: float | None = None,
             window: float | None = None) -> list[Path]:
    """Write ``<kind>.png`` into ``out_dir`` for each ``kind: names`` in ``plots``, kinds being
    "time", "spectrum" (uses ``skip`` [s] and ``f_max`` [Hz]), "film" and "envelope" (needs
    ``window`` [s]). Every name is checked before any file is written. Returns the paths."""
    unknown = set(plots) - set(_KINDS)
    if unknown:
        raise ValueError(f"unknown plot kinds {sorted(unknown)}; known: {', '.join(_KINDS)}")
    if "envelope" in plots and window is None:
        raise ValueError("an envelope plot needs window [s]")
    for names in plots.values():
        _check_names(rec, names)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    writers = {
        "time": lambda names, path: plot_time(rec, names, path),
        "spectrum": lambda names, path: plot_spectra(rec, names, path, skip, f_max),
        "film": lambda names, path: plot_film(rec, names, path),
        "envelope": lambda names, path: plot_envelope(rec, names, path, window),
    }
    return [writers[kind](names, out_dir / f"{kind}.png") for kind, names in plots.items()]


def oscillates(time, values) -> bool:
    """Whether ``values`` [any unit] over ``time`` [s] swing about their straight-line trend
    (MIN_CROSSINGS crossings or more, by more than ROUND_OFF of their size): the signals whose
    spectrum means something, unlike a constant, a ramp or a step."""
    time, values = np.asarray(time, float), np.asarray(values, float)
    if time.size < MIN_CROSSINGS + 2 or not np.all(np.isfinite(values)):
        return False
    residual = values - np.polyval(np.polyfit(time - time[0], values, 1), time - time[0])
    size = max(np.max(np.abs(values)), np.finfo(float).tiny)
    if np.ptp(residual) <= ROUND_OFF * size:
        return False
    return np.count_nonzero(np.diff(np.signbit(residual))) >= MIN_CROSSINGS


def plot_defaults(rec: Recording, out_dir, *, skip: float = 0.0,
                  f_max: float | None = None) -> list[Path]:
    """The plots of a run whose scenario names none, per instance ``I`` (its name with any
    character outside letters, digits and ``_.-`` as ``_``): ``time_I.png``, the time history
    of every column of it, and ``spectrum_I.png``, the spectra (``skip`` [s], ``f_max`` [Hz]) of
    those that :func:`oscillates` says swing. Axis labels from the FMUs' descriptions and
    units. Returns the paths."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    instances: dict[str, list[str]] = {}
    for name in rec.columns:
        instances.setdefault(name.split(".", 1)[0], []).append(name)
    kept = rec.time - rec.time[0] >= skip
    paths = []
    for instance, names in instances.items():
        stem = re.sub(r"[^A-Za-z0-9_.-]", "_", instance)
        paths.append(plot_time(rec, names, out_dir / f"time_{stem}.png"))
        swinging = [n for n in names if oscillates(rec.time[kept], rec.columns[n][kept])]
        if swinging:
            paths.append(plot_spectra(rec, swinging, out_dir / f"spectrum_{stem}.png", skip,
                                      f_max))
    return paths
