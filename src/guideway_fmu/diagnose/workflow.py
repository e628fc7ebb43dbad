"""The discrepancy workflow, ``diagnose(run_dir, out_dir)``: read the measured run once
(run_io.py), then the steps of its rig (rigs.py: a plug-in per [rig] kind): decide which
effects the model misses (load and check, calibrate the baseline, locate the gap, fit and score
the candidates, name them in turn), realise the named model as a scenario run through the FMUs,
and report (report.py: diagnosis.json, fit.csv, plots, report.html)."""
from __future__ import annotations

import time as clock
from pathlib import Path

from ..cosim.folder_lock import folder_lock
from ..fmu_build import cache
from ..output.progress import stages
from .rigs import RIGS
from .run_io import load_run


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
        rig = RIGS[run.kind]()  # run_io checked the kind against the format's
        with folder_lock(out):
            begin("fit and score the candidate effects")
            naming = rig.decide(run, out, fmus)
            begin("co-simulate the named model")
            realised = rig.realise(naming, out, fmus)
            begin("write the report")
            return rig.report(out, naming, realised, clock.perf_counter() - started)
