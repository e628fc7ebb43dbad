"""Explicit (full numerical) EHL analyses: one roller contact given on the command line
(``guideway-fmu ehl``) and the passive analysis of a recorded co-simulation at chosen instants
(``guideway-fmu ehl-cycle``, Soleimanian et al. (2020) Figs. 32-35). SI units unless a name says otherwise.

Why the cycle analysis is a post-processor and not an FMU
---------------------------------------------------------
In Soleimanian et al. (2020) the dynamics runs with an analytical film ("implicit" tribology) and the numerical
EHL solution is applied afterwards to the recorded contact load ("explicit and passive"). Nothing
flows back from the detailed contact to the dynamics, so an FMU in the loop would compute the
same numbers while the co-simulation runs. It would also cost far more: one solution takes
0.1-1 s against a 2 us macro step, so solving at every step of a 0.2 s cycle (1e5 steps) costs
about 1e5 times what solving at the ~10 instants of interest does; even the squeeze history,
marched over the recorded samples before each instant, touches only a few hundred of them.
A post-processor reads results.csv and summary.json of any run, can be repeated with other
surfaces or grids without simulating again, and keeps the FMUs light.

What is solved at an instant
----------------------------
One upper roller: load per unit length w' = F_upper / roller_length, radius, E', mu0 and alpha
from the contact instance's resolved parameters in summary.json, surface from Table 4 (sigma =
0.45 um by default). The rail moves at the feed velocity u and the roller rolls on it and on the
carriage raceway at rest, so the mean surface velocity of each contact, the entrainment
velocity, is u_m = |u| / 2 (pure rolling, no sliding).

The squeeze term matters when the load changes within the time the lubricant takes to cross the
contact, t_c = 2 b / u_m (b the Hertz half-width): at 9000 N / 9000 Hz the load of an upper
roller swings between 0 and ~600 N every ~150 us while t_c ~ 0.7 ms, a squeeze-dominated film.
An instant is therefore solved as a transient (:func:`~.physics.ehl.solve_transient`) over the
recorded samples of the preceding ``history`` (default t_c at the instant, at most
MAX_HISTORY_SAMPLES samples), started from the steady state at the first of them; the start's
error decays over about t_c (at 9000 N / 9000 Hz, smooth, the central film at the load peak
changes by 3 % between 0.64 and 1.28 ms of history, by 13 % between 0.32 and 0.64 ms; the
default grid of a march holds the default domains of its lightest and heaviest contact at the
finer spacing, since a transient keeps the grid of its first state). It is solved steady
when load and entrainment velocity stay within QUASI_STEADY of their values over that history
(the squeeze term is then negligible) or when nothing was recorded before it. A steady film
needs u_m > 0; at u = 0 only the transient applies (pure squeeze of the film entrained before).
Instants whose histories overlap share one transient march.

A roller that separates (recorded load 0) carries nothing and has no EHL solution: over the
history such samples, and any below it, are raised to ``floor`` times the largest load of the
march (default 5 %), a lightly loaded contact whose film may grow. This is a modelling choice the
co-simulation cannot inform (it does not track the gap of a separated roller); at 9000 N /
9000 Hz (0.32 ms of history) a floor of 2 % instead of 5 % thickens the peak film by ~15 %.
An instant at zero load is reported as separated, one below the floor as floored.

Each row compares the numerical central film h_c with the film of the dynamics recorded at that
instant, h_analytical (``<instance>.h_upper``): film_ratio = h_analytical / h_c. The analytical
film of ContactEHL (eqs. 4-5) takes the feed velocity u in its U, as published, where the
numerical solution takes u_m = u / 2; the ratio includes that convention.
"""
from __future__ import annotations

import csv
import json
import math
import string
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from tqdm import tqdm

from .ehl_plots import plot_distribution, plot_load_history
from ..cosim.run import read as read_results
from ..physics import checks
from ..physics.papers import soleimanian2020 as paper
from ..physics.roller_guide.ehl import (EHLConvergenceError, EHLResult, LineContactEHL,
                                        flow_factors, pan_hamrock, solve_steady, solve_transient,
                                        solver)

