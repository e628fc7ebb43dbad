"""Which host runs which export of a scenario as our master does, measured: docs/hosts.md.

For each scenario of SCENARIOS (one loaded and lubricated, one dry, the unloaded rig, one ball
guide), over its stop time of STOPS:

(a) our master, the scenario as it is (the stabilised coupling where it declares tangents): the
    run the others are judged against;
(j) our master with the jacobi algorithm, the explicit coupling an SSP host runs;
(b) its SSP package (``export-ssp``, baked) in fmpy's SSP runner (``simulate_ssp``);
(c) the same package in libcosim (``cosim.ssp.run_libcosim``);
(u) the package unbaked (``export-ssp --no-bake``) in fmpy's SSP runner, which ignores the
    parameter bindings;
(d) its packed FMU (``export-fmu``) in fmpy's ``simulate_fmu``, communicating every macro step;
(e) the packed FMU in libcosim, as the one component of an SSP package.

Per host: whether it finished, else the step it stopped in and why (the FMU's message; a run
that stops is repeated with fewer steps, by bisection, to find the last step it completes),
the largest |judged signal| and the RMS error of the judged signal against (a) over the time it
ran, relative to (a)'s range over the whole run. The judged signal is verify's:
Contact.F_upper, else the first plotted time history.

    python benchmarks/hosts.py [--fmus fmus] [--out docs/hosts.md]
"""
from __future__ import annotations

import argparse
import contextlib
import io
import math
import tempfile
from dataclasses import dataclass
from pathlib import Path

import fmpy
import numpy as np
from fmpy.ssp.simulation import simulate_ssp  # fmpy.ssp.simulate parses sys.argv on import

from guideway_fmu import scenarios
from guideway_fmu.cosim import master, ssp, system
from guideway_fmu.cosim.export_fmu import export_fmu
from guideway_fmu.reference.verify import judged_signals

import pages

SCENARIOS = ("soleimanian2020_9000N_4500Hz", "soleimanian2020_9000N_4500Hz_dry",
             "soleimanian2020_unloaded", "lin2019_ball_to_ball_friction")
STOPS = {"lin2019_ball_to_ball_friction": 0.03}  # s; the others DEFAULT_STOP
DEFAULT_STOP = 6e-3  # s: 1500 steps of the Soleimanian rig, long enough to see it part ways
INPUTS = tuple(f"{pages.SCENARIOS}/{name}.toml" for name in SCENARIOS)
FAITHFUL = 1e-3  # RMS error of the judged signal, relative to (a)'s range, of a faithful run
HOSTS = {"a": "our master", "j": "our master, jacobi (the coupling of an SSP host)",
         "b": "SSP package in fmpy (simulate_ssp)", "c": "SSP package in libcosim",
         "u": "SSP package, --no-bake, in fmpy", "d": "packed FMU in fmpy (simulate_fmu)",
         "e": "packed FMU in libcosim"}


@dataclass
class Run:
    """What one host did: the steps it completed of ``steps``, why it stopped, and its judged
    signal [its unit] at ``time`` [s] over the steps it completed."""

    steps: int
    completed: int
    reason: str
    time: np.ndarray
    values: np.ndarray


def attempt(runner, steps: int) -> tuple[tuple | None, str]:
    """(runner(steps)'s (time, values), or None if it raised; the FMU's last message or the
    exception's). The FMUs print their errors on Python's stderr."""
    said = io.StringIO()
    try:
        with contextlib.redirect_stderr(said):
            return runner(steps), ""
    except Exception as exc:  # noqa: BLE001 - each host raises its own kind for a failed step
        lines = [line for line in said.getvalue().splitlines() if line.strip()]
        return None, lines[-1] if lines else f"{type(exc).__name__}: {exc}"


def host_run(runner, steps: int) -> Run:
    """Run ``runner`` (steps -> (time, values)) for ``steps`` macro steps; if it fails, find by
    bisection the most steps it completes, for its data up to there."""
    done, reason = attempt(runner, steps)
    if done is not None:
        return Run(steps, steps, "", *done)
    low, high, data = 0, steps, None  # completes `low` steps, fails at `high`
    while high - low > 1:
        middle = (low + high) // 2
        got, _ = attempt(runner, middle)
        if got is None:
            high = middle
        else:
            low, data = middle, got
    empty = (np.empty(0), np.empty(0))
    return Run(steps, low, reason, *(data or empty))


def runners(scenario: system.System, signal: str, folder: Path) -> dict:
    """Host letter -> runner(steps) -> (time [s], the judged signal) of that host."""
    h = scenario.experiment.step
    package = ssp.export_ssp(scenario, folder / "system.ssp")
    unbaked = ssp.export_ssp(scenario, folder / "unbaked.ssp", bake=False)
    packed = export_fmu(scenario, folder / "Packed.fmu")
    outer = (system.Builder("packed").experiment(stop=scenario.experiment.stop, step=h,
                                                 algorithm="jacobi")
             .component("Rig", packed).record([f"Rig.{signal}"]).system())
    packed_package = ssp.export_ssp(outer, folder / "packed.ssp")

    def jacobi(steps):
        rec = master.simulate(scenario.with_changes(algorithm="jacobi", stop=steps * h)).recording
        return rec.time, rec.columns[signal]

    def fmpy_ssp(steps, package=package):  # row k: the values read after the step t_k -> t_k + h
        rows = simulate_ssp(str(package), start_time=0.0, stop_time=steps * h, step_size=h)
        return rows["time"][:steps] + h, rows[signal][:steps]

    def libcosim(steps):
        times, columns = ssp.run_libcosim(package, [signal], steps)
        return times, columns[signal]

    def fmpy_packed(steps):
        res = fmpy.simulate_fmu(str(packed), stop_time=steps * h, step_size=h,
                                output_interval=h, output=[signal])
        return res["time"], res[signal]

    def libcosim_packed(steps):
        times, columns = ssp.run_libcosim(packed_package, [f"Rig.{signal}"], steps)
        return times, columns[f"Rig.{signal}"]

    return {"j": jacobi, "b": fmpy_ssp, "c": libcosim,
            "u": lambda steps: fmpy_ssp(steps, unbaked), "d": fmpy_packed, "e": libcosim_packed}


