"""Plot of the ball-to-ball friction of a case against the side ratio (cf. Lin, Duan and
Okwudire 2019, Fig. 8): the contact force and the friction losses of both models, the case
marked. Drawn on matplotlib's Agg canvas without pyplot, like :mod:`.cosim.plots`.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

STYLES = {"analytical": ("C0", "--", "analytical (eqs. 22, 30, 32)"),
          "numerical": ("C1", "-", "numerical (eqs. 4-10)")}


def _values(values) -> np.ndarray:
    """The values with None (out of four-point contact) as NaN, which leaves a gap."""
    return np.array([np.nan if v is None else v for v in values], dtype=float)


def plot_side_ratio(sweep: dict, case: dict, side_ratio: float, path: str | Path) -> Path:
    """Two panels over the side ratio rho = N_x / N_y of ball 1 (``sweep``:
    ball_to_ball.side_ratio_sweep): the ball-to-ball contact force [N], and the ball-to-ball
    friction loss of both models with the numerical groove loss [mW]; the case (``case``:
    ball_to_ball.analyse, at ``side_ratio``) marked. Writes a PNG to ``path``, returns it."""
    rho = np.asarray(sweep["side_ratio"])
    fig = Figure(figsize=(7.0, 7.0))
    force, loss = fig.subplots(2, 1, sharex=True)
    for model, (colour, style, label) in STYLES.items():
        force.plot(rho, _values(sweep[model]["contact_force"]), style, color=colour, label=label)
        force.plot(side_ratio, case[model]["contact_force"], "o", color=colour, mfc="none")
        loss.plot(rho, 1e3 * _values(sweep[model]["friction_loss"]), style, color=colour,
                  label=f"ball-to-ball, {label}")
        loss.plot(side_ratio, 1e3 * case[model]["friction_loss"], "o", color=colour, mfc="none")
    loss.plot(rho, 1e3 * _values(sweep["numerical"]["groove_loss"]), ":", color="C1",
              label="grooves, numerical")
    loss.plot(side_ratio, 1e3 * case["numerical"]["groove_loss"], "o", color="C1", mfc="none")
    force.set_ylabel("ball-to-ball contact force F_B2B [N]")
    loss.set_ylabel("friction loss [mW]")
    loss.set_xlabel("side ratio rho = N_x / N_y of ball 1 (ball 2: -rho)")
    for ax in (force, loss):
        ax.axvline(side_ratio, color="0.6", lw=0.8)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    force.set_title("Two balls, the case's deviations and load held; circles: the case\n"
                    "(cf. Lin, Duan and Okwudire 2019, Fig. 8)", fontsize=9)
    fig.tight_layout()
    path = Path(path)
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=110)
    return path
