"""Command line: ``guideway-fmu build | run | verify | export-ssp | demo | facts``."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path


def _scenario_args(p) -> None:
    p.add_argument("scenario", type=Path, help="scenario TOML (see orchestration/scenarios/)")
    p.add_argument("--fmus", type=Path, default=None,
                   help="take every FMU by file name from this folder instead of the scenario's paths")
    p.add_argument("--stop", type=float, default=None, help="override the stop time [s]")
    p.add_argument("--step", type=float, default=None, help="override the macro step [s]")
    p.add_argument("--algorithm", choices=("jacobi", "gauss-seidel", "stabilised"), default=None)


def _load(args):
    from .cosim import system
    s = system.load(args.scenario, args.fmus)
    changes = {k: getattr(args, k) for k in ("stop", "step", "algorithm") if getattr(args, k) is not None}
    return s.with_changes(**changes) if changes else s


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="guideway-fmu", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("build", help="build the FMUs and their README")
    p.add_argument("--out", type=Path, default=Path("fmus"), help="output folder (default fmus/)")
    p.add_argument("names", nargs="*", help="FMUs to build (default: all)")
    p = sub.add_parser("run", help="co-simulate a scenario: results.csv, summary.json, plots")
    _scenario_args(p)
    p.add_argument("--out", type=Path, required=True, help="output folder")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p = sub.add_parser("verify", help="co-simulation against the monolithic SciPy reference")
    _scenario_args(p)
    p.add_argument("--json", action="store_true", help="print the comparison as JSON")
    p = sub.add_parser("export-ssp", help="write the scenario as an SSP 1.0 package")
    _scenario_args(p)
    p.add_argument("out", type=Path, help="the .ssp file to write")
    p = sub.add_parser("demo", help="the main job: FMUs, stiffness curves, paper scenarios, verification")
    p.add_argument("--out", type=Path, default=Path("out/demo"))
    p.add_argument("--fmus", type=Path, default=Path("fmus"))
    p.add_argument("--stop", type=float, default=0.02, help="simulated time of each run [s]")
    p = sub.add_parser("facts", help="print k, delta0, film and natural frequency of paper 000's rig")
    p.add_argument("--u", type=float, default=0.29, help="feed speed [m/s] (default 0.29)")
    args = parser.parse_args(argv)
    try:
        if args.command == "build":
            from .build import build
            for path in build(args.out, args.names or None):
                print(path)
        elif args.command == "run":
            from .cosim.run import run
            result = run(_load(args), args.out, progress=not args.no_progress)
            print(json.dumps({k: v for k, v in result.summary().items() if k != "parameters"}, indent=2))
        elif args.command == "verify":
            from .verify import format_table, verify
            report = verify(_load(args))
            print(json.dumps(report, indent=2) if args.json else format_table(report))
        elif args.command == "export-ssp":
            from .cosim.ssp import export_ssp
            print(export_ssp(_load(args), args.out))
        elif args.command == "demo":
            if not args.stop > 0:
                raise ValueError(f"need --stop > 0, got {args.stop}")
            from .demo import run_demo
            print(json.dumps(run_demo(args.out, args.fmus, args.stop), indent=2))
        elif args.command == "facts":
            from .demo import rig_facts
            print(json.dumps(rig_facts(args.u), indent=2))
    except (ValueError, FileNotFoundError, KeyError, RuntimeError) as exc:  # incl. SimulationError
        print(f"guideway-fmu {args.command}: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
