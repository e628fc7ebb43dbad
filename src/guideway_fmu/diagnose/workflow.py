"""The discrepancy workflow, ``diagnose(run_dir, out_dir)``: decide which effect the model
misses (decide.py: load and check the run, derive the motion, calibrate the baseline, locate the
gap, fit and score the candidates, name one), realise the named model as a scenario run
through the FMUs (realise.py), and report (report.py: diagnosis.json, fit.csv, plots,
report.html). Vertical responses take the same steps in vertical.py."""
from __future__ import annotations

import time as clock
from pathlib import Path

from ..cosim.folder_lock import folder_lock
from ..fmu_build import cache
from ..output.progress import stages
from .decide import decide
from .realise import realise
from .report import write_report, write_vertical_report
from .run_io import load_run
from .vertical import decide_vertical, realise_vertical


def diagnose(run_dir, out_dir, fmu_dir=None, progress: bool = False) -> dict:
    """Diagnose the measured run in ``run_dir``; write everything into ``out_dir``.

    ``fmu_dir``: where to find (or build) the FMUs, by default the FMU cache's folder
    (fmu_build.cache). ``progress``: a bar of the steps (decide, realise, report) on stderr.
    Returns the content of diagnosis.json. Raises FileNotFoundError or ValueError (one message
    naming the file and the row, column, section or key) for a run that cannot be used, and
    FolderInUse (cosim/folder_lock.py) if another diagnosis or run writes into ``out_dir``: it is
    locked meanwhile.
    """
    started = clock.perf_counter()
    out = Path(out_dir)
    fmus = Path(fmu_dir) if fmu_dir is not None else cache.folder()
    with stages(f"diagnose {Path(run_dir).name}", total=4, enabled=progress) as begin:
        begin("read the run")
        run = load_run(run_dir)
        vertical = run.kind == "vertical_response"
        with folder_lock(out):
            begin("fit and score the candidate effects")
            naming = (decide_vertical(run, out / "model", fmus) if vertical
                      else decide(run_dir))
            begin("co-simulate the named model")
            realised = realise_vertical(naming, out) if vertical else realise(naming, out, fmus)
            begin("write the report")
            seconds = clock.perf_counter() - started
            return (write_vertical_report(out, naming, realised, seconds) if vertical
                    else write_report(out, naming, realised, seconds))
