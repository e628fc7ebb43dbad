"""Every FMU in a plain C host, many runs each: the pythonfmu edition with the environment
`guideway-fmu host-env` prints, the native edition with an empty one; exit statuses and the cost
of a step in the host, written to docs/c-host.md.

The host (src/guideway_fmu/fmu_build/c_host.c) does what a commercial tool does: dlopen,
instantiate, initialise, ten steps at the FMU's default step, read every Real output, terminate,
free, dlclose, exit. A crash at exit (SIGSEGV, SIGABRT) shows as a negative status. ForceTable is
given a two-row force table, the only FMU that needs a file. The cost of a step is the host's
stepping loop timed by the host itself over many steps (median of three runs): fmi2DoStep as the
host calls it, the FMU's physics included.

    python benchmarks/c_host_exit.py [--runs 20] [--out docs/c-host.md]
"""
from __future__ import annotations

import argparse
import collections
import re
import statistics
import tempfile
import time
from pathlib import Path

from guideway_fmu.fmu_build import build, host_env
from guideway_fmu.fmu_build.native import COMPONENTS

import pages


def step_cost(executable, fmu, environment, work_dir, steps: int) -> float:
    """Seconds per fmi2DoStep in the C host: its stepping loop's own clock (c_host.c), median of
    three runs."""
    def run():
        done = host_env.run_in_c_host(executable, fmu, environment, work_dir=work_dir, steps=steps)
        assert done.status == 0, done.stderr[-2000:]
        return float(re.search(r"c_host: \d+ steps in (\S+) s", done.stderr)[1]) / steps
    return statistics.median(run() for _ in range(3))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=20)
    parser.add_argument("--out", type=Path, default=Path("docs/c-host.md"))
    args = parser.parse_args()
    environments = {"python": host_env.host_environment(), "native": {}}
    rows, costs = [], {}
    with tempfile.TemporaryDirectory(prefix="guideway_fmu_c_host_") as tmp:
        tmp = Path(tmp)
        table = tmp / "force.csv"
        table.write_text("time,normal_force\n0,100\n1,200\n")
        executable = host_env.compile_c_host(tmp)
        fmus = {"python": build.build(tmp / "python"),
                "native": build.build(tmp / "native", list(COMPONENTS), "native")}
        for edition, built in fmus.items():
            for fmu in built:
                start = {"table_file": str(table)} if fmu.stem == "ForceTable" else {}
                begun = time.perf_counter()
                statuses = collections.Counter(
                    host_env.run_in_c_host(executable, fmu, environments[edition], work_dir=tmp,
                                           start_values=start).status for _ in range(args.runs))
                seconds = (time.perf_counter() - begun) / args.runs
                rows.append((fmu.stem, edition, statuses, seconds))
                print(fmu.stem, edition, dict(statuses), f"{seconds:.2f} s per run", flush=True)
                if fmu.stem in COMPONENTS:
                    costs[fmu.stem, edition] = step_cost(
                        executable, fmu, environments[edition], tmp,
                        20000 if edition == "python" else 1000000)
    clean = sum(s[0] for _, _, s, _ in rows)
    lines = ["# The FMUs in a C host", "",
             f"Each FMU runs {args.runs} times in",
             "`src/guideway_fmu/fmu_build/c_host.c` (dlopen, instantiate, ten steps, read the "
             "outputs, terminate, free, dlclose, exit): the pythonfmu edition with the "
             "environment `guideway-fmu host-env` prints "
             f"({', '.join(f'`{k}`' for k in environments['python'])}: this machine's paths, so "
             "not shown here), the native edition (`guideway-fmu build --edition native`) with "
             "no environment variable at all and no patch of its binary.", "",
             f"{clean} of {len(rows) * args.runs} runs exited with status 0.", "",
             "| FMU | edition | environment variables | runs | exit 0 | other statuses | "
             "seconds per run |", "| --- | --- | --- | --- | --- | --- | --- |"]
    for name, edition, statuses, seconds in rows:
        other = ", ".join(f"{k}: {n}" for k, n in sorted(statuses.items()) if k != 0) or "none"
        lines.append(f"| {name} | {edition} | {len(environments[edition])} | {args.runs} | "
                     f"{statuses[0]} | {other} | {seconds:.3f} |")
    lines += ["", "## A step in the C host", "",
              "Microseconds per fmi2DoStep at the FMU's default step, its physics included (the "
              "host's stepping loop timed by the host, median of three runs). The "
              "pythonfmu edition enters the Python interpreter on every call (a thread state "
              "created and released, the arguments converted); the native one is a C call.", "",
              "| FMU | python edition us | native edition us | ratio |", "| --- | --- | --- | --- |"]
    for name in COMPONENTS:
        python, native = costs[name, "python"], costs[name, "native"]
        lines.append(f"| {name} | {python * 1e6:.2f} | {native * 1e6:.3f} | {python / native:.0f} |")
    lines += ["", "Before the build worked around two defects outside this project "
              "(`components/runtime.py`, `fmu_build/exit_patch.py`), FeedKinematics died at exit "
              "in 10 of 10 runs (SIGSEGV in SciPy's `_uarray` during the interpreter's "
              "finalisation) and HorizontalRig in 5 of 5 runs from one folder (`free(): corrupted "
              "unsorted chunks`, pythonfmu's exit-time use-after-free), after every FMI call had "
              "returned OK. The native edition needs neither.", ""]
    pages.write(args.out, "\n".join(lines), f"python benchmarks/c_host_exit.py --runs {args.runs}",
                __file__)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
