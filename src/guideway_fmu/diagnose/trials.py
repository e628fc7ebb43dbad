"""Synthetic trials of the discrepancy workflow: a truth run hiding one effect (truth.py),
diagnosed end to end, summarised.

    python -m guideway_fmu.diagnose.trials ROOT FMU_DIR TRIALS_JSON

runs a list of trials (``[{"name", "effect", "seed", **truth knobs}]``) in one process and
prints their summaries as one JSON list on the last line. Each diagnosis co-simulates through
FMUs loaded into the process, so tests and benchmarks run a batch in a child process
(:func:`run_batch`), several batches side by side.
"""
from __future__ import annotations

import json
import subprocess
import sys
import time as clock
import warnings
from pathlib import Path

import numpy as np

from ..process import exit_without_finalising
from . import truth
from .workflow import diagnose


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


def main(argv=None) -> None:
    root, fmu_dir, trials = argv if argv is not None else sys.argv[1:]
    warnings.simplefilter("ignore")
    print(json.dumps([trial(root, fmu_dir, **t) for t in json.loads(trials)]), flush=True)


if __name__ == "__main__":
    main()
    exit_without_finalising(0)  # the child has loaded FMUs (guideway_fmu.process)
