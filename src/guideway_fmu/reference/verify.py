"""Co-simulation against the monolithic reference: error of every shared output, wall times, and
a verdict by the criterion the reference's predictability allows (reference/criterion.py)."""
from __future__ import annotations

import time

import numpy as np

from . import criterion, monolithic, statistics
from ..cosim import master
from ..cosim.system import System
from ..output.progress import stages

LOAD = "Contact.F_upper"  # the judged signal where the system has it


def compare(time, columns: dict, reference) -> tuple[dict, dict]:
    """RMS and peak error of each column against the reference's column of the same name at the
    same times, relative to the reference's range (max - min); columns it lacks are skipped."""
    rms, peak = {}, {}
    for name, values in columns.items():
        if name in reference.columns:
            ref = np.interp(time, reference.time, reference.columns[name])
            rms[name], peak[name] = criterion.relative_error(values, ref)
    return rms, peak


def judged_signals(system: System, columns) -> tuple[str, list[str]]:
    """The signal a verdict is on (Contact.F_upper, else the first plotted time history, else
    the first column) and the films whose distributions the statistics add (the film plots')."""
    plotted = [n for n in system.plots.get("time", []) if n in columns]
    signal = LOAD if LOAD in columns else (plotted or list(columns))[0]
    return signal, [n for n in system.plots.get("film", []) if n in columns and n != signal]


def excitation_period(system: System, time, values) -> float:
    """Period [s] of the load cycle: of the first component's load_frequency parameter that is
    positive, else of the highest spectral peak of ``values``."""
    for component in system.components.values():
        frequency = float(component.parameters.get("load_frequency", 0.0))
        if frequency > 0:
            return 1.0 / frequency
    frequencies = statistics.spectral_peaks(time, values, 1)[0]
    if not len(frequencies) or frequencies[0] <= 0:
        raise ValueError(f"{system.name}: no load_frequency parameter and no spectral peak in the "
                         "judged signal: the load cycle of its statistics is undefined")
    return 1.0 / float(frequencies[0])


def _statistics(system, time, signal, films, cosim: dict, reference: dict, disturbed: list) -> dict:
    """Statistics of the judged signal and the films after the scenario's plot transient (at
    most half the run) for the co-simulation, the reference and the disturbed references, each
    judged against the reference's spread."""
    skip = min(float(system.plots.get("skip", 0.0)), (time[-1] - time[0]) / 2)
    keep = time >= time[0] + skip
    t = time[keep]
    period = excitation_period(system, t, reference[signal][keep])
    frequencies = statistics.spectral_peaks(t, reference[signal][keep])[0]
    bin_width = 1.0 / (t[-1] - t[0] + (t[1] - t[0]))
    judged = {}
    for name in [signal, *films]:
        def of(columns):
            v = np.asarray(columns[name])[keep]
            return (statistics.load_statistics(t, v, period, frequencies) if name == signal
                    else statistics.distribution(v))
        judged[name] = criterion.judge_statistics(of(cosim), of(reference),
                                                  [of(d) for d in disturbed],
                                                  float(np.ptp(reference[name][keep])), bin_width)
    return {"load_cycle_period": period, "skip": skip, "signals": judged}


