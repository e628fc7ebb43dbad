"""Plot of a carriage's mode shapes (cf. Wu et al. 2012, Fig. 3): for each mode, how much each
ball is compressed along the carriage, the two rows side by side, with the frequency and the
coordinates that hold the mode's kinetic energy. Drawn on matplotlib's Agg canvas without
pyplot, like :mod:`.cosim.plots`.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

ROWS = {"row_1": ("C0", "o", "row 1"), "row_2": ("C3", "s", "row 2")}
SHOWN_SHARE = 0.05  # coordinates named in a mode's title: at least this share of its energy


def plot_modes(result: dict, path: str | Path) -> Path:
    """One panel per mode of ``result`` (carriage_modes.analyse): each ball's approach in the
    mode shape over the largest against its position along the carriage [mm], rows 1 and 2
    (sign common to the mode, scale arbitrary). Writes a PNG to ``path`` and returns it."""
    x = 1e3 * np.asarray(result["ball_positions"])
    modes = result["modes"]
    fig = Figure(figsize=(7.0, 1.0 + 1.7 * len(modes)))
    panels = fig.subplots(len(modes), 1, sharex=True, squeeze=False)[:, 0]
    for number, (ax, mode) in enumerate(zip(panels, modes), 1):
        for row, (colour, marker, label) in ROWS.items():
            ax.plot(x, mode["ball_approach"][row], marker + "-", color=colour, ms=4, lw=0.8,
                    label=label)
        ax.axhline(0.0, color="0.5", lw=0.6)
        ax.set_ylim(-1.2, 1.2)
        ax.set_ylabel("ball approach [-]", fontsize=8)
        ax.grid(True, alpha=0.3)
        energy = ", ".join(f"{k} {v:.2f}" for k, v in mode["participation"].items()
                           if v >= SHOWN_SHARE)
        ax.set_title(f"mode {number}: {mode['frequency_hz']:.1f} Hz, {mode['label']}"
                     + (" (stretches no ball)" if mode["label"] == "rigid" else
                        f"; kinetic energy in {energy}"), fontsize=9)
    panels[0].legend(fontsize=8, loc="upper right")
    panels[-1].set_xlabel("ball position along the carriage l [mm]")
    fig.tight_layout()
    path = Path(path)
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=110)
    return path