QUASI_STEADY = 0.01  # relative change of load and u_m over the history below which steady holds
DEFAULT_FLOOR = 0.05  # separated samples: fraction of the march's largest load
MAX_HISTORY_SAMPLES = 500  # cap of the default history (cost ~0.1-0.3 s per sample)
CONTACT_KEYS = ("roller_length", "roller_radius", "e_reduced", "viscosity", "pressure_viscosity")

UNITS = {"time": "s", "load": "N", "load_per_length": "N/m", "u": "m/s", "u_m": "m/s",
         "history": "s", "transit_time": "s", "H_c": "1", "h_c": "m", "H_min": "1", "h_min": "m",
         "P_max": "1", "p_max": "Pa", "asperity_load_ratio": "1", "friction_coefficient": "1",
         "h_analytical": "m", "film_ratio": "1", "h_c_pan_hamrock": "m"}
COLUMNS = ("label", "time", "load", "load_per_length", "u", "u_m", "status", "method", "history",
           "transit_time", "floored", "H_c", "h_c", "H_min", "h_min", "P_max", "p_max",
           "asperity_load_ratio", "friction_coefficient", "nodes", "iterations", "converged",
           "h_analytical", "film_ratio", "h_c_pan_hamrock", "error")


def _quoted(name: str) -> str:
    """An argument's name as errors quote it (the command line turns it into its option)."""
    return f"'{name}'"


_CONTACT_CHECKS = {  # checks of a roller contact's arguments (a steady film needs u_m > 0)
    "load": checks.positive, "velocity": checks.positive, "pressure_viscosity": checks.non_negative,
    "W": checks.positive, "U": checks.positive, "G": checks.non_negative,
    "radius": checks.positive, "e_reduced": checks.positive, "viscosity": checks.positive,
    "roughness": checks.non_negative, "sliding_velocity": checks.finite,
    "peklenik": flow_factors.check_peklenik}


# --- guideway-fmu ehl ------------------------------------------------------------------------

def roller_contact(*, load=None, velocity=None, pressure_viscosity=None, W=None, U=None, G=None,
                  radius=None, e_reduced=None, viscosity=None, roughness=None,
                  sliding_velocity=None, peklenik=None) -> LineContactEHL:
    """The line contact of one roller from either dimensional input (load w' [N/m] and
    entrainment velocity u_m [m/s] required, alpha [1/Pa] optional) or Hamrock's W, U, G (all
    three). radius [m] (default Soleimanian et al.'s roller on a flat raceway), e_reduced [Pa],
    viscosity [Pa s], roughness [m], sliding_velocity [m/s] and peklenik (the average flow
    model's roughness orientation, which switches that model on; needs roughness) apply to
    both; None leaves LineContactEHL's default. Raises ValueError naming the arguments of a
    mixed or incomplete set."""
    for name, value in locals().copy().items():
        if value is not None:
            _CONTACT_CHECKS[name](_quoted(name), value)
    dimensional = {"load": load, "velocity": velocity, "pressure_viscosity": pressure_viscosity}
    groups = {"W": W, "U": U, "G": G}
    given_d = [_quoted(k) for k, v in dimensional.items() if v is not None]
    given_g = [_quoted(k) for k, v in groups.items() if v is not None]
    if given_d and given_g:
        raise ValueError(f"give dimensional input or W, U, G, not both: {', '.join(given_d)} "
                         f"mixed with {', '.join(given_g)}")
    if not given_d and not given_g:
        raise ValueError("no contact given: pass 'load' and 'velocity' (dimensional) or "
                         "'W', 'U' and 'G' (dimensionless)")
    common = {k: v for k, v in {"e_reduced": e_reduced, "viscosity": viscosity,
                                "roughness": roughness, "sliding_velocity": sliding_velocity}.items()
              if v is not None}
    if peklenik is not None:
        if not roughness:
            raise ValueError("'peklenik' selects the average flow model of rough surfaces; "
                             "give 'roughness' > 0 with it")
        common.update(peklenik=flow_factors.check_peklenik("'peklenik'", peklenik),
                      average_flow=True)
    radius = paper.ROLLER_RADIUS if radius is None else radius
    if given_g:
        missing = [_quoted(k) for k, v in groups.items() if v is None]
        if missing:
            raise ValueError(f"dimensionless input needs 'W', 'U' and 'G'; missing {', '.join(missing)}")
        return LineContactEHL.from_dimensionless(W, U, G, radius=radius, **common)
    missing = [_quoted(k) for k in ("load", "velocity") if dimensional[k] is None]
    if missing:
        raise ValueError(f"dimensional input needs 'load' and 'velocity'; missing {', '.join(missing)}")
    if pressure_viscosity is not None:
        common["pressure_viscosity"] = pressure_viscosity
    contact = LineContactEHL(load=load, radius=radius, entrainment_velocity=velocity, **common)
    contact.validate()
    return contact


