"""Speed-up of a sweep on a local Dask cluster of two worker processes over the same points run
one after the other in this process.

16 points (4 load amplitudes x 4 excitation frequencies) of Soleimanian et al.'s lubricated rig
(the shipped 9000 N / 4500 Hz scenario with the carriage's external force changed), each a
co-simulation of --stop seconds reduced to the upper roller load's peak and envelope. Prints
both wall times, the speed-up with and without the cluster's start, and whether the two runs
gave the same numbers, and writes them to docs/sweep-speedup.md. Needs two free cores to show
what two workers can do.

    python benchmarks/sweep_speedup.py [--stop 0.1] [--workers 2] [--fmus fmus] [--out docs/sweep-speedup.md]
"""
from __future__ import annotations

import argparse
import csv
import os
import tempfile
import time
from pathlib import Path

from guideway_fmu.fmu_build import build
from guideway_fmu.sweep import run, sweep_file
from guideway_fmu.sweep.point import run_point

import pages

SWEEP = """scenario = "soleimanian2020_9000N_4500Hz"
[experiment]
stop = {stop}
[design]
kind = "factorial"
[design.values]
"Carriage.load_amplitude" = [6000.0, 8000.0, 10000.0, 12000.0]
"Carriage.load_frequency" = [2500.0, 4500.0, 5000.0, 9000.0]
[[outputs]]
variable = "Contact.F_upper"
reduce = "peak"
[[outputs]]
variable = "Contact.F_upper"
reduce = "envelope"
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stop", type=float, default=0.1, help="simulated time per point [s]")
    parser.add_argument("--workers", type=int, default=2, help="worker processes")
    parser.add_argument("--fmus", type=Path, default=Path("fmus"), help="FMU folder (built where missing)")
    parser.add_argument("--out", type=Path, default=Path("docs/sweep-speedup.md"), help="page written")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "speedup.toml"
        path.write_text(SWEEP.format(stop=args.stop))
        sweep = sweep_file.load(path, build.ensure(args.fmus))
        start = time.perf_counter()
        serial = {i: run_point(sweep.system, p, sweep.outputs)["outputs"]
                  for i, p in zip(sweep.ids, sweep.points)}
        serial_s = time.perf_counter() - start
        start = time.perf_counter()
        with run.dask_client(args.workers) as client:
            ready = time.perf_counter()
            run.run_sweep(sweep, Path(tmp) / "out", client, progress=False, plot=False)
            swept = time.perf_counter()
        with (Path(tmp) / "out" / "results.csv").open(newline="") as f:
            table = {r["point"]: {c: float(r[c]) for c in serial[r["point"]]} for r in csv.DictReader(f)}
    rows = [("serial, in this process", f"{serial_s:.2f}", "1.00"),
            (f"{args.workers} Dask worker processes, cluster start included",
             f"{swept - start:.2f}", f"{serial_s / (swept - start):.2f}"),
            (f"{args.workers} Dask worker processes, points only (cluster start "
             f"{ready - start:.2f} s)", f"{swept - ready:.2f}", f"{serial_s / (swept - ready):.2f}")]
    lines = ["# Sweep speed-up", "",
             f"{len(sweep.points)} points (4 load amplitudes x 4 "
             "excitation frequencies) of the shipped 9000 N / 4500 Hz scenario, each a "
             f"co-simulation of {args.stop:g} s reduced to the upper roller load's peak and "
             f"envelope, on a machine with {os.cpu_count()} cores, both runs in one process one "
             "after the other.", "",
             "| run | wall time [s] | speed-up |", "| --- | --- | --- |",
             *(f"| {r} | {w} | {x} |" for r, w, x in rows), "",
             f"The swept table equals the serial run's numbers: {'yes' if table == serial else 'NO'}.",
             "The cluster's start (worker processes importing numpy, SciPy and fmpy) is paid once "
             "per sweep; the points themselves share nothing, so the speed-up approaches the "
             "worker count as points get longer. Other programs on the machine lower it.", ""]
    pages.write(args.out, "\n".join(lines),
                f"python benchmarks/sweep_speedup.py --stop {args.stop:g} --workers {args.workers}",
                __file__, (f"{pages.SCENARIOS}/soleimanian2020_9000N_4500Hz.toml",))
    print("\n".join(lines))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
