"""The main job on built-in data: the FMUs, Soleimanian et al. 2020's stiffness curves and a rig run.

0. The FMUs: the FMU cache's (fmu_build.cache, built once per code), or a folder given, built
   where missing or built from other code.

1. Quasi-static stiffness K(y), lubricated (Fig. 3) and dry (Fig. 4), computed through the
   contact FMUs: each point is a fresh initialisation at displacement y (the EHL film starts at
   its steady value), K the central difference of the FMU's F_contact over y; the dry FMU's
   K_contact output is checked against it.
2. Three shipped scenarios (guideway_fmu/scenarios/) through the co-simulation master, shortened to
   ``stop`` seconds: the unloaded rig (Soleimanian et al. 2020, with friction), 9000 N at 4500 Hz lubricated
   and the same with dry contacts; results, plots and summary per run.
3. ``guideway-fmu verify`` of the 9000 N / 4500 Hz run against the monolithic reference.
4. ``guideway-fmu diagnose`` on the bundled measured run with a hidden pre-sliding hysteresis
   (guideway_fmu/examples/measured_run): the named effect and the held-out gap before and after.
5. ``guideway-fmu sweep`` of the shipped example sweep (roller load against excitation
   frequency at three loads), its runs shortened to ``stop`` seconds, on 2 Dask workers.
6. index.html (demo/page.py): every plot and table with what it shows and its command.
"""
from __future__ import annotations

import json
import shutil
import time
import tomllib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import tomli_w  # noqa: E402

from . import page  # noqa: E402
from .. import scenarios  # noqa: E402
from ..fmu_build import build, cache  # noqa: E402
from ..reference import verify  # noqa: E402
from ..cosim import plots, run, system  # noqa: E402
from ..cosim.fmu_instance import FmuInstance  # noqa: E402
from ..diagnose import workflow  # noqa: E402
from ..examples import FOLDER as EXAMPLES  # noqa: E402
from ..analysis.soleimanian2020 import RIG_SPEED  # noqa: E402
from ..sweep import run as sweep_run, sweep_file  # noqa: E402
from ..output.progress import stages  # noqa: E402


def stiffness_curves(fmu_dir: Path, y: np.ndarray, u: float = RIG_SPEED) -> dict[str, np.ndarray]:
    """Net force and stiffness over y [m] from ContactEHL (at feed speed u) and ContactDryHertz."""
    out = {"y": y}
    for label, fmu in (("lubricated", "ContactEHL"), ("dry", "ContactDryHertz")):
        inst = FmuInstance(fmu_dir / f"{fmu}.fmu", fmu)
        force, k_out = np.empty_like(y), np.empty_like(y)
        for i, yi in enumerate(y):
            inst.fmu.reset()
            inst.initialise(0.0, {"y": float(yi), "u": u})
            force[i], k_out[i] = inst.get("F_contact"), inst.get("K_contact")
        inst.close()
        out[f"F_{label}"], out[f"K_{label}"] = force, np.gradient(force, y)
        out[f"K_contact_output_{label}"] = k_out
    return out


def _plot_stiffness(curves, path: Path) -> None:
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, label, fig_no in zip(axes, ("lubricated", "dry"), (3, 4)):
        ax.plot(curves["y"] * 1e6, curves[f"K_{label}"] / 1e6)
        ax.set(title=f"{label} (Soleimanian et al. 2020 Fig. {fig_no})",
               xlabel="vertical displacement of the moving body y [µm]")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("stiffness K = dF_contact/dy [N/µm]")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


DEMO_SCENARIOS = ("soleimanian2020_unloaded", "soleimanian2020_9000N_4500Hz", "soleimanian2020_9000N_4500Hz_dry")
VERIFIED = "soleimanian2020_9000N_4500Hz"
SWEEP = scenarios.FOLDER / "sweeps" / "soleimanian2020_envelope_vs_frequency.toml"
SWEEP_WORKERS = 2
#: what the bundled measured run hides (its README.md says how it was made)
HIDDEN_EFFECT = "presliding_hysteresis"


def shortened_sweep(path: Path, stop: float) -> Path:
    """Write the example sweep (SWEEP) to ``path`` with its runs ``stop`` seconds long and the
    outputs' settle times at most half of that [s]; returns ``path``."""
    data = tomllib.loads(SWEEP.read_text())
    data["experiment"] = {**data.get("experiment", {}), "stop": stop}
    for output in data["outputs"]:
        output["settle"] = min(output.get("settle", 0.0), stop / 2)
    path.write_text(f"# {SWEEP.name} with runs of {stop:g} s (guideway-fmu demo)\n"
                    + tomli_w.dumps(data))
    return path


