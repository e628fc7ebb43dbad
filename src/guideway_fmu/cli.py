"""Command line: ``guideway-fmu build | host-env | scenarios | run | sweep | verify | export-ssp | export-fmu | diagnose | demo | facts | ehl | ehl-cycle | modes | feed-unit | ball-to-ball | wear``."""
from __future__ import annotations

import argparse
import json
import math
import re
import signal
import sys
from fractions import Fraction
from pathlib import Path

from .cosim.algorithms import ALGORITHMS
from .cosim.interrupts import exit_without_finalising


def _scenario_args(p) -> None:
    p.add_argument("scenario", help="scenario TOML file, or the name of a shipped scenario "
                   "(guideway-fmu scenarios lists them)")
    p.add_argument("--fmus", type=Path, default=None,
                   help="take every FMU by file name from this folder instead of the scenario's "
                        "paths (shipped scenarios: default ./fmus, built where missing)")
    p.add_argument("--stop", type=float, default=None, help="override the stop time [s]")
    p.add_argument("--step", type=float, default=None, help="override the macro step [s]")
    p.add_argument("--algorithm", choices=tuple(ALGORITHMS), default=None,
                   help="override the co-simulation algorithm")


def _load(args):
    from . import scenarios
    from .cosim import system
    path = scenarios.find(args.scenario)
    s = system.load(path, scenarios.fmu_folder(path, args.fmus))
    changes = {k: getattr(args, k, None) for k in ("stop", "step", "algorithm", "step_timeout")
               if getattr(args, k, None) is not None}
    return s.with_changes(**changes) if changes else s


def _ratio(text: str) -> float:
    """A number or a fraction such as 1/3 (argparse type)."""
    try:
        return float(Fraction(text))
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"expected a number or a fraction like 1/3, got {text!r}")


def _ehl_args(sub) -> None:
    from .physics.papers import soleimanian2020 as paper
    p = sub.add_parser("ehl", help="numerical mixed-EHL solution of one roller contact")
    for name, unit in (("load", "load per unit length w' [N/m]"),
                       ("velocity", "entrainment (mean) velocity u_m [m/s]"),
                       ("pressure-viscosity",
                        f"alpha [1/Pa] (default {paper.PRESSURE_VISCOSITY:g})"),
                       ("W", "Hamrock's load W = w'/(E' R)"), ("U", "speed U = mu0 u_m/(E' R)"),
                       ("G", "material G = alpha E'"),
                       ("radius", f"reduced radius R [m] (default {paper.ROLLER_RADIUS:g})"),
                       ("e-reduced", f"E' [Pa] (default {paper.E_REDUCED:g})"),
                       ("viscosity", f"mu0 [Pa s] (default {paper.VISCOSITY:g})"),
                       ("roughness", "composite RMS roughness [m] (default 0: smooth)"),
                       ("sliding-velocity", "u_s [m/s], friction only (default 0)"),
                       ("peklenik", "Patir-Cheng average flow with this roughness orientation "
                                    "gamma: 1 isotropic, 3/6/9 along the motion, 1/3/1/6/1/9 "
                                    "across (default: Soleimanian et al. 2020, eq. 18, no flow factors)")):
        p.add_argument(f"--{name}", type=_ratio if name == "peklenik" else float, default=None,
                       help=unit)
    p.add_argument("--nodes", type=int, default=None, help="grid nodes (default from the film)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--plot", type=Path, default=None, help="PNG of pressure and film against x/b")
    p = sub.add_parser("ehl-cycle", help="numerical EHL of one upper roller at instants of a run")
    p.add_argument("run_dir", type=Path, help="folder written by guideway-fmu run")
    p.add_argument("--out", type=Path, required=True, help="output folder")
    p.add_argument("--instance", default="Contact", help="contact instance (default Contact)")
    p.add_argument("--feed", default="Feed.u", help="feed velocity column (default Feed.u)")
    p.add_argument("--times", default=None,
                   help="instants t1,t2,... [s] (default: --count over the largest load oscillation)")
    p.add_argument("--count", type=int, default=None, help="instants A, B, ... (default 10)")
    p.add_argument("--window", type=float, default=None,
                   help="span [s] around the load peak (default: minimum to minimum)")
    p.add_argument("--history", type=float, default=None,
                   help="squeeze history before an instant [s] (default 2b/u_m; 0: steady)")
    p.add_argument("--floor", type=float, default=None,
                   help="load of separated samples, fraction of the largest (default 0.05)")
    p.add_argument("--roughness", type=float, default=None,
                   help=f"RMS roughness [m] (default {paper.ROUGHNESS:g}, Soleimanian et al. "
                        f"2020, Table 4)")
    p.add_argument("--nodes", type=int, default=None, help="grid nodes (default from the film)")


def _in_option_terms(error: ValueError, names) -> ValueError:
    """The analysis library quotes its arguments ('load'); the command line names options."""
    text = re.sub(r"'(\w+)'", lambda m: f"--{m[1].replace('_', '-')}" if m[1] in names else m[0],
                  str(error))
    return ValueError(text)


def _ehl(args) -> str:
    from .analysis import ehl as ea
    if args.command == "ehl":
        names = ("load", "velocity", "pressure_viscosity", "W", "U", "G", "radius", "e_reduced",
                 "viscosity", "roughness", "sliding_velocity", "peklenik")
        try:
            contact = ea.roller_contact(**{k: getattr(args, k) for k in names})
        except ValueError as error:
            raise _in_option_terms(error, names) from None
        result, summary = ea.solve_roller(contact, args.nodes)
        if args.plot:
            from .analysis.ehl_plots import plot_distribution
            summary["plot"] = str(plot_distribution(result, args.plot))
        text = ea.format_roller(summary) + (f"\nplot: {args.plot}" if args.plot else "")
        return json.dumps(summary, indent=2) if args.json else text
    names = ("instance", "feed", "times", "count", "window", "history", "floor", "roughness",
             "nodes")
    options = {k: getattr(args, k) for k in names if getattr(args, k) is not None}
    try:
        if "times" in options:
            options["times"] = ea.parse_times(options["times"])
        instants, files = ea.ehl_cycle(args.run_dir, args.out, **options)
    except ValueError as error:
        raise _in_option_terms(error, names) from None
    except FileNotFoundError as error:
        raise FileNotFoundError(f"{error} (is it the --out folder of guideway-fmu run?)") from None
    return ea.format_cycle(instants) + "\n" + "\n".join(str(f) for f in files)


def _feed_unit_args(sub) -> None:
    from .analysis.feed_unit import SWEEPS
    p = sub.add_parser("feed-unit", help="errors and stiffness of a four-slider ball-guide feed unit")
    p.add_argument("feed_unit", type=Path, help="feed-unit file (docs/feed-unit.md)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--sweep", choices=list(SWEEPS), default=None,
                   help="vary the load (fraction of the file's), the load point or the contact angle")
    p.add_argument("--range", nargs=2, type=float, metavar=("LOW", "HIGH"), default=None,
                   help="swept range (default: load 0 to 1, load point across the sliders' span, "
                        "contact angle 30 to 65 deg)")
    p.add_argument("--points", type=int, default=21, help="swept values (default 21)")
    p.add_argument("--plot", type=Path, default=None, help="PNG of the sweep")


def _feed_unit(args) -> str:
    from .analysis import feed_unit as fa
    case = fa.read_feed_unit(args.feed_unit)
    if args.sweep is None:
        if args.range is not None or args.plot is not None:
            raise ValueError("--range and --plot need --sweep")
        result = fa.analyse(case)
        return json.dumps(result, indent=2) if args.json else fa.format_result(result)
    try:
        values = fa.sweep_values(case, args.sweep, *(args.range or (None, None)), args.points)
    except ValueError as error:
        raise _in_option_terms(error, ("points", "sweep")) from None
    result = fa.sweep(case, args.sweep, values)
    if args.plot is not None:
        from .analysis.feed_unit_plots import plot_sweep
        result["plot"] = str(plot_sweep(result, args.plot))
    if args.json:
        return json.dumps(result, indent=2)
    return fa.format_sweep(result) + (f"\nplot: {result['plot']}" if args.plot else "")


def _wear(args) -> str:
    from .analysis import wear
    if not (math.isfinite(args.distance) and args.distance > 0):
        raise ValueError(f"--distance must be a running distance > 0 m, got {args.distance}")
    if args.points < 2:
        raise ValueError(f"--points must be >= 2, got {args.points}")
    case = wear.read_case(args.case)
    result = wear.analyse(case, args.distance, args.points)
    if args.plot is not None:
        from .analysis.wear_plots import plot_figures
        result["plot"] = str(plot_figures(case, result, args.plot))
    if args.json:
        return json.dumps(result, indent=2)
    return wear.format_result(result) + (f"\nplot: {result['plot']}" if args.plot else "")


def _host_env(fmu) -> int:
    from .fmu_build import host_env
    environment = host_env.host_environment()
    print(host_env.exports(environment), end="")
    if fmu is None:
        return 0
    run = host_env.check(None if fmu is True else fmu, environment)
    if run.status == 0:
        print(f"# check: {run.fmu.name} ran in a C host with this environment and exited 0",
              file=sys.stderr)
        return 0
    print(f"# check: {run.fmu.name} in a C host with this environment exited with status "
          f"{run.status}:\n{run.stderr}", file=sys.stderr)
    return 1


