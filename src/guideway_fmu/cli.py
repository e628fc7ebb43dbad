"""The ``guideway-fmu`` command line: a table of subcommands and one error boundary.

Each subcommand is a :class:`Command` in :data:`COMMANDS`: its name, one line of help, a
function that adds its arguments to its parser and a function that runs it and returns the
exit status. The library is imported inside the run functions, after what can be checked
without it (a path that does not exist, a scenario's name), so ``--help`` and those errors do
not pay for numpy, fmpy or dask.

Errors: the library raises named errors (ValueError and its subclasses for bad input,
OSError for files, RuntimeError for a computation that failed) and quotes the arguments it
was given as ``'name'``. :func:`main` is the one boundary: it words those names as the
command's options (``'workers'`` becomes ``--workers``), prints one line and returns 2; a run
stopped by a signal returns the shell's status for it. Anything else is a defect and keeps
its traceback.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import signal
import sys
import textwrap
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from .fmu_build import EDITIONS

#: errors the library raises about its input or a failed computation: exit status 2
NAMED_ERRORS = (ValueError, OSError, RuntimeError)


@dataclass(frozen=True)
class Command:
    """One subcommand: ``arguments(parser)`` declares its arguments, ``run(args)`` does the
    work and returns the exit status; ``options`` rewords the library's phrases about its
    arguments (besides every ``'dest'`` -> ``--dest``)."""

    name: str
    help: str
    arguments: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], int]
    options: tuple[tuple[str, str], ...] = ()


def _print_json(value) -> None:
    print(json.dumps(value, indent=2))


def _ratio(text: str) -> float:
    """A number or a fraction such as 1/3 (argparse type)."""
    try:
        return float(Fraction(text))
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"expected a number or a fraction like 1/3, got {text!r}")


def _existing(path: Path, what: str) -> Path:
    """``path``, which must exist: checked before the library loads, so a mistyped name is told
    at once; FileNotFoundError ``PATH: cannot read: no such WHAT`` otherwise."""
    if not path.exists():
        raise FileNotFoundError(f"{path}: cannot read: no such {what}")
    return path


def _print_result(args, result: dict, text) -> int:
    """Print an analysis' ``result`` as JSON with ``--json``, else as ``text(result)`` and the
    plot it drew; exit status 0."""
    print(json.dumps(result, indent=2) if args.json else
          text(result) + (f"\nplot: {result['plot']}" if result.get("plot") else ""))
    return 0


def _json_flag(p) -> None:
    p.add_argument("--json", action="store_true", help="print the result as JSON")


def _progress_flag(p) -> None:
    p.add_argument("--no-progress", action="store_true",
                   help="no progress bar (there is none either when stderr is not a terminal)")


def _progress(args) -> bool:
    """Whether the command shows its progress bar: on stderr when that is a terminal, unless
    --no-progress."""
    return not args.no_progress and sys.stderr.isatty()


def _written(folder: Path, since: float) -> list[str]:
    """The files under ``folder`` modified since ``since`` (time.time() at the command's start,
    less the file system's timestamp granularity), sorted."""
    return sorted(str(p) for p in folder.rglob("*") if p.is_file() and p.stat().st_mtime >= since)




def _edition_option(p, what: str) -> None:
    p.add_argument("--edition", choices=EDITIONS, default="python",
                   help=f"{what}: python (pythonfmu, runs in the host's Python; the default) or "
                        "native (compiled C, no Python inside, for the components that have a "
                        "native edition; the others stay python)")


def _fmus_option(p, default_text: str) -> None:
    p.add_argument("--fmus", type=Path, default=None,
                   help=f"take every FMU by file name from this folder ({default_text})")
    _edition_option(p, "the FMU cache's edition, without --fmus")


# -- building and hosts ----------------------------------------------------------------------
def _build_arguments(p) -> None:
    p.add_argument("--out", type=Path, default=Path("fmus"), help="output folder (default fmus/)")
    p.add_argument("names", nargs="*", help="FMUs to build (default: all)")
    _edition_option(p, "how the FMUs run, under the same file names")
    p.add_argument("--cross", action="store_true",
                   help="native FMUs carry win64 and darwin64 binaries too, cross-compiled with "
                        "zig (pip install 'guideway-fmu[cross]')")


def _build(args) -> int:
    from .fmu_build.build import build
    if args.cross and args.edition != "native":
        raise ValueError("--cross cross-compiles native FMUs: give --edition native with it")
    for path in build(args.out, args.names or None, args.edition, args.cross):
        print(path)
    return 0


def _host_env_arguments(p) -> None:
    p.add_argument("--check", nargs="?", type=Path, const=True, default=None, metavar="FMU",
                   help="also run an FMU (default: FeedKinematics) in a compiled C host with that "
                        "environment; the result goes to stderr, exit status 1 if it fails")


def _host_env(args) -> int:
    from .fmu_build import host_env
    environment = host_env.host_environment()
    print(host_env.exports(environment), end="")
    if args.check is None:
        return 0
    run = host_env.check(None if args.check is True else args.check, environment)
    if run.status == 0:
        print(f"# check: {run.fmu.name} ran in a C host with this environment and exited 0",
              file=sys.stderr)
        return 0
    print(f"# check: {run.fmu.name} in a C host with this environment exited with status "
          f"{run.status}:\n{run.stderr}", file=sys.stderr)
    return 1


# -- scenarios: run, verify, export ----------------------------------------------------------
def _scenario_arguments(p) -> None:
    p.add_argument("scenario", help="scenario TOML file, or the name of a shipped scenario "
                   "(guideway-fmu scenarios lists them)")
    _fmus_option(p, "shipped scenarios: default the FMU cache, built where missing; others: "
                    "the scenario's paths")
    p.add_argument("--stop", type=float, default=None, help="override the stop time [s]")
    p.add_argument("--step", type=float, default=None, help="override the macro step [s]")
    p.add_argument("--algorithm", default=None,
                   help="override the co-simulation algorithm (jacobi, gauss-seidel, "
                        "stabilised, or a registered one)")


def _load(args):
    """The scenario of ``args`` with the experiment's overrides, checked."""
    from . import scenarios
    path = scenarios.find(args.scenario)  # a wrong name is told before the library loads
    from .cosim import system
    s = system.load(path, scenarios.fmu_folder(path, args.fmus, args.edition))
    changes = {k: getattr(args, k, None) for k in ("stop", "step", "algorithm", "step_timeout")
               if getattr(args, k, None) is not None}
    return s.with_changes(**changes) if changes else s


def _run_arguments(p) -> None:
    _scenario_arguments(p)
    p.add_argument("--out", type=Path, required=True, help="output folder")
    _progress_flag(p)
    p.add_argument("--step-timeout", type=float, default=None, metavar="SECONDS",
                   help="end the run (exit status 124) when one FMI call (a step, the "
                        "initialisation, ...) takes longer than this wall time [s]; overrides "
                        "the scenario's experiment.step_timeout")


def _run(args) -> int:
    scenario = _load(args)
    from .cosim.run import run
    result = run(scenario, args.out, progress=_progress(args))
    files = json.loads((args.out / "summary.json").read_text())["files"]
    _print_json({**{k: v for k, v in result.summary().items() if k != "parameters"},
                 "files": [str(args.out / name) for name in files]})
    return 0


def _verify_arguments(p) -> None:
    _scenario_arguments(p)
    _json_flag(p)
    _progress_flag(p)


def _verify(args) -> int:
    """Exit status 1 when the verdict is FAILED (the report printed all the same)."""
    scenario = _load(args)
    from .reference.verify import format_table, verify
    report = verify(scenario, progress=_progress(args))
    print(json.dumps(report, indent=2) if args.json else format_table(report))
    if not report["passed"]:
        print(f"guideway-fmu verify: {report['scenario']} FAILED verification against the "
              f"monolithic reference ({report['criterion']} criterion; the report above says "
              "where)", file=sys.stderr)
        return 1
    return 0


def _export_ssp_arguments(p) -> None:
    _scenario_arguments(p)
    p.add_argument("out", type=Path, help="the .ssp file to write")
    p.add_argument("--no-bake", action="store_true",
                   help="pack the FMUs unchanged; the parameters are then only in the SSD's "
                        "bindings, which fmpy.ssp ignores (default: each FMU copy starts at its "
                        "instance's parameters)")


def _export_ssp(args) -> int:
    """The package's path; a warning on stderr for a stiff loop an SSP host cannot follow."""
    scenario = _load(args)
    from .cosim.ssp import explicit_coupling_warning, export_ssp
    print(export_ssp(scenario, args.out, bake=not args.no_bake))
    warning = explicit_coupling_warning(scenario)
    if warning:
        print(textwrap.fill(warning, 100), file=sys.stderr)
    return 0


def _export_fmu_arguments(p) -> None:
    _scenario_arguments(p)
    p.add_argument("out", type=Path, help="the .fmu file to write")


def _export_fmu(args) -> int:
    scenario = _load(args)
    from .cosim.export_fmu import export_fmu
    print(export_fmu(scenario, args.out))
    return 0


def _scenarios(args) -> int:
    from . import scenarios
    print("\n".join(scenarios.names()))
    return 0


def _examples_arguments(p) -> None:
    p.add_argument("dir", type=Path, help="folder to copy them into (made if missing; a file "
                   "already there stops the copy before it starts)")


def _examples(args) -> int:
    from . import examples
    for path in examples.copy_out(args.dir):
        print(path)
    return 0


# -- sweeps, diagnosis, the demo -------------------------------------------------------------
def _sweep_arguments(p) -> None:
    p.add_argument("sweep", type=Path, help="sweep file (docs/sweep.md)")
    p.add_argument("--out", type=Path, required=True, help="output folder")
    _fmus_option(p, "shipped scenarios: default the FMU cache, built where missing")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, default=2,
                       help="worker processes of the local Dask cluster (default 2)")
    where.add_argument("--scheduler", default=None,
                       help="address of a running Dask scheduler to use instead")
    p.add_argument("--resume", action="store_true",
                   help="continue the sweep in --out: skip the points already in results.csv")
    _progress_flag(p)


def _sweep(args) -> int:
    _existing(args.sweep, "sweep file")
    from .sweep import sweep_file
    spec = sweep_file.load(args.sweep, args.fmus, args.edition)  # told before dask loads
    from .sweep import run
    with run.dask_client(args.workers, args.scheduler) as client:
        outcome = run.run_sweep(spec, args.out, client, args.resume, progress=_progress(args))
    _print_json(outcome.__dict__)
    if outcome.failed:
        raise RuntimeError(f"{outcome.failed} of the {outcome.points} points failed; their errors "
                           f"are in {outcome.files[0]} (rerun them with 'resume')")
    return 0


def _diagnose_arguments(p) -> None:
    p.add_argument("run_dir", type=Path, help="measured run: rig.toml + data.csv (docs/measured-run.md)")
    p.add_argument("--out", type=Path, required=True,
                   help="output folder: diagnosis.json, fit.csv, report.html, plots")
    p.add_argument("--fmus", type=Path, default=None,
                   help="where to find or build the FMUs (default: the FMU cache)")
    _progress_flag(p)


def _diagnose(args) -> int:
    _existing(args.run_dir, "measured-run folder (rig.toml and data.csv)")
    import time

    from .diagnose.workflow import diagnose
    since = time.time() - 1.0
    diagnosis = diagnose(args.run_dir, args.out, fmu_dir=args.fmus, progress=_progress(args))
    _print_json({**{k: v for k, v in diagnosis.items() if k != "candidates"},
                 "files": _written(args.out, since)})
    return 0