def solve_roller(contact: LineContactEHL, nodes: int | None = None) -> tuple[EHLResult, dict]:
    """Steady solution and its JSON-ready summary: EHLResult.to_dict() plus the Hertz half-width
    b [m], peak pressure p_H [Pa] and Pan-Hamrock's H_c, H_min for comparison."""
    result = solve_steady(contact, nodes=nodes)
    ph_c, ph_min = pan_hamrock(contact.W, contact.U, contact.G)
    out = {k: v for k, v in result.to_dict().items() if k != "time"}
    out.update({ "e_reduced": contact.e_reduced, "viscosity": contact.viscosity,
           "pressure_viscosity": contact.pressure_viscosity, "half_width": contact.half_width,
           "hertz_pressure": contact.hertz_pressure, "H_c_pan_hamrock": ph_c,
           "H_min_pan_hamrock": ph_min})
    return result, out


def format_roller(d: dict) -> str:
    """A short readable table of :func:`solve_roller`'s summary."""
    rows = [
        ("W, U, G", f"{d['W']:.4g}, {d['U']:.4g}, {d['G']:.4g}"),
        ("load w'", f"{d['load']:.4g} N/m"),
        ("entrainment velocity u_m", f"{d['entrainment_velocity']:.4g} m/s"),
        ("radius R, roughness", f"{d['radius']:.4g} m, {d['roughness']:.3g} m"),
        ("Reynolds equation", "Soleimanian et al. (2020) eq. 18" if d["peklenik"] is None else
         f"Patir-Cheng average flow, gamma = {d['peklenik']:.4g}"),
        ("Hertz half-width b, p_H", f"{d['half_width'] * 1e6:.4g} um, {d['hertz_pressure'] * 1e-9:.4g} GPa"),
        ("central film h_c (H_c)", f"{d['h_c'] * 1e9:.4g} nm ({d['H_c']:.4g}; Pan-Hamrock "
                                   f"{d['H_c_pan_hamrock']:.4g})"),
        ("minimum film h_min (H_min)", f"{d['h_min'] * 1e9:.4g} nm ({d['H_min']:.4g}; Pan-Hamrock "
                                       f"{d['H_min_pan_hamrock']:.4g})"),
        ("peak pressure (P_max)", f"{d['p_max'] * 1e-9:.4g} GPa ({d['P_max']:.4g})"),
        ("asperity load ratio", f"{d['asperity_load_ratio']:.4g}"),
        ("friction coefficient", f"{d['friction_coefficient']:.4g}"),
        ("nodes, Newton iterations", f"{d['nodes']}, {d['iterations']} (converged: {d['converged']})"),
    ]
    width = max(len(k) for k, _ in rows)
    return "\n".join(f"{k:<{width}}  {v}" for k, v in rows)


# --- guideway-fmu ehl-cycle: reading a run and choosing instants ----------------------------