def _demo(args) -> str:
    """The demo's short summary and where its page is."""
    from .demo.job import run_demo
    s = run_demo(args.out, args.fmus, args.stop)
    lines = [f"stiffness at y = 0: {s['stiffness_at_y0_lubricated_N_per_m']:.4g} N/m lubricated, "
             f"{s['stiffness_at_y0_dry_N_per_m']:.4g} N/m dry"]
    for name, r in s["runs"].items():
        lines.append(f"{name}: {r['steps']} steps in {r['wall_time_s']:.2f} s, dominant "
                     f"frequency {r['dominant_frequency_above_1kHz_Hz']:.5g} Hz, upper roller load "
                     f"{r['F_upper_range_N'][0]:.4g} to {r['F_upper_range_N'][1]:.4g} N")
    for name, v in s["verify"].items():
        lines.append(f"verify {name}: RMS error of Contact.F_upper "
                     f"{v['rms_error_Contact.F_upper']:.2e} of its range")
    d = s["diagnose"]
    lines.append(f"diagnose: hidden {d['hidden_effect']}, named {d['missing_effect']}, held-out "
                 f"gap {d['gap_before']:.4g} -> {d['gap_after']:.4g}")
    w = s["sweep"]
    lines.append(f"sweep: {w['ok']} of {w['points']} points in {w['wall_time_s']:.1f} s")
    lines += [f"numbers: {args.out / 'summary.json'}",
              f"open {(args.out / 'index.html').resolve().as_uri()}"]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="guideway-fmu", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("build", help="build the FMUs and their README")
    p.add_argument("--out", type=Path, default=Path("fmus"), help="output folder (default fmus/)")
    p.add_argument("names", nargs="*", help="FMUs to build (default: all)")
    p = sub.add_parser("host-env", help="export lines of the environment a C host (libcosim, "
                       "commercial tools) needs to run the FMUs with this Python")
    p.add_argument("--check", nargs="?", type=Path, const=True, default=None, metavar="FMU",
                   help="also run an FMU (default: FeedKinematics) in a compiled C host with that "
                        "environment; the result goes to stderr, exit status 1 if it fails")
    p = sub.add_parser("run", help="co-simulate a scenario: results.csv, summary.json, plots")
    _scenario_args(p)
    p.add_argument("--out", type=Path, required=True, help="output folder")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--step-timeout", type=float, default=None, metavar="SECONDS",
                   help="end the run (exit status 124) when one FMU step takes longer than this "
                        "wall time [s]; overrides the scenario's experiment.step_timeout")
    p = sub.add_parser("sweep", help="parameter sweep of a scenario on Dask workers: results "
                       "table and plots (docs/sweep.md)")
    p.add_argument("sweep", type=Path, help="sweep file (docs/sweep.md)")
    p.add_argument("--out", type=Path, required=True, help="output folder")
    p.add_argument("--fmus", type=Path, default=None,
                   help="take every FMU by file name from this folder (shipped scenarios: "
                        "default ./fmus, built where missing)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, default=2,
                       help="worker processes of the local Dask cluster (default 2)")
    where.add_argument("--scheduler", default=None,
                       help="address of a running Dask scheduler to use instead")
    p.add_argument("--resume", action="store_true",
                   help="continue the sweep in --out: skip the points already in results.csv")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p = sub.add_parser("verify", help="co-simulation against the monolithic SciPy reference")
    _scenario_args(p)
    p.add_argument("--json", action="store_true", help="print the comparison as JSON")
    p = sub.add_parser("export-ssp", help="write the scenario as an SSP 1.0 package")
    _scenario_args(p)
    p.add_argument("out", type=Path, help="the .ssp file to write")
    p.add_argument("--no-bake", action="store_true",
                   help="pack the FMUs unchanged; the parameters are then only in the SSD's "
                        "bindings, which fmpy.ssp ignores (default: each FMU copy starts at its "
                        "instance's parameters)")
    p = sub.add_parser("export-fmu", help="pack the scenario's system into one FMI 2.0 "
                       "co-simulation FMU that runs our master inside (docs/export-fmu.md)")
    _scenario_args(p)
    p.add_argument("out", type=Path, help="the .fmu file to write")
    p = sub.add_parser("diagnose", help="find, name and close the gap between a measured run and the model")
    p.add_argument("run_dir", type=Path, help="measured run: rig.toml + data.csv (docs/measured-run.md)")
    p.add_argument("--out", type=Path, required=True, help="output folder: diagnosis.json, fit.csv, report.html, plots")
    p.add_argument("--fmus", type=Path, default=None, help="where to find or build the FMUs (default OUT/fmus)")
    p = sub.add_parser("demo", help="the main job: FMUs, stiffness curves, paper scenarios, "
                       "verification, diagnosis, a sweep; OUT/index.html shows it all")
    p.add_argument("--out", type=Path, default=Path("out/demo"))
    p.add_argument("--fmus", type=Path, default=Path("fmus"))
    p.add_argument("--stop", type=float, default=0.02, help="simulated time of each run [s]")
    sub.add_parser("scenarios", help="list the shipped scenarios")
    p = sub.add_parser("facts", help="print k, delta0, film and natural frequency of the rig of Soleimanian et al. (2020)")
    p.add_argument("--u", type=float, default=0.29, help="feed speed [m/s] (default 0.29)")
    _ehl_args(sub)
    p = sub.add_parser("modes", help="natural frequencies and mode shapes of a ball-guide carriage")
    p.add_argument("carriage", type=Path, help="carriage file (docs/ball-guides.md)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    _feed_unit_args(sub)
    p = sub.add_parser("ball-to-ball", help="ball-to-ball contact force and friction of two balls")
    p.add_argument("case", type=Path, help="case file (docs/ball-to-ball.md)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p = sub.add_parser("wear", help="raceway wear and preload loss of a ball guide over its running distance")
    p.add_argument("case", type=Path, help="case file (docs/wear.md)")
    p.add_argument("--distance", type=float, default=5000.0, help="running distance [m] (default 5000)")
    p.add_argument("--points", type=int, default=101, help="distances reported (default 101)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--plot", type=Path, default=None, help="PNG of the analogues of Figs. 14-17")
    args = parser.parse_args(argv)
    try:
        if args.command == "build":
            from .fmu_build.build import build
            for path in build(args.out, args.names or None):
                print(path)
        elif args.command == "host-env":
            return _host_env(args.check)
        elif args.command == "run":
            from .cosim.run import run
            result = run(_load(args), args.out, progress=not args.no_progress)
            print(json.dumps({k: v for k, v in result.summary().items() if k != "parameters"}, indent=2))
        elif args.command == "sweep":
            from .sweep import run, sweep_file
            spec = sweep_file.load(args.sweep, args.fmus)
            with run.dask_client(args.workers, args.scheduler) as client:
                outcome = run.run_sweep(spec, args.out, client, args.resume,
                                        progress=not args.no_progress)
            print(json.dumps(outcome.__dict__, indent=2))
        elif args.command == "verify":
            from .reference.verify import format_table, verify
            report = verify(_load(args))
            print(json.dumps(report, indent=2) if args.json else format_table(report))
        elif args.command == "export-ssp":
            from .cosim.ssp import export_ssp
            print(export_ssp(_load(args), args.out, bake=not args.no_bake))
        elif args.command == "export-fmu":
            from .cosim.export_fmu import export_fmu
            print(export_fmu(_load(args), args.out))
        elif args.command == "diagnose":
            from .diagnose.workflow import diagnose
            diagnosis = diagnose(args.run_dir, args.out, fmu_dir=args.fmus)
            print(json.dumps({k: v for k, v in diagnosis.items() if k != "candidates"}, indent=2))
        elif args.command == "demo":
            if not args.stop > 0:
                raise ValueError(f"need --stop > 0, got {args.stop}")
            print(_demo(args))
        elif args.command == "scenarios":
            from . import scenarios
            print("\n".join(scenarios.names()))
        elif args.command == "modes":
            from .analysis import carriage_modes
            result = carriage_modes.analyse(carriage_modes.read_carriage(args.carriage))
            print(json.dumps(result, indent=2) if args.json else carriage_modes.format_modes(result))
        elif args.command == "facts":
            from .analysis.soleimanian2020 import rig_facts
            print(json.dumps(rig_facts(args.u), indent=2))
        elif args.command in ("ehl", "ehl-cycle"):
            print(_ehl(args))
        elif args.command == "feed-unit":
            print(_feed_unit(args))
        elif args.command == "ball-to-ball":
            from .analysis import ball_to_ball
            case = ball_to_ball.read_case(args.case)
            result = ball_to_ball.analyse(case, args.case)
            print(json.dumps(result, indent=2) if args.json else ball_to_ball.format_result(result))
        elif args.command == "wear":
            print(_wear(args))
    except (ValueError, OSError, KeyError, RuntimeError) as exc:  # incl. SimulationError,
        # EHLConvergenceError, files that cannot be read or written
        signum = getattr(exc, "signal", None)  # a run stopped by SIGINT or SIGTERM
        print(f"guideway-fmu {args.command}: {'error: ' if signum is None else ''}{exc}",
              file=sys.stderr)
        return 2 if signum is None else 128 + signum  # the shell's status for a signal
    except KeyboardInterrupt:  # Ctrl-C outside a run
        print(f"guideway-fmu {args.command}: interrupted", file=sys.stderr)
        return 128 + signal.SIGINT
    return 0


def entry() -> None:
    """The ``guideway-fmu`` command: :func:`main`, then the process ends without the
    interpreter's finalisation (process.exit_without_finalising)."""
    exit_without_finalising(main())


if __name__ == "__main__":
    entry()
