"""Plots of a sweep: each reduced output against each swept parameter, one PNG per output with
an axis per parameter. Where the other parameters take few combinations (a factorial design), a
line joins the points of each combination; otherwise the points are scattered. Failed points
are left out. Drawn on matplotlib's Agg canvas without pyplot, as cosim/plots.py."""
from __future__ import annotations

import json
import re
import textwrap
from pathlib import Path

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from .reduce import QUANTITY

MAX_LINES = 8  # more combinations of the other parameters than this: scattered points


def plot_outputs(results_json: Path, out: Path) -> list[Path]:
    """Write ``<column>.png`` into ``out`` for every reduced output of ``results_json``
    (written by table.ResultsTable.write_json); returns the paths."""
    data = json.loads(Path(results_json).read_text())
    points = [p for p in data["points"] if p["status"] == "ok"]
    names, about = data["parameters"], data["descriptions"]
    paths = []
    for output in data["outputs"]:
        column = output["column"]
        fig = Figure(figsize=(5 * len(names), 3.8), layout="constrained")
        FigureCanvasAgg(fig)
        for ax, name in zip(fig.subplots(1, len(names), squeeze=False)[0], names):
            others = [n for n in names if n != name]
            groups: dict[tuple, list] = {}
            for p in points:
                key = tuple(p["parameters"][n] for n in others)
                groups.setdefault(key, []).append((p["parameters"][name], p["outputs"][column]))
            lines = len(groups) <= MAX_LINES and all(len(g) > 1 for g in groups.values())
            for key, xy in sorted(groups.items()):
                xy.sort(key=lambda pair: pair[0])
                label = ", ".join(f"{n} = {v:g}" if isinstance(v, (int, float)) else f"{n} = {v}"
                                  for n, v in zip(others, key))
                ax.plot(*zip(*xy), "o-" if lines else "o", ms=4,
                        color=None if lines else "C0", label=label if lines and label else None)
            if lines and others:
                ax.legend(fontsize=7)
            quantity = f"{QUANTITY[output['reduce']]} {about[output['variable']] or output['variable']}"
            ax.set(xlabel=f"{about[name] or name} [{data['parameter_units'][name] or '-'}]",
                   ylabel=textwrap.fill(f"{quantity} [{output['unit'] or '-'}]", 40))
            ax.grid(alpha=0.3)
        settle = f", first {output['settle_s']:g} s left out" if output["settle_s"] else ""
        fig.suptitle(f"{data['scenario']}: {column}{settle}", fontsize=10)
        path = Path(out) / f"{re.sub(r'[^A-Za-z0-9_.-]+', '_', column).strip('_')}.png"
        fig.savefig(path, dpi=110)
        paths.append(path)
    return paths
