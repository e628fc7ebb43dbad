"""index.html of the demo's output folder: every plot and table the demo made, each with what it
shows and the command that makes it again. Static HTML (output/pages.py), images referenced by
paths relative to the page."""
from __future__ import annotations

import html
import json
import shlex
from pathlib import Path

from ..output import pages

KIND_TEXT = {  # what each plot of guideway-fmu run shows (cosim/plots.py)
    "time": "Time histories of the recorded signals: the carriage's vertical displacement and "
            "the loads of one roller in an upper and in a lower groove.",
    "spectrum": "Amplitude spectra of the same signals (Hann window, the start's transient left "
                "out), log scale; the five highest peaks are marked and their frequencies listed.",
    "film": "Lubricant film thickness of an upper and a lower roller contact (zero with dry "
            "contacts).",
    "envelope": "The signals (grey) with their upper and lower envelope, the running maximum "
                "and minimum over a short window.",
}
DIAGNOSIS_TEXT = {  # by file-name prefix (diagnose/report.py)
    "measured_vs_models": "The measured channel against the calibrated baseline model and the "
                          "model with the named effect added, both co-simulated; over the "
                          "whole record and zoomed on held-out samples.",
    "residual_vs_": "What is left of the measurement after the baseline (and after the "
                    "augmented model) against the signal that gave the missing effect away, "
                    "with the baseline residual's bin means.",
    "candidate_ranking": "Every candidate effect's cross-validated score and held-out gap, "
                         "with the baseline's gap and the noise floor.",
}


def command(*args) -> str:
    """A guideway-fmu command line, its arguments quoted for a POSIX shell."""
    return shlex.join(["guideway-fmu", *map(str, args)])


def _section(title: str, text: str, cmd: str | None = None) -> list[str]:
    return [f"<h2>{html.escape(title)}</h2>", f"<p>{html.escape(text)}</p>",
            *([f"<pre>{html.escape(cmd)}</pre>"] if cmd else [])]


def _image(out: Path, path: Path, text: str) -> list[str]:
    rel = path.relative_to(out).as_posix()
    return [f"<h3>{html.escape(rel)}</h3>", f"<p>{html.escape(text)}</p>",
            pages.figure(rel, text)]


def _g(value: float) -> str:
    return f"{value:.4g}"


def write_index(out: Path, fmus: Path | None, fmu_dir: Path, stop: float, summary: dict,
                scenarios: tuple[str, ...], verified: str) -> Path:
    """Write ``out``/index.html from the demo's ``summary`` and the files it wrote into ``out``
    (runs of ``stop`` seconds with the FMUs in ``fmu_dir``: the folder ``fmus`` given to the
    demo, or the FMU cache's when None, which the commands shown then find themselves);
    returns its path."""
    option = () if fmus is None else ("--fmus", fmus)  # the commands' FMU option
    body = ["<h1>guideway-fmu demo</h1>",
            "<p>Everything below was made by one command; the FMUs it ran are in "
            f"{html.escape(str(fmu_dir))}, the numbers in summary.json.</p>",
            f"<pre>{html.escape(command('demo', '--out', out, *option, '--stop', stop))}</pre>"]
    body += _section(
        "Quasi-static stiffness of the guideway (Soleimanian et al. 2020, Figs. 3 and 4)",
        "The stiffness K = dF_contact/dy of the roller contacts against the vertical displacement "
        "y of the moving body, lubricated (ContactEHL, film at its steady value for the feed "
        "speed) and dry (ContactDryHertz): each point a fresh initialisation of the contact FMU "
        "at y, K the central difference of its net force. The demo computes it itself "
        "(guideway_fmu.demo.stiffness_curves, values in stiffness.csv); the stiffness, film and "
        "natural frequency at y = 0 are printed by:", command("facts"))
    body += [pages.table([("lubricated", _g(summary["stiffness_at_y0_lubricated_N_per_m"])),
                              ("dry", _g(summary["stiffness_at_y0_dry_N_per_m"]))],
                             ["contacts", "K at y = 0 [N/m]"])]
    body += _image(out, out / "stiffness.png", "Stiffness K [N/µm] against y [µm], lubricated "
                   "and dry.")
    body += _section(
        "Co-simulation of the rig", f"Three shipped scenarios through the co-simulation master, "
        f"{stop:g} s each: the unloaded rig with friction, 9000 N at 4500 Hz with lubricated "
        "contacts, and the same with dry contacts. Each folder holds results.csv (with "
        "results.units.json) and summary.json; each run's command is given with its plots below.")
    rows = [(name, r["steps"], f"{r['wall_time_s']:.2f}", _g(r["dominant_frequency_above_1kHz_Hz"]),
             " to ".join(map(_g, r["F_upper_range_N"])), " to ".join(_g(h * 1e6) for h in r["h_upper_range_m"]))
            for name, r in summary["runs"].items()]
    body.append(pages.table(rows, ["scenario", "steps", "wall time [s]",
                                       "dominant frequency of y above 1 kHz [Hz]",
                                       "load of an upper roller [N]",
                                       "film of an upper roller [µm]"]))
    for name in scenarios:
        files = json.loads((out / name / "summary.json").read_text())["files"]
        body.append(f"<h3>{html.escape(name)}</h3>"
                    f"<pre>{html.escape(command('run', name, *option, '--stop', stop, '--out', out / name))}</pre>")
        for file in files:
            if file.endswith(".png"):
                body += _image(out, out / name / file, KIND_TEXT[Path(file).stem])
    body += _verification(out, option, stop, verified)
    body += _sweep(out, option, summary["sweep"])
    body += _diagnosis(out, option, summary["diagnose"])
    path = out / "index.html"
    path.write_text(pages.page("guideway-fmu demo", body), encoding="utf-8")
    return path


