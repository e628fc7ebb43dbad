"""What diagnose writes: diagnosis.json and fit.csv (spec: measured-run.md), PNG plots and a
self-contained report.html (plots inlined as base64)."""
from __future__ import annotations

import base64
import html
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def plain(value) -> str:
    """A number as a plain decimal (no exponent, shortest round trip)."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return np.format_float_positional(float(value), unique=True, trim="-")


def to_json(value, indent: int = 0) -> str:
    """JSON text with every number written by :func:`plain` (json.dumps would use exponents)."""
    pad, inner = "  " * indent, "  " * (indent + 1)
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = [f"{inner}{json.dumps(str(k))}: {to_json(v, indent + 1)}" for k, v in value.items()]
        return "{\n" + ",\n".join(items) + f"\n{pad}}}"
    if isinstance(value, (list, tuple)):
        if not value:
            return "[]"
        return "[\n" + ",\n".join(inner + to_json(v, indent + 1) for v in value) + f"\n{pad}]"
    if value is None or isinstance(value, str):
        return json.dumps(value)
    return plain(value)


def write_diagnosis(path: Path, diagnosis: dict) -> Path:
    path.write_text(to_json(diagnosis) + "\n")
    return path


def write_fit(path: Path, time, measured, baseline, augmented) -> Path:
    """fit.csv: time, measured, baseline, augmented on the held-out samples."""
    rows = ["time,measured,baseline,augmented"]
    rows += [",".join(plain(v) for v in row) for row in zip(time, measured, baseline, augmented)]
    path.write_text("\n".join(rows) + "\n")
    return path


def _save(fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_comparison(path, time, measured, baseline, augmented, held, channel, effect) -> Path:
    """Measured vs baseline vs augmented over the record and in a zoom on one held-out block."""
    fig, axes = plt.subplots(2, 1, figsize=(10, 6.5))
    block = np.flatnonzero(held)
    for ax, sel in ((axes[0], slice(None)), (axes[1], block[: max(len(block) // 10, 20)])):
        ax.plot(time[sel], measured[sel], ".", ms=1.5, color="0.4", label="measured")
        ax.plot(time[sel], baseline[sel], lw=1, label="baseline (co-simulation)")
        if effect not in ("none", "unknown"):
            ax.plot(time[sel], augmented[sel], lw=1, label=f"+ {effect} (co-simulation)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel(f"{channel} [N]")
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
    ax.set_xlabel(f"{name} [{unit}]")
    ax.set_ylabel("residual [N]")
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


def _table(rows, header) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>"
                   for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def write_html(path: Path, diagnosis: dict, notes: dict, images: list[Path]) -> Path:
    """report.html: the verdict, the numbers, how they were obtained and the plots, inline."""
    d = diagnosis
    verdict = [("missing effect", d["missing_effect"]), ("confidence", plain(round(d["confidence"], 4))),
               ("compared channel", d["channel"]), ("gap before (baseline)", plain(round(d["gap_before"], 6))),
               ("gap after", plain(round(d["gap_after"], 6))), ("noise floor", plain(round(d["noise_floor"], 6))),
               ("proposed equation for the residual", d["equation"] or "-")]
    candidates = [(c["effect"], plain(round(c["score"], 2)), plain(round(c["gap_after"], 6)),
                   ", ".join(f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}"
                             for k, v in c["parameters"].items()))
                  for c in d["candidates"]]
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>diagnosis</title>",
             "<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto}"
             "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;"
             "padding:3px 8px;text-align:left;vertical-align:top}img{max-width:100%}</style>"
             "</head><body>",
             f"<h1>Diagnosis of {html.escape(notes['run'])}</h1>",
             _table(verdict, ["", ""]),
             "<h2>Candidates (scored on held-out samples, cross-validated over 3 folds; "
             "parameters and held-out gap of fold 1)</h2>",
             _table(candidates, ["effect", "score", "held-out gap", "parameters"])]
    for title, entries in notes["sections"].items():
        parts.append(f"<h2>{html.escape(title)}</h2>")
        parts.append(_table(list(entries.items()), ["", ""]))
    for image in images:
        data = base64.b64encode(image.read_bytes()).decode("ascii")
        parts.append(f"<h3>{html.escape(image.stem.replace('_', ' '))}</h3>"
                     f"<img alt='{html.escape(image.stem)}' src='data:image/png;base64,{data}'>")
    parts.append("</body></html>")
    path.write_text("\n".join(parts), encoding="utf-8")
    return path