@dataclass(frozen=True)
class RunRecord:
    """What the cycle analysis takes from a run folder (SI units)."""

    path: Path
    time: np.ndarray  # s, strictly increasing
    load: np.ndarray  # N, one upper roller
    velocity: np.ndarray  # m/s, feed velocity u
    film: np.ndarray  # m, the analytical film of the dynamics
    parameters: dict  # the contact instance's resolved parameters (CONTACT_KEYS at least)


def read_run(run_dir: str | Path, instance: str = "Contact", feed: str = "Feed.u") -> RunRecord:
    """Read ``<instance>.F_upper``, ``<instance>.h_upper`` and the ``feed`` velocity column of
    results.csv (checked against summary.json: cosim.run.read) and the instance's parameters
    from summary.json. Raises FileNotFoundError or ValueError naming the file and the missing
    column or key."""
    run_dir = Path(run_dir)
    csv_path, summary_path = run_dir / "results.csv", run_dir / "summary.json"
    recording, summary = read_results(run_dir)
    columns = {"time": recording.time, **recording.columns}
    names = {"time": "time", "load": f"{instance}.F_upper", "film": f"{instance}.h_upper",
             "velocity": feed}
    missing = [c for c in names.values() if c not in columns]
    if missing:
        raise ValueError(f"{csv_path} has no column {', '.join(missing)} "
                         f"(columns: {', '.join(columns)}); see 'instance' and 'feed'")
    if len(recording.time) < 2:
        raise ValueError(f"{csv_path}: need at least 2 rows")
    cols = {k: columns[c] for k, c in names.items()}
    if not all(np.all(np.isfinite(v)) for v in cols.values()):
        raise ValueError(f"{csv_path}: non-finite values in {', '.join(names.values())}")
    if np.any(np.diff(cols["time"]) < 0.0):
        raise ValueError(f"{csv_path}: time is not increasing")
    keep = np.r_[True, np.diff(cols["time"]) > 0.0]  # a repeated time (final sample) once
    try:
        parameters = summary["parameters"][instance]
    except (KeyError, TypeError):
        raise ValueError(f"{summary_path} has no parameters of instance {instance!r}") from None
    lacking = [k for k in CONTACT_KEYS if k not in parameters]
    if lacking:
        raise ValueError(f"{summary_path}: instance {instance!r} has no {', '.join(lacking)} "
                         "(a lubricated contact such as ContactEHL is needed)")
    return RunRecord(run_dir, cols["time"][keep], cols["load"][keep], cols["velocity"][keep],
                     cols["film"][keep], parameters)


def parse_times(text: str) -> list[float]:
    """``"t1,t2,..."`` [s] as floats; ValueError naming 'times' otherwise."""
    try:
        return [float(t) for t in text.split(",")]
    except ValueError:
        raise ValueError(f"'times' must be comma-separated times in s, got {text!r}") from None


