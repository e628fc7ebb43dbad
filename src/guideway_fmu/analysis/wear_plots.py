"""Analogues of the wear figures of Zhang, Wang and Jiang (Figs. 14-17): the slider's
displacement against the load after a running distance, and its wear, total displacement and
preload deformation against the distance. Drawn on matplotlib's Agg canvas without pyplot, like
:mod:`.cosim.plots`.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from . import wear as wa


def plot_figures(case: wa.WearCase, result: dict, path: str | Path, loads=None) -> Path:
    """Four panels: (Fig. 14) elastic, wear and total displacement after the run against the
    vertical load (``loads`` [N], default 0 to twice the case's); (Fig. 15) the displacement
    wear adds and (Fig. 16) the total displacement against the distance at three creep rates;
    (Fig. 17) the total displacement, the wear part and the preload deformation of
    :func:`..wear.analyse`'s ``result``. Writes a PNG to ``path`` and returns it."""
    distance = result["distance"][-1]
    loads = np.linspace(0.0, 2.0 * max(case.load, 1.0), 9) if loads is None else loads
    sweep = wa.load_sweep(case, distance, loads)
    cases = wa.creep_cases(case, distance)
    km = np.asarray(result["distance"]) / 1e3
    fig = Figure(figsize=(11.0, 8.5))
    (a14, a15), (a16, a17) = fig.subplots(2, 2)
    load_kn = np.asarray(sweep["load"]) / 1e3
    a14.plot(load_kn, 1e6 * np.asarray(sweep["elastic"]), label="elastic (new guide)")
    a14.plot(load_kn, 1e6 * np.asarray(sweep["total"]), "--", label=f"total after {distance / 1e3:g} km")
    a14b = a14.twinx()
    a14b.plot(load_kn, 1e9 * np.asarray(sweep["wear"]), color="C2", label="added by wear")
    a14b.set_ylabel("displacement added by wear [nm]", color="C2")
    a14.set_xlabel("vertical load on the slider [kN]")
    a14.set_ylabel("slider displacement toward the rail [um]")
    a14.set_title(f"cf. Fig. 14: after {distance / 1e3:g} km")
    a14.legend(fontsize=7, loc="upper left")
    for c in cases:
        label = f"creep rate {abs(c['creep_rate']):.2e}"
        d = np.asarray(c["distance"]) / 1e3
        a15.plot(d, 1e9 * np.asarray(c["wear"]), label=label)
        a16.plot(d, 1e6 * np.asarray(c["total"]), label=label)
    a15.set_ylabel("slider displacement added by wear [nm]")
    a15.set_title(f"cf. Fig. 15: wear under {case.load / 1e3:g} kN")
    a16.set_ylabel("total slider displacement [um]")
    a16.set_title(f"cf. Fig. 16: total displacement under {case.load / 1e3:g} kN")
    z = np.asarray(result["vertical_displacement"])
    a17.plot(km, 1e6 * z, label="total displacement")
    a17.plot(km, 1e6 * np.asarray(result["preload_deformation"]), ":",
             label="preload deformation (approach at rest)")
    if result["preload_lost_at"] is not None:
        a17.axvline(result["preload_lost_at"] / 1e3, color="k", lw=0.8, label="preload lost")
    a17.set_ylabel("displacement, preload deformation [um]")
    a17b = a17.twinx()
    a17b.plot(km, 1e9 * (z - z[0]), color="C2")
    a17b.set_ylabel("displacement added by wear [nm]", color="C2")
    a17.set_title(f"cf. Fig. 17: under {case.load / 1e3:g} kN")
    for ax in (a15, a16, a17):
        ax.set_xlabel("running distance [km]")
        ax.legend(fontsize=7)
    for ax in (a14, a15, a16, a17):
        ax.grid(True, alpha=0.3)
    fig.suptitle("Fractal-creep wear of a linear ball guide (after Zhang, Wang and Jiang)")
    fig.tight_layout()
    path = Path(path)
    FigureCanvasAgg(fig).print_png(str(path))
    return path