def _demo_arguments(p) -> None:
    p.add_argument("--out", type=Path, default=Path("out/demo"))
    p.add_argument("--fmus", type=Path, default=None,
                   help="take the FMUs from this folder, built where missing or built from other "
                        "code (default: the FMU cache)")
    p.add_argument("--stop", type=float, default=0.02, help="simulated time of each run [s]")
    _progress_flag(p)


def _demo(args) -> int:
    """The demo's short summary, the files it wrote and where its page is."""
    from .demo.job import run_demo
    s = run_demo(args.out, args.fmus, args.stop, progress=_progress(args))
    lines = [(f"stiffness at y = 0: {s['stiffness_at_y0_lubricated_N_per_m']:.4g} N/m lubricated, "
             f"{s['stiffness_at_y0_dry_N_per_m']:.4g} N/m dry")]
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
    lines += [f"files: {len(s['files'])} in {args.out}, listed in summary.json",
              f"numbers: {args.out / 'summary.json'}",
              f"open {(args.out / 'index.html').resolve().as_uri()}"]
    print("\n".join(lines))
    return 0


# -- analyses --------------------------------------------------------------------------------
def _facts_arguments(p) -> None:
    from .physics.papers.soleimanian2020 import RIG_SPEED
    p.add_argument("--u", type=float, default=RIG_SPEED,
                   help=f"feed speed [m/s] (default {RIG_SPEED:g}, the rig's)")


def _facts(args) -> int:
    from .analysis.soleimanian2020 import rig_facts
    _print_json(rig_facts(args.u))
    return 0