def select_instants(time, load, *, times=None, count: int = 10,
                    window: float | None = None) -> list[tuple[str, int]]:
    """Instants to analyse as (label, sample index), labels A, B, C, ... in time order.

    ``times`` [s]: the recorded samples nearest to these times (each must lie in the record).
    Otherwise ``count`` instants spread over one load oscillation around the largest load: from
    the load minimum before that peak to the one after it (the innermost sample of a zero-load
    stretch), or over ``window`` [s] centred on the peak; they sit at the middles of ``count``
    equal parts, snapped to the nearest samples (coinciding ones kept once).
    """
    time, load = np.asarray(time, dtype=float), np.asarray(load, dtype=float)
    if times is not None:
        targets = np.asarray(times, dtype=float)
        outside = [t for t in targets if not (time[0] <= t <= time[-1])]
        if targets.size == 0 or outside:
            raise ValueError(f"'times': instant {outside[0] if outside else 'none'} s is outside "
                             f"the record [{time[0]:.6g}, {time[-1]:.6g}] s")
    else:
        if not 1 <= count <= len(string.ascii_uppercase):
            raise ValueError(f"'count' must be between 1 and 26, got {count}")
        if not np.max(load) > 0.0:
            raise ValueError("the roller load is never positive in the record: nothing to analyse")
        peak = int(np.argmax(load))
        if window is None:
            lo = hi = peak
            while lo > 0 and load[lo - 1] < load[lo]:
                lo -= 1
            while hi < load.size - 1 and load[hi + 1] < load[hi]:
                hi += 1
            start, stop = time[lo], time[hi]
        else:
            if not (math.isfinite(window) and window > 0.0):
                raise ValueError(f"'window' must be > 0 s, got {window}")
            start = max(time[0], time[peak] - 0.5 * window)
            stop = min(time[-1], time[peak] + 0.5 * window)
        targets = start + (np.arange(count) + 0.5) * (stop - start) / count
    right = np.clip(np.searchsorted(time, targets), 1, time.size - 1)
    nearest = np.where(targets - time[right - 1] <= time[right] - targets, right - 1, right)
    return list(zip(string.ascii_uppercase, np.unique(nearest).tolist()))


# --- guideway-fmu ehl-cycle: solving ---------------------------------------------------------

@dataclass(frozen=True)
class Instant:
    """One analysed instant: its table row (keys COLUMNS) and the solution, None if there is none."""

    row: dict
    result: EHLResult | None


def _march(template, time, w, u_m, start, stop, floor, nodes, reached=None):
    """Transient over samples start..stop; returns its steps (index k -> steps[k - start]).
    ``reached(t)`` is called as each sample is solved."""
    part = slice(start, stop + 1)
    loads = np.maximum(w[part], floor * np.max(w[part]))
    if not u_m[start] > 0.0:
        raise ValueError(f"no entrainment (u = 0) at t = {time[start]:.6g} s, where the history "
                         "starts: no steady film to start from; give a longer 'history'")
    first = replace(template, load=float(loads[0]), entrainment_velocity=float(u_m[start]))
    inlet, outlet, default_nodes = solver.transient_grid(first, float(np.max(loads)))
    return solve_transient(first, time[part], loads, entrainment_velocities=u_m[part],
                           inlet=inlet, outlet=outlet, nodes=nodes or default_nodes,
                           progress=reached).steps


@dataclass(frozen=True)
class _Plan:
    """How one loaded instant is solved: sample ``index``, its history from sample ``start``."""

    label: str
    index: int
    start: int
    steady: bool
    contact: LineContactEHL


