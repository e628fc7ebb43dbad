"""The plots of the diagnosis report (PNG): measured vs models, the residual against the signal
that gave the effect away, and the candidates' ranking."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def _save(fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_comparison(path, time, measured, baseline, augmented, held, channel, effect,
                    unit: str = "N") -> Path:
    """Measured vs baseline vs augmented over the record and in a zoom on one held-out block."""
    fig, axes = plt.subplots(2, 1, figsize=(10, 6.5))
    block = np.flatnonzero(held)
    for ax, sel in ((axes[0], slice(None)), (axes[1], block[: max(len(block) // 10, 20)])):
        ax.plot(time[sel], measured[sel], ".", ms=1.5, color="0.4", label="measured")
        ax.plot(time[sel], baseline[sel], lw=1, label="baseline (co-simulation)")
        if effect not in ("none", "unknown"):
            ax.plot(time[sel], augmented[sel], lw=1, label=f"+ {effect} (co-simulation)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel(f"{channel.replace('_', ' ')} [{unit}]")
    axes[0].set_title("whole record")
    axes[1].set_title("zoom on held-out samples")
    axes[0].legend(loc="upper right", fontsize=8)
    return _save(fig, path)


def plot_residual(path, signal, name, unit, before, after, mask, effect) -> Path:
    """Residual (measured - model) against the signal that gave the effect away, with bin means."""
    fig, ax = plt.subplots(figsize=(10, 4.5))
    s = signal[mask]
    ax.plot(s, before[mask], ".", ms=1.5, alpha=0.4, label="baseline residual")
    if effect not in ("none", "unknown"):
        ax.plot(s, after[mask], ".", ms=1.5, alpha=0.4, label="augmented residual")
    edges = np.quantile(s, np.linspace(0, 1, 41))
    centre = 0.5 * (edges[1:] + edges[:-1])
    index = np.clip(np.searchsorted(edges, s, side="right") - 1, 0, 39)
    counts = np.maximum(np.bincount(index, minlength=40), 1)
    ax.plot(centre, np.bincount(index, before[mask], 40) / counts, "k-", lw=1.5,
            label="baseline residual, bin means")
    ax.set_xlabel(f"{name.replace('_', ' ')} [{unit}]")
    ax.set_ylabel("residual, measured - model [N]")
    ax.legend(fontsize=8)
    ax.set_title(f"residual against {name} (held-out samples)")
    return _save(fig, path)


def plot_ranking(path, candidates, gap_before, noise) -> Path:
    """Cross-validated held-out score (BIC improvement over the baseline) and gap of every
    candidate."""
    names = [c["effect"] for c in candidates]
    fig, axes = plt.subplots(1, 2, figsize=(10, 0.5 * len(names) + 2))
    axes[0].barh(names, [c["score"] for c in candidates])
    axes[0].set_xlabel("score: cross-validated held-out BIC, baseline - candidate")
    axes[0].invert_yaxis()
    axes[1].barh(names, [c["gap_after"] for c in candidates])
    axes[1].axvline(gap_before, color="k", ls="--", label="baseline gap")
    axes[1].axvline(noise, color="r", ls=":", label="noise floor")
    axes[1].set_xlabel("held-out gap (range-normalised RMS)")
    axes[1].invert_yaxis()
    axes[1].legend(fontsize=8)
    return _save(fig, path)


def plot_spectra(path, spectra: dict, channel, unit, marks: dict) -> Path:
    """Amplitude spectra of the measured, baseline and augmented responses (``spectra``: label
    -> (f [Hz], amplitude)) on a log scale, with vertical lines at ``marks`` (label -> f [Hz]):
    a film shows at the feed frequency and its harmonics, a preload or a mass in the natural
    frequency."""
    fig, axes = plt.subplots(2, 1, figsize=(10, 7))
    f_high = 2.5 * max([f for f in marks.values() if f] or [1e3])
    f_feed = min([f for f in marks.values() if f] or [10.0])
    for ax, top in ((axes[0], f_high), (axes[1], 12 * f_feed)):
        for (label, (f, amplitude)), style in zip(spectra.items(), ("-", "--", ":")):
            keep = (f > 0) & (f <= top)
            ax.semilogy(f[keep], amplitude[keep], style, lw=1, label=label)
        for label, f in marks.items():
            if f and f <= top:
                ax.axvline(f, color="0.6", lw=0.8)
                ax.text(f, ax.get_ylim()[1], f" {label}", fontsize=7, va="top", rotation=90)
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel(f"amplitude of {channel.replace('_', ' ')} [{unit}]")
    axes[0].set_title("whole band")
    axes[1].set_title("feed frequency and its harmonics")
    axes[0].legend(fontsize=8)
    return _save(fig, path)
