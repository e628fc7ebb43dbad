"""Command line: ``guideway-fmu build | demo | facts``."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path


def _facts(args) -> dict:
    from .physics import carriage, film, guideway
    g, body = guideway.Guideway(), carriage.Body()
    f_u, _, h_u, _ = guideway.quasi_static_state(g, 0.0, args.u)
    k_lub = float(guideway.quasi_static_stiffness(g, 0.0, args.u))
    k_dry = float(guideway.quasi_static_stiffness(g, 0.0, lubricated=False))
    ph = film.LineContact(model="pan_hamrock")
    hz = lambda k: (k / body.mass) ** 0.5 / (2 * 3.141592653589793)  # noqa: E731
    return {
        "roller_stiffness_k_N_per_m^(10/9)": g.k,
        "preload_per_roller_N": g.preload_per_roller,
        "preload_approach_delta0_m": g.delta0,
        "feed_speed_m_per_s": args.u,
        "film_extrapolated_at_y0_m": float(h_u),
        "film_pan_hamrock_at_y0_m": float(film.steady_film(ph, f_u, args.u)),
        "roller_load_at_y0_N": float(f_u),
        "rail_mass_kg": body.mass,
        "stiffness_y0_lubricated_N_per_m": k_lub,
        "stiffness_y0_dry_N_per_m": k_dry,
        "natural_frequency_lubricated_Hz": hz(k_lub),
        "natural_frequency_dry_Hz": hz(k_dry),
        "paper_natural_frequency_Hz": 6590.0,
    }


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
            from .demo import run_demo
            print(json.dumps(run_demo(args.out, args.fmus, args.stop, args.step), indent=2))
        elif args.command == "facts":
            print(json.dumps(_facts(args), indent=2))
    except (ValueError, FileNotFoundError, KeyError) as exc:
        print(f"guideway-fmu {args.command}: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