def _ehl_arguments(p) -> None:
    from .physics.papers import soleimanian2020 as paper
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
                       ("peklenik", ("Patir-Cheng average flow with this roughness orientation "
                                    "gamma: 1 isotropic, 3/6/9 along the motion, 1/3/1/6/1/9 "
                                    "across (default: Soleimanian et al. 2020, eq. 18, no flow factors)"))):
        p.add_argument(f"--{name}", type=_ratio if name == "peklenik" else float, default=None,
                       help=unit)
    p.add_argument("--nodes", type=int, default=None, help="grid nodes (default from the film)")
    _json_flag(p)
    p.add_argument("--plot", type=Path, default=None, help="PNG of pressure and film against x/b")


_EHL_INPUTS = ("load", "velocity", "pressure_viscosity", "W", "U", "G", "radius", "e_reduced",
               "viscosity", "roughness", "sliding_velocity", "peklenik")


def _ehl(args) -> int:
    from .analysis import ehl as ea
    contact = ea.roller_contact(**{k: getattr(args, k) for k in _EHL_INPUTS})
    result, summary = ea.solve_roller(contact, args.nodes)
    if args.plot:
        from .analysis.ehl_plots import plot_distribution
        summary["plot"] = str(plot_distribution(result, args.plot))
    text = ea.format_roller(summary) + (f"\nplot: {args.plot}" if args.plot else "")
    print(json.dumps(summary, indent=2) if args.json else text)
    return 0


def _ehl_cycle_arguments(p) -> None:
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
    from .physics.papers.soleimanian2020 import ROUGHNESS
    p.add_argument("--roughness", type=float, default=None,
                   help=f"RMS roughness [m] (default {ROUGHNESS:g}, Soleimanian et al. 2020, "
                        "Table 4)")
    p.add_argument("--nodes", type=int, default=None, help="grid nodes (default from the film)")
    _progress_flag(p)


_EHL_CYCLE_OPTIONS = ("instance", "feed", "times", "count", "window", "history", "floor",
                      "roughness", "nodes")


def _ehl_cycle(args) -> int:
    """Exit status 2 when an instant could not be solved, after writing the others."""
    _existing(args.run_dir, "run folder")
    from .analysis import ehl as ea
    options = {k: getattr(args, k) for k in _EHL_CYCLE_OPTIONS if getattr(args, k) is not None}
    if "times" in options:
        options["times"] = ea.parse_times(options["times"])
    try:
        instants, files = ea.ehl_cycle(args.run_dir, args.out, progress=_progress(args),
                                       **options)
    except FileNotFoundError as error:
        raise FileNotFoundError(f"{error} (is it the --out folder of guideway-fmu run?)") from None
    print(ea.format_cycle(instants) + "\n" + "\n".join(str(f) for f in files))
    failed = [i.row for i in instants if i.row["status"] == "failed"]
    if failed:
        raise RuntimeError(
            f"{len(failed)} of {len(instants)} instants not solved: " + ", ".join(
                f"{r['label']} (t = {r['time']:.6g} s)" for r in failed)
            + f"; their errors are in {files[1]}")
    return 0


def _modes_arguments(p) -> None:
    p.add_argument("carriage", type=Path, help="carriage file (docs/ball-guides.md)")
    _json_flag(p)
    p.add_argument("--plot", type=Path, default=None, metavar="P.png",
                   help="PNG of the mode shapes: for each mode, every ball's approach along the "
                        "carriage, both rows, with the frequency and where its energy is")


def _modes(args) -> int:
    _existing(args.carriage, "carriage file")
    from .analysis import carriage_modes
    result = carriage_modes.analyse(carriage_modes.read_carriage(args.carriage))
    if args.plot is not None:
        from .analysis.carriage_modes_plots import plot_modes
        result["plot"] = str(plot_modes(result, args.plot))
    return _print_result(args, result, carriage_modes.format_modes)


def _feed_unit_arguments(p) -> None:
    p.add_argument("feed_unit", type=Path, help="feed-unit file (docs/feed-unit.md)")
    _json_flag(p)
    p.add_argument("--sweep", default=None, metavar="QUANTITY",
                   help="vary load (a fraction of the file's load), point_x or point_y (the load "
                        "point) or contact_angle")
    p.add_argument("--range", nargs=2, type=float, metavar=("LOW", "HIGH"), default=None,
                   help="swept range (default: load 0 to 1, load point across the sliders' span, "
                        "contact angle 30 to 65 deg)")
    p.add_argument("--points", type=int, default=21, help="swept values (default 21)")
    p.add_argument("--plot", type=Path, default=None, help="PNG of the sweep")