def _sweep(out_dir: Path, fmu_dir: Path, stop: float) -> dict:
    """The shortened example sweep into out_dir/envelope_vs_frequency; its summary."""
    folder = out_dir / "envelope_vs_frequency"
    spec = sweep_file.load(shortened_sweep(out_dir / "envelope_vs_frequency.toml", stop), fmu_dir)
    (folder / "results.csv").unlink(missing_ok=True)  # a new sweep, not the last demo's
    start = time.perf_counter()
    with sweep_run.dask_client(SWEEP_WORKERS) as client:
        outcome = sweep_run.run_sweep(spec, folder, client, progress=False)
    return {"file": "envelope_vs_frequency.toml", "folder": folder.name, "points": outcome.points,
            "workers": SWEEP_WORKERS,
            "ok": outcome.ok, "failed": outcome.failed,
            "wall_time_s": time.perf_counter() - start,
            "plots": [str(Path(p).relative_to(out_dir)) for p in outcome.files if p.endswith(".png")]}


def run_demo(out_dir: Path, fmus: Path | None = None, stop: float = 0.02,
             progress: bool = False) -> dict:
    """Take the FMUs from the cache (or ``fmus``, built where needed), draw the stiffness curves,
    run three paper scenarios for ``stop`` seconds each (results, plots), verify one against the
    monolithic reference, diagnose a generated measured run, sweep the example's points for
    ``stop`` seconds each and write index.html; returns the summary (also in summary.json).
    ``progress``: a bar of these steps on stderr."""
    if not stop > 0:
        raise ValueError(f"'stop' must be > 0 s, got {stop}")
    with stages("demo", total=6 + len(DEMO_SCENARIOS), enabled=progress) as begin:
        return _demo(out_dir, fmus, stop, begin)


def _demo(out_dir: Path, fmus: Path | None, stop: float, begin) -> dict:
    """The steps of :func:`run_demo`, each announced by ``begin(name)``."""
    out_dir.mkdir(parents=True, exist_ok=True)
    begin("the FMUs (from the cache, built where missing)")
    fmu_dir = cache.folder() if fmus is None else build.ensure(fmus)
    begin("stiffness curves through the contact FMUs")
    curves = stiffness_curves(fmu_dir, np.linspace(-5e-6, 5e-6, 101))
    np.savetxt(out_dir / "stiffness.csv", np.column_stack(list(curves.values())), delimiter=",",
               header=",".join(curves), comments="")
    _plot_stiffness(curves, out_dir / "stiffness.png")
    summary = {
        "stiffness_at_y0_lubricated_N_per_m": float(np.interp(0.0, curves["y"], curves["K_lubricated"])),
        "stiffness_at_y0_dry_N_per_m": float(np.interp(0.0, curves["y"], curves["K_dry"])),
        "runs": {},
    }
    for name in DEMO_SCENARIOS:
        begin(f"run {name}")
        scenario = system.load(scenarios.find(name), fmu_dir).with_changes(stop=stop)
        result = run.run(scenario, out_dir / name, progress=False)
        rec = result.recording
        freq, amp = plots.spectrum(rec.time, rec.columns["Carriage.y"])
        band = freq > 1000.0
        summary["runs"][name] = {
            "steps": result.steps, "wall_time_s": result.wall_time,
            "dominant_frequency_above_1kHz_Hz": float(freq[band][np.argmax(amp[band])]),
            "F_upper_range_N": [float(rec.columns["Contact.F_upper"].min()),
                                float(rec.columns["Contact.F_upper"].max())],
            "h_upper_range_m": [float(rec.columns["Contact.h_upper"].min()),
                                float(rec.columns["Contact.h_upper"].max())]}
    begin(f"verify {VERIFIED}")
    report = verify.verify(system.load(scenarios.find(VERIFIED), fmu_dir).with_changes(stop=stop))
    (out_dir / "verify.json").write_text(json.dumps(report, indent=2))
    summary["verify"] = {VERIFIED: {"rms_error_Contact.F_upper": report["rms_error"]["Contact.F_upper"],
                                    "wall_time_cosim_s": report["wall_time_cosim"],
                                    "wall_time_reference_s": report["wall_time_reference"]}}
    begin("diagnose the bundled measured run")
    example = out_dir / "diagnose_example" / "run"
    example.mkdir(parents=True, exist_ok=True)
    for name in ("rig.toml", "data.csv"):
        shutil.copyfile(EXAMPLES / "measured_run" / name, example / name)
    diagnosis = workflow.diagnose(out_dir / "diagnose_example" / "run", out_dir / "diagnose_example",
                                  fmu_dir=fmu_dir)
    summary["diagnose"] = {"hidden_effect": HIDDEN_EFFECT,
                           **{k: diagnosis[k] for k in ("missing_effect", "gap_before", "gap_after",
                                                        "noise_floor")}}
    begin("sweep the example's points")
    summary["sweep"] = _sweep(out_dir, fmu_dir, stop)
    begin("write index.html")
    page.write_index(out_dir, fmus, fmu_dir, stop, summary, DEMO_SCENARIOS, VERIFIED)
    summary["files"] = sorted(str(p.relative_to(out_dir)) for p in out_dir.rglob("*") if p.is_file())
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary
