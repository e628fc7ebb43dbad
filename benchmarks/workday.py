"""A developer's day in wall times, side by side in one run: the command line's start (help,
version, a missing input file, a wrong scenario name, a bad sweep file), the FMU cache filled
and looked up, the demo with an empty FMU cache and again with the full one, the fast test loop
and the whole test suite. Prints each as it is measured and writes docs/workday.md.

    python benchmarks/workday.py [--repeat 5] [--skip-demo] [--skip-fast-loop] [--skip-full-suite]

Every command runs in a child process with this interpreter and environment (PYTHONPATH
included); the demo and the cache into temporary folders (GUIDEWAY_FMU_CACHE), never the
user's. The whole suite is the two pytest passes of ``python3 bootstrap.py test`` with this
interpreter (bootstrap's install step left out). The machine's load average is printed beside
each time: other programs on the machine lengthen every one.
"""
from __future__ import annotations

import argparse
import importlib.util
import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path
from subprocess import DEVNULL, run

import pages

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("bootstrap", ROOT / "bootstrap.py")
bootstrap = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bootstrap)

#: the command line as a user calls it: the console script beside this interpreter
CLI = [shutil.which("guideway-fmu", path=str(Path(sys.executable).parent))
       or "guideway-fmu"]
BAD_SWEEP = 'scenario = "soleimanian2020_9000N_4500Hz"\ndesing = 1\n'  # a misspelt key
PYTEST = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"]


def load() -> str:
    """The 1-minute load average and the cores, as printed beside a time."""
    return f"load {os.getloadavg()[0]:.1f} on {bootstrap.workers()} cores"


def timed(command: list, cwd: Path, env: dict | None = None, status: int | None = 0) -> tuple:
    """(wall time [s], exit status) of ``command`` run in ``cwd``; RuntimeError if it ends
    otherwise than with ``status`` (None: any)."""
    start = time.perf_counter()
    done = run([str(c) for c in command], cwd=cwd, env=env, stdout=DEVNULL, stderr=DEVNULL)
    seconds = time.perf_counter() - start
    if status is not None and done.returncode != status:
        raise RuntimeError(f"{' '.join(map(str, command))} ended with {done.returncode}, "
                           f"not {status}")
    return seconds, done.returncode


def startup(folder: Path, repeat: int) -> list[tuple[str, str, float, int]]:
    """(what, command, median wall time [s] of ``repeat`` runs, exit status) of each start-up
    case."""
    (folder / "bad_sweep.toml").write_text(BAD_SWEEP)
    cases = [("help", ["--help"], 0), ("version", ["--version"], 0),
             ("a missing input file", ["modes", "no_such_carriage.toml"], 2),
             ("a wrong scenario name", ["run", "no_such_scenario", "--out", "out"], 2),
             ("a bad sweep file", ["sweep", "bad_sweep.toml", "--out", "out"], 2)]
    rows = []
    for what, args, status in cases:
        seconds = statistics.median(timed(CLI + args, folder, status=status)[0]
                                    for _ in range(repeat))
        rows.append((f"start-up: {what}", " ".join(["guideway-fmu", *args]), seconds, status))
        print(f"start-up: {what}: {seconds:.2f} s ({load()})", flush=True)
    return rows


def fmus_and_demo(folder: Path, with_demo: bool) -> list[tuple[str, str, float, int]]:
    """The FMU cache filled and looked up, and the demo on an empty and on a full cache."""
    rows = []
    fill = [sys.executable, "-c", "from guideway_fmu.fmu_build import cache; cache.folder()"]
    for what, cache in (("FMU cache: every FMU built into an empty cache", "fill"),
                        ("FMU cache: looked up, full", "fill")):
        env = {**os.environ, "GUIDEWAY_FMU_CACHE": str(folder / cache)}
        rows.append((what, "python -c 'from guideway_fmu.fmu_build import cache; "
                     "cache.folder()'", *timed(fill, folder, env)))
        print(f"{what}: {rows[-1][2]:.1f} s ({load()})", flush=True)
    if not with_demo:
        return rows
    env = {**os.environ, "GUIDEWAY_FMU_CACHE": str(folder / "demo-cache")}
    for what, out in (("demo, empty FMU cache", "first"), ("demo, full FMU cache", "second")):
        rows.append((what, f"guideway-fmu demo --out {out}",
                     *timed(CLI + ["demo", "--out", out], folder, env)))
        print(f"{what}: {rows[-1][2]:.1f} s ({load()})", flush=True)
    return rows


def suites(fast: bool, full: bool) -> list[tuple[str, str, float, int]]:
    """The fast loop and the whole suite, run in the repository, whatever their outcome."""
    rows = []
    if fast:
        rows.append(("fast test loop", 'python -m pytest -m "not slow" -n 2',
                     *timed(PYTEST + ["-m", "not slow", "-n", "2"], ROOT, status=None)))
        print(f"fast test loop: {rows[-1][2]:.0f} s ({load()})", flush=True)
    if full:
        start = time.perf_counter()
        status = bootstrap.test(["-q", "-p", "no:cacheprovider"], python=Path(sys.executable))
        rows.append(("whole test suite", "python3 bootstrap.py test",
                     time.perf_counter() - start, status))
        print(f"whole test suite: {rows[-1][2] / 60:.1f} min ({load()})", flush=True)
    return rows


def _time(seconds: float) -> str:
    return f"{seconds:.2f} s" if seconds < 10 else (
        f"{seconds:.0f} s" if seconds < 300 else f"{seconds / 60:.1f} min")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs of each start-up case")
    parser.add_argument("--skip-demo", action="store_true", help="no demo runs")
    parser.add_argument("--skip-fast-loop", action="store_true", help="no fast test loop")
    parser.add_argument("--skip-full-suite", action="store_true", help="no whole test suite")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "workday.md")
    args = parser.parse_args()
    before = load()
    with tempfile.TemporaryDirectory(prefix="workday-") as tmp:
        rows = startup(Path(tmp), args.repeat) + fmus_and_demo(Path(tmp), not args.skip_demo)
    rows += suites(not args.skip_fast_loop, not args.skip_full_suite)
    demo = {what: seconds for what, _, seconds, _ in rows if what.startswith("demo")}
    skipped = [name for name, flag in (("the demo", args.skip_demo),
                                       ("the fast loop", args.skip_fast_loop),
                                       ("the whole suite", args.skip_full_suite)) if flag]
    lines = ["# A working day's wall times", "",
             f"Measured one after the other on this machine: {before} at the start, "
             f"{load()} at the end (other programs lengthen every time). Each start-up time is the "
             f"median of {args.repeat} runs; the demo (runs of 0.02 s) and the FMU cache work "
             "in temporary folders, never the user's cache.", "",
             "| what | command | wall time | exit status |", "|---|---|---|---|",
             *[f"| {what} | `{command}` | {_time(seconds)} | {status} |"
               for what, command, seconds, status in rows], ""]
    if any(status not in (0, 2) for *_, status in rows):
        lines += ["An exit status of 1 is a test run with failures: the times stand, the "
                  "failures are the suite's to report.", ""]
    if len(demo) == 2:
        first, second = demo["demo, empty FMU cache"], demo["demo, full FMU cache"]
        lines += [f"The demo's second run takes {second / first:.0%} of its first: the FMU "
                  "cache saves the build of every FMU; the rest of the demo (the paper "
                  "scenarios, verification, diagnosis and the sweep) computes anew each time.",
                  ""]
    if skipped:
        lines += [f"Not measured in this run: {', '.join(skipped)}.", ""]
    flags = [f for f, on in (("--skip-demo", args.skip_demo),
                             ("--skip-fast-loop", args.skip_fast_loop),
                             ("--skip-full-suite", args.skip_full_suite)) if on]
    command = " ".join(["python benchmarks/workday.py", f"--repeat {args.repeat}", *flags])
    pages.write(args.out, "\n".join(lines), command, __file__,
                ("bootstrap.py", "pyproject.toml", "tests/**/*.py"))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