def _feed_unit(args) -> int:
    if args.sweep is None and (args.range is not None or args.plot is not None):
        raise ValueError("--range and --plot need --sweep")
    _existing(args.feed_unit, "feed-unit file")
    from .analysis import feed_unit as fa
    case = fa.read_feed_unit(args.feed_unit)
    if args.sweep is None:
        result = fa.analyse(case)
        return _print_result(args, result, fa.format_result)
    values = fa.sweep_values(case, args.sweep, *(args.range or (None, None)), args.points)
    result = fa.sweep(case, args.sweep, values)
    if args.plot is not None:
        from .analysis.feed_unit_plots import plot_sweep
        result["plot"] = str(plot_sweep(result, args.plot))
    return _print_result(args, result, fa.format_sweep)


def _ball_to_ball_arguments(p) -> None:
    p.add_argument("case", type=Path, help="case file (docs/ball-to-ball.md)")
    _json_flag(p)
    p.add_argument("--plot", type=Path, default=None, metavar="P.png",
                   help="PNG of the ball-to-ball contact force and the friction losses of both "
                        "models against the side ratio rho (the case's deviations and load "
                        "held, the case marked; cf. the paper's Fig. 8)")
    _progress_flag(p)


def _ball_to_ball(args) -> int:
    _existing(args.case, "ball-to-ball case file")
    from .analysis import ball_to_ball
    case = ball_to_ball.read_case(args.case)
    result = ball_to_ball.analyse(case, args.case, progress=_progress(args))
    if args.plot is not None:
        from .analysis.ball_to_ball_plots import plot_side_ratio
        sweep = ball_to_ball.side_ratio_sweep(case, progress=_progress(args))
        result["plot"] = str(plot_side_ratio(sweep, result, case.side_ratio, args.plot))
    return _print_result(args, result, ball_to_ball.format_result)


def _wear_arguments(p) -> None:
    p.add_argument("case", type=Path, help="case file (docs/wear.md)")
    p.add_argument("--distance", type=float, default=5000.0, help="running distance [m] (default 5000)")
    p.add_argument("--points", type=int, default=101, help="distances reported (default 101)")
    _json_flag(p)
    p.add_argument("--plot", type=Path, default=None, help="PNG of the analogues of Figs. 14-17")


def _wear(args) -> int:
    _existing(args.case, "wear case file")
    from .analysis import wear
    case = wear.read_case(args.case)
    result = wear.analyse(case, args.distance, args.points)
    if args.plot is not None:
        from .analysis.wear_plots import plot_figures
        result["plot"] = str(plot_figures(case, result, args.plot))
    return _print_result(args, result, wear.format_result)


def _nothing(p) -> None:
    """A command without arguments."""


COMMANDS = (
    Command("build", "build the FMUs and their README", _build_arguments, _build),
    Command("host-env", "export lines of the environment a C host (libcosim, commercial tools) "
            "needs to run the FMUs with this Python", _host_env_arguments, _host_env),
    Command("scenarios", "list the shipped scenarios", _nothing, _scenarios),
    Command("examples", "copy the example inputs (the paper commands' cases, a measured run, "
            "the shipped scenarios) into a folder and list them", _examples_arguments,
            _examples),
    Command("run", "co-simulate a scenario: results.csv, summary.json, plots", _run_arguments, _run),
    Command("sweep", "parameter sweep of a scenario on Dask workers: results table and plots "
            "(docs/sweep.md)", _sweep_arguments, _sweep),
    Command("verify", "co-simulation against the monolithic SciPy reference", _verify_arguments,
            _verify),
    Command("export-ssp", "write the scenario as an SSP 1.0 package", _export_ssp_arguments,
            _export_ssp, options=(("'bake' False", "--no-bake"),)),
    Command("export-fmu", "pack the scenario's system into one FMI 2.0 co-simulation FMU that "
            "runs our master inside (docs/export-fmu.md)", _export_fmu_arguments, _export_fmu),
    Command("diagnose", "find, name and close the gap between a measured run and the model",
            _diagnose_arguments, _diagnose),
    Command("demo", "the main job: FMUs, stiffness curves, paper scenarios, verification, "
            "diagnosis, a sweep; OUT/index.html shows it all", _demo_arguments, _demo),
    Command("facts", "print k, delta0, film and natural frequency of the rig of Soleimanian et al. "
            "(2020)", _facts_arguments, _facts),
    Command("ehl", "numerical mixed-EHL solution of one roller contact", _ehl_arguments, _ehl),
    Command("ehl-cycle", "numerical EHL of one upper roller at instants of a run",
            _ehl_cycle_arguments, _ehl_cycle),
    Command("modes", "natural frequencies and mode shapes of a ball-guide carriage",
            _modes_arguments, _modes),
    Command("feed-unit", "errors and stiffness of a four-slider ball-guide feed unit",
            _feed_unit_arguments, _feed_unit),
    Command("ball-to-ball", "ball-to-ball contact force and friction of two balls",
            _ball_to_ball_arguments, _ball_to_ball),
    Command("wear", "raceway wear and preload loss of a ball guide over its running distance",
            _wear_arguments, _wear),
)