def verify(system: System, progress: bool = False) -> dict:
    """Run the co-simulation and the reference on the same time grid, compare them, and judge
    the judged signal by the criterion the reference's predictability allows (two more
    reference runs, disturbed); a system the reference cannot model is refused before the
    co-simulation runs. ``progress``: a bar of these four runs on stderr."""
    monolithic.check(system)
    with stages(f"verify {system.name}", total=4, enabled=progress) as begin:
        begin("co-simulation")
        start = time.perf_counter()
        result = master.simulate(system)
        wall_time_cosim = time.perf_counter() - start  # s, the whole run, as the reference's
        rec = result.recording
        begin("reference")
        reference = monolithic.simulate(system, times=rec.time)
        rms, peak = compare(rec.time, rec.columns, reference)
        signal, films = judged_signals(system, rms)
        wanted = [signal, *films]
        offset = f"start offset {criterion.START_OFFSET:g}"
        loose = f"rtol {reference.rtol * criterion.LOOSE_RTOL_FACTOR:g}"
        begin(f"reference, {offset}")
        disturbed = {offset: monolithic.simulate(system, times=rec.time, columns=wanted,
                                                 start_offset=criterion.START_OFFSET)}
        begin(f"reference, {loose}")
        disturbed[loose] = monolithic.simulate(
            system, times=rec.time, columns=wanted,
            rtol=reference.rtol * criterion.LOOSE_RTOL_FACTOR)
    chosen, spreads, reason = criterion.choose(
        reference.columns[signal], {label: d.columns[signal] for label, d in disturbed.items()})
    report = {"scenario": system.name, "algorithm": system.experiment.algorithm,
              "step": system.experiment.step, "steps": result.steps, "rejected": result.rejected,
              "rms_error": rms, "peak_error": peak, "signal": signal, "criterion": chosen,
              "predictability": {"spread": spreads, "threshold": criterion.PREDICTABLE},
              "reason": reason}
    if chosen == "pointwise":
        report["passed"] = rms[signal] <= criterion.TOLERANCE
        report["tolerance"] = criterion.TOLERANCE
    else:
        stats = _statistics(system, np.asarray(rec.time), signal, films,
                            {n: np.asarray(rec.columns[n]) for n in wanted}, reference.columns,
                            [d.columns for d in disturbed.values()])
        report["statistics"] = stats
        report["k"], report["floor"] = criterion.K, criterion.FLOOR
        report["passed"] = all(s["passed"] for sig in stats["signals"].values() for s in sig.values())
    report.update({
        "wall_time_cosim": wall_time_cosim, "wall_time_reference": reference.wall_time,
        "wall_time_probe": sum(d.wall_time for d in disturbed.values()),
        "fmi_call_time_cosim": result.fmi_time,
        "reference": {"method": reference.method, "rtol": reference.rtol, "nfev": reference.nfev}})
    return report


def format_table(report: dict) -> str:
    lines = [f"{report['scenario']}: {report['algorithm']}, step {report['step']:g} s, "
             f"{report['steps']} steps ({report['rejected']} rejected)",
             f"{'variable':32s} {'rms error':>10s} {'peak error':>10s}   (relative to range)"]
    for name, value in report["rms_error"].items():
        lines.append(f"{name:32s} {value:10.2e} {report['peak_error'][name]:10.2e}")
    spreads = ", ".join(f"{label}: {v:.2e}" for label, v in report["predictability"]["spread"].items())
    lines += [f"predictability of {report['signal']} (RMS change / range): {spreads}",
              f"criterion: {report['criterion']} ({report['reason']})"]
    if report["criterion"] == "pointwise":
        lines.append(f"verdict: {'passed' if report['passed'] else 'FAILED'}: RMS error "
                     f"{report['rms_error'][report['signal']]:.2e} against {report['tolerance']:g}")
    else:
        stats = report["statistics"]
        lines.append(f"statistics after {stats['skip']:g} s, load cycle {stats['load_cycle_period']:g} s; "
                     f"allowed: {report['k']:g} x the reference's spread or the floor")
        lines.append(f"{'signal / statistic':44s} {'reference':>11s} {'difference':>11s} "
                     f"{'spread':>10s} {'allowed':>10s}")
        for name, judged in stats["signals"].items():
            for stat, s in judged.items():
                lines.append(f"{name + ' ' + stat:44s} {s['reference']:11.4g} {s['difference']:11.3g} "
                             f"{s['spread']:10.3g} {s['allowed']:10.3g}{'' if s['passed'] else '  FAILED'}")
        lines.append(f"verdict: {'passed' if report['passed'] else 'FAILED'}")
    ratio = report["wall_time_cosim"] / report["wall_time_reference"]
    lines.append(f"wall time: co-simulation {report['wall_time_cosim']:.2f} s, reference "
                 f"{report['wall_time_reference']:.2f} s ({report['reference']['method']}, rtol "
                 f"{report['reference']['rtol']:g}): ratio {ratio:.2f}; predictability probe "
                 f"{report['wall_time_probe']:.2f} s")
    return "\n".join(lines)
