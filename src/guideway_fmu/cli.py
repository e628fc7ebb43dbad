"""Command line: ``guideway-fmu build | demo | facts``."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="guideway-fmu", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("build", help="build the FMUs and their README")
    p.add_argument("--out", type=Path, default=Path("fmus"), help="output folder (default fmus/)")
    p.add_argument("names", nargs="*", help="FMUs to build (default: all)")
    p = sub.add_parser("demo", help="the main job: FMUs, stiffness curves, rig co-simulation")
    p.add_argument("--out", type=Path, default=Path("out/demo"))
    p.add_argument("--fmus", type=Path, default=Path("fmus"))
    p.add_argument("--stop", type=float, default=0.02, help="simulated time [s]")
    p.add_argument("--step", type=float, default=5e-6, help="macro step [s]")
    p = sub.add_parser("facts", help="print k, delta0, film and natural frequency of paper 000's rig")
    p.add_argument("--u", type=float, default=0.29, help="feed speed [m/s] (default 0.29)")
    args = parser.parse_args(argv)
    try:
        if args.command == "build":
            from .build import build
            for path in build(args.out, args.names or None):
                print(path)
        elif args.command == "demo":
            if not (args.stop > 0 and args.step > 0 and args.step <= args.stop):
                raise ValueError(f"need 0 < --step <= --stop, got --step {args.step} --stop {args.stop}")
            from .demo import run_demo
            print(json.dumps(run_demo(args.out, args.fmus, args.stop, args.step), indent=2))
        elif args.command == "facts":
            from .demo import rig_facts
            print(json.dumps(rig_facts(args.u), indent=2))
    except (ValueError, FileNotFoundError, KeyError, RuntimeError) as exc:
        print(f"guideway-fmu {args.command}: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