def analyse_instants(record: RunRecord, instants, *, history: float | None = None,
                     floor: float = DEFAULT_FLOOR, roughness: float = paper.ROUGHNESS,
                     nodes: int | None = None, progress: bool = False) -> list[Instant]:
    """Solve the upper-roller contact at each (label, index) of ``instants`` (see the module
    docstring). ``history`` [s] overrides the default squeeze history (0: steady);
    ``floor`` (0 < floor <= 1) is the load of separated samples as a fraction of the march's
    largest load; ``nodes`` overrides the grid; ``progress`` shows a bar of the samples solved
    (tqdm, stderr). A solution that fails is reported in its row (status "failed" and the
    error), a roller without load as status "separated"."""
    if history is not None and not (math.isfinite(history) and history >= 0.0):
        raise ValueError(f"'history' must be >= 0 s, got {history}")
    if not (math.isfinite(floor) and 0.0 < floor <= 1.0):
        raise ValueError(f"'floor' must lie in (0, 1], got {floor}")
    p = record.parameters
    template = LineContactEHL(load=1.0, radius=float(p["roller_radius"]), entrainment_velocity=1.0,
                              e_reduced=float(p["e_reduced"]), viscosity=float(p["viscosity"]),
                              pressure_viscosity=float(p["pressure_viscosity"]),
                              roughness=roughness)
    template.validate()
    time, w = record.time, record.load / float(p["roller_length"])
    u_m = 0.5 * np.abs(record.velocity)
    rows, plans = {}, []
    for label, k in instants:
        row = rows[label] = dict.fromkeys(COLUMNS)
        row.update(label=label, time=float(time[k]), load=float(record.load[k]),
                   load_per_length=float(w[k]), u=float(record.velocity[k]), u_m=float(u_m[k]),
                   h_analytical=float(record.film[k]))
        if not w[k] > 0.0:
            continue
        contact = replace(template, load=float(w[k]), entrainment_velocity=float(u_m[k]))
        transit = 2.0 * contact.half_width / u_m[k] if u_m[k] > 0.0 else math.inf
        start = int(np.searchsorted(time, time[k] - (transit if history is None else history)))
        if history is None:
            start = max(start, k - MAX_HISTORY_SAMPLES)
        part = slice(start, k + 1)
        steady = start == k or (u_m[k] > 0.0 and np.ptp(w[part]) <= QUASI_STEADY * w[k]
                                and np.ptp(u_m[part]) <= QUASI_STEADY * u_m[k])
        row.update(method="steady" if steady else "transient",
                   transit_time=transit if u_m[k] > 0.0 else None,
                   history=0.0 if steady else float(time[k] - time[start]))
        if u_m[k] > 0.0:
            row["h_c_pan_hamrock"] = pan_hamrock(contact.W, contact.U, contact.G)[0] * contact.radius
        plans.append(_Plan(label, k, start, steady, contact))
    results = {}

    def attempt(group: list[_Plan], solve):
        try:
            results.update(zip((g.label for g in group), solve()))
        except (EHLConvergenceError, ValueError) as exc:
            for g in group:
                rows[g.label]["error"] = str(exc)

    groups = _overlapping([plan for plan in plans if not plan.steady])
    bar = tqdm(total=sum(plan.steady for plan in plans) + sum(
        group[-1].index - min(g.start for g in group) + 1 for group in groups),
        unit="sample", desc="EHL at the instants", disable=not progress)

    def march(start: int, stop: int):
        return _march(template, time, w, u_m, start, stop, floor, nodes,
                      lambda t: bar.update())

    def steady_solution(plan: _Plan):
        result = solve_steady(plan.contact, nodes=nodes)
        bar.update()
        return [result]

    with bar:
        for plan in plans:
            if plan.steady:
                attempt([plan], lambda plan=plan: steady_solution(plan))
        for group in groups:
            start = min(g.start for g in group)
            for g in group:
                rows[g.label]["history"] = float(time[g.index] - time[start])

            def shared(group=group, start=start):
                steps = march(start, group[-1].index)
                return [steps[g.index - start] for g in group]

            attempt(group, shared)
            if len(group) > 1 and rows[group[0].label]["error"]:  # each alone, own history
                bar.total += sum(g.index - g.start + 1 for g in group)
                for g in group:
                    rows[g.label].update(error=None, history=float(time[g.index] - time[g.start]))
                    attempt([g], lambda g=g: [march(g.start, g.index)[-1]])
    out = []
    for label, row in rows.items():
        result = results.get(label)
        row["status"] = "solved" if result is not None else "failed" if row["error"] else "separated"
        if result is not None:
            d = result.to_dict()
            row.update({k: d[k] for k in ("H_c", "h_c", "H_min", "h_min", "P_max", "p_max",
                                          "asperity_load_ratio", "friction_coefficient",
                                          "nodes", "iterations", "converged")},
                       film_ratio=row["h_analytical"] / d["h_c"],
                       floored=result.contact.load != row["load_per_length"])
        out.append(Instant(row, result))
    return out


def _overlapping(plans: list[_Plan]) -> list[list[_Plan]]:
    """Consecutive plans whose histories overlap, grouped: each group is one transient march."""
    groups = []
    for plan in plans:
        if groups and plan.start <= groups[-1][-1].index:
            groups[-1].append(plan)
        else:
            groups.append([plan])
    return groups


# --- guideway-fmu ehl-cycle: outputs ---------------------------------------------------------

