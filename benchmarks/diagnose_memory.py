"""Peak memory of ``guideway-fmu diagnose`` on long measured runs, side by side.

    python benchmarks/diagnose_memory.py [--rows 100000 1000000] [--seed 3]
                                         [--page docs/diagnose-memory.md]

Each record is a first-generator horizontal run (guideway_synthetic/truth.py, pre-sliding hysteresis
hidden, 1 kHz, seed SEED; 3 draws a ball guide, the worst case: its ball-to-ball candidate's
table has the most nodes) of the given number of rows. Each diagnosis runs in a child process
(``python -m guideway_fmu.cli diagnose``, guideway_synthetic.trials.diagnose_in_child) whose own peak
resident set size is read when it ends. The FMUs are built once beforehand (not measured).
Prints, per record, the peak RSS [GB = 1e9 bytes], the wall time and the named effect, and
writes them to the page (--page - writes none).
"""
from __future__ import annotations

import argparse
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from guideway_fmu.fmu_build.build import build
from guideway_synthetic import truth
from guideway_synthetic.trials import diagnose_in_child

import pages

TARGET = 2.0  # GB: the bound on the peak RSS of diagnose at 1e6 rows
EFFECT = "presliding_hysteresis"


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, nargs="+", default=[100_000, 1_000_000])
    parser.add_argument("--seed", type=int, default=3, help="seed of the records (3: a ball guide)")
    parser.add_argument("--page", default=str(Path(__file__).resolve().parents[1] / "docs" /
                                              "diagnose-memory.md"),
                        help="Markdown page the figures are written to ('-': none)")
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore")
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        build(folder / "fmus")
        for n in args.rows:
            run = folder / f"run_{n}"
            truth.make_run(run, EFFECT, np.random.default_rng(args.seed), n_samples=n)
            started = time.perf_counter()
            diagnosis, peak = diagnose_in_child(run, folder / f"out_{n}", folder / "fmus")
            wall, peak = time.perf_counter() - started, peak / 1e9
            rows.append((n, peak, wall, diagnosis["missing_effect"]))
            print(f"{n:>9} rows: peak RSS {peak:5.2f} GB   wall {wall:7.1f} s   named "
                  f"{diagnosis['missing_effect']!r} (hidden: {EFFECT!r})", flush=True)
    if args.page == "-":
        return
    command = "python benchmarks/diagnose_memory.py " + " ".join(
        ["--rows", *map(str, args.rows), "--seed", str(args.seed)])
    lines = [
        "# Peak memory of diagnose on long records", "",
        f"First-generator horizontal records (`guideway_synthetic/truth.py`, `{EFFECT}` hidden, 1 kHz, "
        f"seed {args.seed}; seed 3 draws a ball guide, whose ball-to-ball candidate has the "
        f"largest table); each `guideway-fmu diagnose` runs in a child process whose peak "
        f"resident set size (RSS) is read when it ends. Target: under {TARGET:g} GB at 1e6 "
        f"rows. docs/measured-run.md says where the memory went and what bounds it.", "",
        "| rows | peak RSS [GB] | wall time [s] | named |", "|---|---|---|---|",
        *[f"| {n} | {peak:.2f} | {wall:.0f} | `{named}` |" for n, peak, wall, named in rows], ""]
    pages.write(args.page, "\n".join(lines), command, __file__)


if __name__ == "__main__":
    main()
