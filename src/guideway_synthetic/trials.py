"""Synthetic trials of the discrepancy workflow: a truth run hiding one effect (truth.py),
diagnosed end to end, summarised.

    python -m guideway_synthetic.trials ROOT FMU_DIR TRIALS_JSON

runs a list of trials (``[{"name", "effect", "seed", **truth knobs}]``) in one process and
prints their summaries as one JSON list on the last line. Each diagnosis co-simulates through
FMUs loaded into the process, so tests and benchmarks run a batch in a child process
(:func:`run_batch`), several batches side by side.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time as clock
import warnings
from pathlib import Path

import numpy as np

from guideway_fmu.cosim.interrupts import exit_without_finalising
from . import truth
from guideway_fmu.diagnose.workflow import diagnose


def trial(root, fmu_dir, name: str, effect: str, seed: int, **knobs) -> dict:
    """Write the truth run ``root``/``name`` hiding ``effect`` (seed ``seed``, truth.make_run's
    ``knobs``), diagnose it into ``root``/``name``_out; the expected and named effects, the
    gaps, the wall time of the diagnosis [s] and the diagnosis itself."""
    run = Path(root) / name
    info = truth.make_run(run, effect, np.random.default_rng(seed), **knobs)
    started = clock.perf_counter()
    d = diagnose(run, f"{run}_out", fmu_dir=fmu_dir)
    return {"name": name, "effect": effect, "seed": seed, "expected": info.expected,
            "named": d["missing_effect"], "gap_before": d["gap_before"],
            "gap_after": d["gap_after"], "noise_floor": d["noise_floor"],
            "seconds": clock.perf_counter() - started, "diagnosis": d}


def run_batch(root, fmu_dir, trials: list[dict], timeout: float | None = None) -> list[dict]:
    """The summaries of ``trials`` (as :func:`trial`'s keywords), run in a child process.
    Raises RuntimeError with the end of the child's error output if it fails."""
    done = subprocess.run([sys.executable, "-m", __name__, str(root), str(fmu_dir),
                           json.dumps(trials)], capture_output=True, text=True, timeout=timeout)
    if done.returncode != 0:
        raise RuntimeError(f"trials {[t['name'] for t in trials]} failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def diagnose_in_child(run_dir, out_dir, fmu_dir) -> tuple[dict, float]:
    """(diagnosis.json's content, peak resident set size [bytes]) of ``guideway-fmu diagnose``
    run in a child process, its peak read by os.wait4 when it ends (Linux: ru_maxrss in kB).
    Raises RuntimeError with the end of the child's error output if it fails."""
    child = subprocess.Popen([sys.executable, "-m", "guideway_fmu.cli", "diagnose", str(run_dir),
                              "--out", str(out_dir), "--fmus", str(fmu_dir)],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    error = child.stderr.read().decode(errors="replace")
    _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
    if child.returncode != 0:
        raise RuntimeError(f"diagnose {run_dir} failed:\n{error[-3000:]}")
    return json.loads((Path(out_dir) / "diagnosis.json").read_text()), usage.ru_maxrss * 1024.0


def main(argv=None) -> None:
    root, fmu_dir, trials = argv if argv is not None else sys.argv[1:]
    warnings.simplefilter("ignore")
    print(json.dumps([trial(root, fmu_dir, **t) for t in json.loads(trials)]), flush=True)


if __name__ == "__main__":
    main()
    exit_without_finalising(0)  # the child has loaded FMUs (guideway_fmu.cosim.interrupts)