def _verification(out: Path, option: tuple, stop: float, verified: str) -> list[str]:
    report = json.loads((out / "verify.json").read_text())
    body = _section(
        "Co-simulation against the monolithic reference",
        f"The scenario {verified} run by the master and integrated as one system by SciPy "
        f"({report['reference']['method']}, rtol {report['reference']['rtol']:g}) on the same time "
        "grid: the RMS and the largest difference of every recorded signal, relative to its "
        f"range. Wall time: co-simulation {report['wall_time_cosim']:.2f} s, reference "
        f"{report['wall_time_reference']:.2f} s. The numbers are in verify.json (--json).",
        command("verify", verified, *option, "--stop", stop))
    rows = [(name, f"{rms:.2e}", f"{report['peak_error'][name]:.2e}")
            for name, rms in report["rms_error"].items()]
    return body + [pages.table(rows, ["signal", "RMS error / range", "peak error / range"])]


def _sweep(out: Path, option: tuple, sweep: dict) -> list[str]:
    folder = out / sweep["folder"]
    data = json.loads((folder / "results.json").read_text())
    body = _section(
        "Parameter sweep: envelope of the roller load against the excitation frequency",
        f"The shipped example sweep (cf. Figs. 22, 25, 28 of the paper) shortened to "
        f"{data['experiment']['stop']:g} s per point: {data['scenario']} at every combination "
        f"of the listed loads and frequencies, {sweep['ok']} of {data['points_in_design']} "
        f"points finished, on a local Dask cluster of {sweep['workers']} worker processes in "
        f"{sweep['wall_time_s']:.1f} s. The tables are results.csv and results.json in "
        f"{sweep['folder']}; the command (into a folder without results.csv, or with --resume "
        "to continue one):",
        command("sweep", out / sweep["file"], *option, "--workers", sweep["workers"],
                "--out", folder))
    columns = [o["column"] for o in data["outputs"]]
    units = [o["unit"] or "-" for o in data["outputs"]]
    rows = [(*(p["parameters"][n] for n in data["parameters"]),
             *(_g(p["outputs"][c]) if p["outputs"][c] is not None else "-" for c in columns),
             p["status"]) for p in data["points"]]
    header = [f"{n} [{data['parameter_units'][n] or '-'}]" for n in data["parameters"]]
    body.append(pages.table(rows, [*header, *(f"{c} [{u}]" for c, u in zip(columns, units)),
                                       "status"]))
    for output, plot in zip(data["outputs"], sweep["plots"]):
        settle = f", the first {output['settle_s']:g} s left out" if output["settle_s"] else ""
        body += _image(out, out / plot, f"{output['column']} [{output['unit'] or '-'}] of each "
                       f"point{settle}, against each swept parameter, a line per value of the "
                       "other.")
    return body


def _diagnosis(out: Path, option: tuple, diagnosis: dict) -> list[str]:
    folder = out / "diagnose_example"
    body = _section(
        "Diagnosis of a measured run",
        "The bundled measured run of the horizontal rig with a hidden effect "
        "(guideway_fmu/examples/measured_run, copied into diagnose_example/run): the workflow "
        "calibrates a baseline model, ranks candidate effects on held-out samples and names the "
        "missing one. The full report, with how every number was obtained, is "
        "diagnose_example/report.html.",
        command("diagnose", folder / "run", "--out", folder, *option))
    body.append("<p><a href='diagnose_example/report.html'>diagnosis report</a></p>")
    rows = [("hidden effect", diagnosis["hidden_effect"]),
            ("named effect", diagnosis["missing_effect"]),
            ("held-out gap of the baseline", _g(diagnosis["gap_before"])),
            ("held-out gap with the named effect", _g(diagnosis["gap_after"])),
            ("noise floor", _g(diagnosis["noise_floor"]))]
    body.append(pages.table(rows, ["", ""]))
    for plot in sorted(folder.glob("*.png")):
        text = next(t for prefix, t in DIAGNOSIS_TEXT.items() if plot.stem.startswith(prefix))
        body += _image(out, plot, text)
    return body
