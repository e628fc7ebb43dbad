"""One scenario run to a folder: results.csv (+ units, written as the run goes), summary.json
and the plots: those the scenario names, else every recorded column's time history and the
spectra of those that oscillate (plots.plot_defaults); :func:`read` takes a run folder's results
back.

summary.json is strict JSON (no NaN or Infinity: a non-finite number is written as the string
"inf", "-inf" or "nan"), replaced whole (:func:`write_json`), and says what results.csv holds
(``results``: ``rows`` and ``bytes``), so that a reader can tell a file cut by a full disk or a
file-size limit from a whole one.
"""
from __future__ import annotations

import json
import math
import os
import threading
from pathlib import Path

from . import master, plots, recording
from .folder_lock import folder_lock
from .system import PLOT_KINDS, System


def run(system: System, out: Path, progress: bool = True) -> master.Result:
    """Simulate ``system`` and write everything into ``out``, holding its lock (folder_lock.py:
    FolderInUse if another run writes there). The results stream to results.csv as they are
    recorded; on failure, interrupt or step timeout a summary with the cause is written (no
    plots) before SimulationError propagates or the process ends. An earlier run's summary.json
    in ``out`` is removed first: it describes other results."""
    with folder_lock(out):
        (out / "summary.json").unlink(missing_ok=True)
        try:
            result = master.simulate(
                system, progress=progress, results=out / "results.csv",
                before_exit=lambda partial: _write(partial, system, out, plot=False))
        except master.SimulationError as exc:
            try:
                _write(exc.result, system, out, plot=False)
            except OSError as unwritten:
                raise master.SimulationError(f"{exc}\n{unwritten}", exc.result,
                                             exc.signal) from exc
            raise
        _write(result, system, out, plot=True)
    return result


def _write(result: master.Result, system: System, out: Path, plot: bool) -> None:
    """summary.json, then the plots and summary.json again with their files (a plot that fails
    loses no summary)."""
    rec = result.recording
    files = ["results.csv", "results.units.json", "summary.json"]
    _summary(result, system, out, files)
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
        _summary(result, system, out, files)


def _summary(result: master.Result, system: System, out: Path, files: list[str]) -> None:
    write_json(out / "summary.json", {**result.summary(), "experiment": system.experiment.__dict__,
                                      "scenario_file": str(system.path), "files": files})


def write_json(path: Path, value) -> None:
    """``value`` as strict JSON (module doc; other objects, such as paths, as their str) in
    ``path``, atomically: written to a temporary file beside it, synced, renamed over it, so
    that a reader finds the former file or the new one, whole. OSError naming ``path`` if it
    cannot be written (the former file is then left as it was)."""
    text = json.dumps(_finite(value), indent=2, default=str, allow_nan=False)
    # one name per process and thread (the watchdog's thread may write while the main one does)
    temporary = path.with_name(f".{path.name}.{os.getpid()}.{threading.get_ident()}")
    try:
        try:
            with open(temporary, "w") as f:
                f.write(text)
                f.flush()
                os.fsync(f.fileno())
            os.replace(temporary, path)
        except BaseException:
            temporary.unlink(missing_ok=True)
            raise
    except OSError as exc:
        raise OSError(f"cannot write {path}: {exc.strerror or exc}") from exc


def _finite(value):
    """``value`` with each non-finite float, in it at any depth, as its str."""
    if isinstance(value, float):
        return value if math.isfinite(value) else str(value)
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    return value


def read(out: str | Path) -> tuple[recording.Recording, dict]:
    """The recording in results.csv of the run folder ``out`` and its summary; results.csv is
    checked against what summary.json says the run wrote (recording.read). FileNotFoundError
    naming a missing file, ValueError naming one that is not what the run wrote."""
    out = Path(out)
    results, summary_path = out / "results.csv", out / "summary.json"
    for path in (results, summary_path):
        if not path.is_file():
            raise FileNotFoundError(f"{path} not found (a run folder holds results.csv and "
                                    "summary.json; a run killed before its end has no summary)")
    try:
        summary = json.loads(summary_path.read_text())
        rows, size = int(summary["results"]["rows"]), int(summary["results"]["bytes"])
    except (ValueError, KeyError, TypeError):
        raise ValueError(f"{summary_path}: not the summary of a run that wrote results.csv (no "
                         '"results" with its rows and bytes)') from None
    return recording.read(results, rows, size), summary
