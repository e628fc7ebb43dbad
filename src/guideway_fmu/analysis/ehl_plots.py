"""Plots of the numerical EHL solutions: pressure and film against x/b (Soleimanian et al. 2020, Figs. 9-10,
33, 35) and a contact-load history with the analysed instants marked (Figs. 32, 34).

Drawn on matplotlib's Agg canvas without pyplot, like :mod:`.cosim.plots`: the caller's backend
is left alone and no figure stays registered.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..physics.roller_guide.ehl import EHLResult

X_RANGE = (-3.0, 2.0)  # shown part of the domain [Hertz half-widths]
FILM_SPAN = 2.5  # film axis up to this multiple of the largest film in |x| <= b


def _save(fig: Figure, path: str | Path) -> Path:
    path = Path(path)
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=110)
    return path


def plot_distribution(result: EHLResult, path: str | Path, *, analytical_film: float | None = None,
                      title: str = "") -> Path:
    """Pressure [GPa] (total solid, asperity dotted when rough) on the left axis and film [um]
    (dashed) on the right axis, cut at FILM_SPAN times the film in the contact, against x/b;
    ``analytical_film`` [m], if given, is drawn as a
    circle at x = 0 (paper Figs. 33, 35). Writes a PNG to ``path`` and returns it."""
    X = result.X
    shown = (X >= X_RANGE[0]) & (X <= X_RANGE[1])
    fig = Figure(figsize=(6.4, 4.6))
    ax = fig.add_subplot()
    ax.plot(X[shown], result.p[shown] * 1e-9, "k-", label="pressure p")
    if np.any(result.p_a > 0.0):
        ax.plot(X[shown], result.p_a[shown] * 1e-9, "k:", label="asperity pressure p_a")
    ax.set_xlabel("x / b [-]")
    ax.set_ylabel("pressure [GPa]")
    ax.set_ylim(bottom=0.0)
    film = ax.twinx()
    film.plot(X[shown], result.h[shown] * 1e6, "b--", label="film h (numerical)")
    if analytical_film is not None:
        film.plot([0.0], [analytical_film * 1e6], "o", mfc="none", mec="r", ms=8,
                  label="film of the dynamics (analytical)")
    film.set_ylabel("film thickness [um]", color="b")
    inside = result.h[np.abs(X) <= 1.0]
    scale = max(inside.max() if inside.size else result.h.min(), analytical_film or 0.0)
    film.set_ylim(0.0, FILM_SPAN * scale * 1e6)
    lines = ax.get_legend_handles_labels()
    more = film.get_legend_handles_labels()
    ax.legend(lines[0] + more[0], lines[1] + more[1], loc="upper center", fontsize=8, ncol=2,
              bbox_to_anchor=(0.5, -0.15))
    ax.set_title(title or f"w' = {result.contact.load:.4g} N/m, u_m = "
                 f"{result.contact.entrainment_velocity:.3g} m/s", fontsize=9)
    fig.tight_layout()
    return _save(fig, path)


def plot_load_history(time, load, marks: list[tuple[str, float, float]], path: str | Path, *,
                      ylabel: str = "roller load [N]") -> Path:
    """Load [N] against time [ms]: (a) the whole record, (b) a zoom on the span of ``marks``
    ((label, time [s], load [N]) each, drawn as labelled dots). Writes a PNG, returns it."""
    time, load = np.asarray(time), np.asarray(load)
    fig = Figure(figsize=(7.0, 6.0))
    whole, zoom = fig.subplots(2, 1)
    ts = np.array([m[1] for m in marks])
    span = max(ts.max() - ts.min(), 10.0 * np.median(np.diff(time))) if ts.size else 0.0
    lo, hi = (ts.min() - 0.5 * span, ts.max() + 0.5 * span) if ts.size else (time[0], time[-1])
    near = (time >= lo) & (time <= hi)
    for ax, keep in ((whole, slice(None)), (zoom, near)):
        ax.plot(time[keep] * 1e3, load[keep], "k-", lw=0.8)
        for label, t, value in marks:
            ax.plot(t * 1e3, value, "ro", ms=4)
            ax.annotate(label, (t * 1e3, value), textcoords="offset points", xytext=(0, 6),
                        ha="center", fontsize=8, color="r")
        ax.set_xlabel("time [ms]")
        ax.set_ylabel(ylabel)
    whole.set_title("(a) record", fontsize=9)
    if ts.size:
        whole.axvspan(lo * 1e3, hi * 1e3, color="0.9")
    zoom.set_title("(b) zoomed view", fontsize=9)
    fig.tight_layout()
    return _save(fig, path)
