"""Plots of a feed-unit sweep: the linear errors, the angular errors and the unit's stiffness
against the swept quantity, with the contact-angle change (solid) and at a constant angle
(dashed), as Zhang, Wang and Le (2019) draw them (Figs. 10-16, 19, 20). Drawn on matplotlib's
Agg canvas without pyplot, like :mod:`.cosim.plots`.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

#: x axis and the paper's figures of each sweep
AXES = {"load": ("force on the table |F| [kN]", "Figs. 10, 11, 13, 14, 19, 20"),
        "point_x": ("load point x from the table centre [mm]", "Figs. 15, 16"),
        "point_y": ("load point y from the table centre [mm]", "Figs. 15, 16"),
        "contact_angle": ("initial contact angle [deg]", "Fig. 12")}
MIN_SPAN = 1e-6  # smallest y span drawn as data [um, urad]: below it, round-off
STYLES = {"angle_change": ("-", "contact angle changes"),
          "constant_angle": ("--", "constant contact angle")}


def _abscissa(result: dict) -> np.ndarray:
    quantity = result["sweep"]
    if quantity == "load":
        return np.asarray(result["force_magnitude"]) / 1e3
    values = np.asarray(result["values"])
    return values * 1e3 if quantity.startswith("point") else values


def plot_sweep(result: dict, path: str | Path) -> Path:
    """Three panels of :func:`..feed_unit.sweep`'s result: delta_y, delta_z [um]; epsilon_x,
    epsilon_y, epsilon_z [urad]; lateral and vertical stiffness of the unit [N/um]. Writes a PNG
    to ``path`` and returns it."""
    x = _abscissa(result)
    label, figures = AXES[result["sweep"]]
    fig = Figure(figsize=(7.0, 9.0))
    panels = fig.subplots(3, 1, sharex=True)
    groups = ((("delta_y", "lateral error delta_y"), ("delta_z", "vertical error delta_z")),
              (("epsilon_x", "roll error epsilon_x"), ("epsilon_y", "pitch error epsilon_y"),
               ("epsilon_z", "yaw error epsilon_z")),
              (("stiffness_lateral", "lateral stiffness"), ("stiffness_vertical",
                                                            "vertical stiffness")))
    ylabels = ("displacement of the table centre [um]", "rotation of the table [urad]",
               "stiffness of the unit [N/um]")
    for ax, group, ylabel in zip(panels, groups, ylabels):
        for colour, (key, name) in zip(("C0", "C1", "C2"), group):
            for model, (style, model_name) in STYLES.items():
                ax.plot(x, np.asarray(result[model][key]) * 1e6 if "stiffness" not in key
                        else np.asarray(result[model][key]) / 1e6,
                        style, color=colour, label=f"{name}, {model_name}")
        low, high = ax.get_ylim()
        if high - low < MIN_SPAN:  # round-off only: do not magnify it
            ax.set_ylim(-1.0, 1.0)
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    panels[-1].set_xlabel(label)
    panels[0].set_title(f"Four-slider ball-guide feed unit (cf. Zhang, Wang and Le 2019, {figures})",
                        fontsize=9)
    fig.tight_layout()
    path = Path(path)
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=110)
    return path