def _version() -> str:
    try:
        return version("guideway_fmu")
    except PackageNotFoundError:  # run from a source tree that is not installed
        return "unknown (not installed)"


def parsers() -> tuple[argparse.ArgumentParser, dict[str, argparse.ArgumentParser]]:
    """The argument parser of the command line and each command's own, by name."""
    top = argparse.ArgumentParser(
        prog="guideway-fmu", description="FMI co-simulation of linear guideways: "
        f"{' | '.join(c.name for c in COMMANDS)}; 'guideway-fmu COMMAND --help' says more.")
    top.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = top.add_subparsers(dest="command", required=True, metavar="COMMAND")
    own = {c.name: sub.add_parser(c.name, help=c.help, description=c.help) for c in COMMANDS}
    for command in COMMANDS:
        command.arguments(own[command.name])
    return top, own


def in_option_terms(message: str, command: Command, options: argparse.ArgumentParser) -> str:
    """``message`` with each quoted argument name of the library (``'step_timeout'``) written
    as the option of ``command`` that sets it (``--step-timeout``) and the command's own
    phrases reworded. A quoted key of an input file (``key 'points'``) is left as it is."""
    for phrase, option in command.options:
        message = message.replace(phrase, option)
    names = {action.dest: max(action.option_strings, key=len)
             for action in options._actions if action.option_strings}
    return re.sub(r"(?<!key )'(\w+)'", lambda m: names.get(m[1], m[0]), message)


def main(argv: list[str] | None = None) -> int:
    """Parse ``argv``, run the command and return its exit status: 2 for a named error of the
    library (one line on stderr), 128 + the signal for a run stopped by SIGINT or SIGTERM."""
    top, own = parsers()
    args = top.parse_args(argv)
    command = next(c for c in COMMANDS if c.name == args.command)
    try:
        return command.run(args)
    except NAMED_ERRORS as exc:
        signum = getattr(exc, "signal", None)  # a run stopped by SIGINT or SIGTERM
        if signum is not None:
            print(f"guideway-fmu {command.name}: {exc}", file=sys.stderr)
            return 128 + signum  # the shell's status for a signal
        print(f"guideway-fmu {command.name}: error: "
              f"{in_option_terms(str(exc), command, own[command.name])}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # Ctrl-C outside a run
        print(f"guideway-fmu {command.name}: interrupted", file=sys.stderr)
        return 128 + signal.SIGINT


#: thread pools of the numerical libraries, one thread each unless the user set them: the
#: matrices here are small, so the threads only wait on each other and on the sweep's other
#: workers (diagnose on the bundled measured run: 1.5x the CPU time and 1.15x the wall time
#: with the default pools on an idle 2-core machine, about 4x the wall time on a busy one)
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def entry() -> None:
    """The ``guideway-fmu`` command: :func:`main` with one-thread numerical libraries
    (:data:`THREAD_VARIABLES`, set before numpy loads; child processes inherit them), then the
    process ends without the interpreter's finalisation
    (cosim.interrupts.exit_without_finalising) once fmpy, through which FMUs load, is loaded;
    a command that loaded none (an error told early) exits as usual, without loading cosim to
    do so."""
    for variable in THREAD_VARIABLES:
        os.environ.setdefault(variable, "1")
    status = main()
    if "fmpy" not in sys.modules:
        sys.exit(status)
    from .cosim.interrupts import exit_without_finalising
    exit_without_finalising(status)


if __name__ == "__main__":
    entry()