def judge(run: Run, time_, reference) -> tuple[float, float]:
    """(RMS error of the run's signal against the reference at its times, relative to the
    reference's range over the whole run; its largest magnitude); NaN without data."""
    if run.values.size == 0:
        return math.nan, math.nan
    expected = np.interp(run.time, time_, reference)
    with np.errstate(over="ignore"):  # a diverged run: its error is infinite
        rms = np.sqrt(np.mean((run.values - expected) ** 2)) / np.ptp(reference)
    return float(rms), float(np.max(np.abs(run.values)))


def measure(name: str, fmus: Path) -> dict:
    """The runs of one scenario in every host (HOSTS), judged against our master's."""
    stop = STOPS.get(name, DEFAULT_STOP)
    scenario = system.load(scenarios.find(name), fmus).with_changes(stop=stop)
    steps = round(stop / scenario.experiment.step)
    rec = master.simulate(scenario).recording
    signal = judged_signals(scenario, rec.columns)[0]
    reference = rec.columns[signal]
    rows = [("a", Run(steps, steps, "", rec.time, reference))]
    with tempfile.TemporaryDirectory(prefix="guideway_fmu_hosts_") as tmp:
        for host, runner in runners(scenario, signal, Path(tmp)).items():
            rows.append((host, host_run(runner, steps)))
            print(f"{name} ({host}): {rows[-1][1].completed} of {steps} steps "
                  f"{rows[-1][1].reason}", flush=True)
    return {"name": name, "stop": stop, "step": scenario.experiment.step, "signal": signal,
            "unit": scenario.unit(*signal.split(".", 1)) or "-",
            "tangents": bool(scenario.tangents), "algorithm": scenario.experiment.algorithm,
            "runs": [(host, run, *judge(run, rec.time, reference)) for host, run in rows]}


def table(result: dict) -> list[str]:
    """The Markdown table of one scenario."""
    h = result["step"]
    lines = [f"### {result['name']}", "",
             f"{result['stop'] * 1e3:g} ms ({round(result['stop'] / h)} steps of {h:g} s), "
             f"our master's {result['algorithm']} algorithm"
             + (" with the scenario's tangents" if result["tangents"] else " (no tangents)")
             + f"; judged signal {result['signal']} [{result['unit']}].", "",
             "| host | ran | largest abs. value of the signal | RMS error / range | faithful |",
             "| --- | --- | --- | --- | --- |"]
    for host, run, error, peak in result["runs"]:
        what = f"({host}) {HOSTS[host]}"
        if run.completed == run.steps:
            ran = "to the end"
        else:
            ran = (f"stopped in the step to t = {(run.completed + 1) * h * 1e3:.4g} ms: "
                   f"{run.reason.replace('|', '/')}")
        faithful = ("(the reference)" if host == "a" else
                    "yes" if run.completed == run.steps and error <= FAITHFUL else "no")
        lines.append(f"| {what} | {ran} | {peak:.4g} | "
                     f"{'-' if host == 'a' else f'{error:.2e}'} | {faithful} |")
    return lines + [""]


def page(results: list[dict]) -> str:
    """The page's Markdown."""
    lines = ["# Hosts: which export runs where as our master runs it", "",
             "A scenario leaves this project two ways: `guideway-fmu export-ssp` writes an SSP "
             "package of its FMUs and connections, which a host steps itself; `guideway-fmu "
             "export-fmu` packs the system into one FMU with our master inside, which a host "
             "steps as one component. Each scenario below ran (a) in our master and in two hosts "
             "each way; every run is judged against (a): the RMS error of the judged signal "
             f"over the time the host ran, relative to (a)'s range; faithful: the host ran to "
             f"the end within {FAITHFUL:g} of the range. A host that stopped was rerun with "
             "fewer steps to find the last step it completes; its error and largest value are "
             "those of the steps it completed. (j) is our master with the explicit coupling an "
             "SSP host runs (each output held over the step, every instance stepped from the "
             "same inputs), and (u) the package without its FMUs' baked start values in fmpy, "
             "which ignores the SSD's parameter bindings and cannot set String parameters.", ""]
    for result in results:
        lines += table(result)
    lines += ["## Summary", ""]
    for host, what in HOSTS.items():
        if host != "a":
            faithful = [r["name"] for r in results for h, run, error, _ in r["runs"]
                        if h == host and run.completed == run.steps and error <= FAITHFUL]
            lines.append(f"- ({host}) {what}: faithful on {len(faithful)} of {len(results)}"
                         + (f" ({', '.join(faithful)})" if faithful else ""))
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fmus", type=Path, default=Path("fmus"))
    parser.add_argument("--out", type=Path, default=Path("docs/hosts.md"))
    args = parser.parse_args()
    results = [measure(name, args.fmus) for name in SCENARIOS]
    pages.write(args.out, page(results), "python benchmarks/hosts.py", __file__, INPUTS)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
