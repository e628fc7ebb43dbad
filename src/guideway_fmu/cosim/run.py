"""One scenario run to a folder: results.csv (+ units, written as the run goes), summary.json
and the plots: those the scenario names, else every recorded column's time history and the
spectra of those that oscillate (plots.plot_defaults)."""
from __future__ import annotations

import json
from pathlib import Path

from . import master, plots
from .system import PLOT_KINDS, System


def run(system: System, out: Path, progress: bool = True) -> master.Result:
    """Simulate ``system`` and write everything into ``out``. The results stream to
    results.csv as they are recorded; on failure, interrupt or step timeout a summary with the
    cause is written (no plots) before SimulationError propagates or the process ends."""
    out.mkdir(parents=True, exist_ok=True)
    try:
        result = master.simulate(system, progress=progress, results=out / "results.csv",
                                 before_exit=lambda partial: _write(partial, system, out, plot=False))
    except master.SimulationError as exc:
        _write(exc.result, system, out, plot=False)
        raise
    _write(result, system, out, plot=True)
    return result


def _write(result: master.Result, system: System, out: Path, plot: bool) -> None:
    rec = result.recording
    files = ["results.csv", "results.units.json", "summary.json"]
    if plot and len(rec.time) > 8:
        kinds = {k: v for k, v in system.plots.items() if k in PLOT_KINDS and v}
        options = {k: system.plots[k] for k in ("skip", "f_max", "window") if k in system.plots}
        span = rec.time[-1] - rec.time[0]
        if "envelope" in kinds and "window" not in options:
            options["window"] = span / 200
        if options.get("skip", 0.0) > span / 2:  # a shortened run: keep half for the spectrum
            options["skip"] = span / 2
        files += [p.name for p in (plots.plot_all(rec, kinds, out, **options) if kinds else
                                   plots.plot_defaults(rec, out, skip=options.get("skip", 0.0),
                                                       f_max=options.get("f_max")))]
    summary = {**result.summary(), "experiment": system.experiment.__dict__,
               "scenario_file": str(system.path), "files": files}
    (out / "summary.json").write_text(json.dumps(summary, indent=2, default=str))