def write_cycle(out: str | Path, record: RunRecord, instants: list[Instant], options: dict) -> list[Path]:
    """instants.json (rows, units, run, contact parameters, ``options``), instants.csv,
    load_history.png (Figs. 32/34) and instant_<label>.png (Figs. 33/35) in ``out``."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    rows = [i.row for i in instants]
    doc = {"run": str(record.path), "contact": {k: record.parameters[k] for k in CONTACT_KEYS},
           "options": options, "units": UNITS, "instants": rows}
    files = [out / "instants.json", out / "instants.csv"]
    files[0].write_text(json.dumps(doc, indent=1))
    with files[1].open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    marks = [(r["label"], r["time"], r["load"]) for r in rows]
    files.append(plot_load_history(record.time, record.load, marks, out / "load_history.png",
                                   ylabel="upper roller load [N]"))
    for i in instants:
        if i.result is not None:
            r = i.row
            title = (f"{r['label']}: t = {r['time'] * 1e3:.4f} ms, F = {r['load']:.4g} N, "
                     f"u = {r['u']:.3g} m/s ({r['method']}"
                     + (f", solved at the floor w' = {i.result.contact.load:.4g} N/m)"
                        if r["floored"] else ")"))
            files.append(plot_distribution(i.result, out / f"instant_{r['label']}.png",
                                           analytical_film=r["h_analytical"], title=title))
    return files


def format_cycle(instants: list[Instant]) -> str:
    """The instants as a readable table: films in nm, pressure in GPa."""
    head = (f"{'':2} {'t [ms]':>9} {'F [N]':>7} {'u [m/s]':>7} {'method':>9} {'h_c [nm]':>8} "
            f"{'h_min':>6} {'p_max GPa':>9} {'asp.':>6} {'mu':>7} {'h_dyn nm':>8} {'dyn/num':>7}")
    lines = [head]
    for i in instants:
        r = i.row
        left = f"{r['label']:2} {r['time'] * 1e3:9.4f} {r['load']:7.1f} {r['u']:7.3f}"
        if r["status"] != "solved":
            reason = r["error"] or "roller unloaded: no contact"
            lines.append(f"{left} {r['status']:>9}  {reason}")
            continue
        lines.append(f"{left} {r['method']:>9} {r['h_c'] * 1e9:8.1f} {r['h_min'] * 1e9:6.1f} "
                     f"{r['p_max'] * 1e-9:9.3f} {r['asperity_load_ratio']:6.3f} "
                     f"{r['friction_coefficient']:7.4f} {r['h_analytical'] * 1e9:8.1f} "
                     f"{r['film_ratio']:7.3f}" + (" (floored)" if r["floored"] else ""))
    return "\n".join(lines)


def ehl_cycle(run_dir, out, *, instance: str = "Contact", feed: str = "Feed.u", times=None,
              count: int = 10, window: float | None = None, history: float | None = None,
              floor: float = DEFAULT_FLOOR, roughness: float = paper.ROUGHNESS,
              nodes: int | None = None,
              progress: bool = False) -> tuple[list[Instant], list[Path]]:
    """Read the run, choose the instants, solve them (``progress``: a bar on stderr) and write
    the outputs (see above), the instants that failed too."""
    if roughness < 0.0 or not math.isfinite(roughness):
        raise ValueError(f"'roughness' must be >= 0 m, got {roughness}")
    if nodes is not None and nodes < 33:
        raise ValueError(f"'nodes' must be >= 33, got {nodes}")
    record = read_run(run_dir, instance, feed)
    chosen = select_instants(record.time, record.load, times=times, count=count, window=window)
    instants = analyse_instants(record, chosen, history=history, floor=floor,
                                roughness=roughness, nodes=nodes, progress=progress)
    options = {"instance": instance, "feed": feed, "history": history, "floor": floor,
               "roughness": roughness, "nodes": nodes}
    return instants, write_cycle(out, record, instants, options)
