"""The main job on built-in data: build the FMUs, paper 000's stiffness curves and a rig run.

1. Quasi-static stiffness K(y), lubricated (Fig. 3) and dry (Fig. 4), computed through the
   contact FMUs: each point is a fresh initialisation at displacement y (the EHL film starts at
   its steady value), K the central difference of the FMU's F_contact over y; the dry FMU's
   K_contact output is checked against it.
2. The unloaded rig (paper 000, "Unloaded case") as a co-simulation of FeedKinematics
   (bi-harmonic feed), ContactEHL, VerticalDynamics and FrictionMixedEHL through fmpy.
"""
from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import build  # noqa: E402
from .cosim import gauss_seidel  # noqa: E402
from .cosim.fmu_instance import FmuInstance  # noqa: E402
from .physics import carriage, film, guideway  # noqa: E402

RIG_SPEED = 0.29  # m/s, feed speed amplitude of the rig's bi-harmonic fit (eq. 1a)
PAPER_NATURAL_FREQUENCY = 6590.0  # Hz, paper 000, unloaded case


def rig_facts(u: float = RIG_SPEED) -> dict:
    """k, preload approach, films and natural frequencies of paper 000's rig at y = 0, feed speed u."""
    g, body = guideway.Guideway(), carriage.Body()
    state = guideway.quasi_static_state(g, 0.0, u)
    f_u, h_u = float(state[0]), float(state[2])
    k_lub = float(guideway.quasi_static_stiffness(g, 0.0, u, state=state))
    k_dry = float(guideway.quasi_static_stiffness(g, 0.0, lubricated=False))
    pan_hamrock = film.LineContact(model="pan_hamrock")

    def hz(k):
        return float(np.sqrt(k / body.mass) / (2 * np.pi))

    return {
        "roller_stiffness_k_N_per_m^(10/9)": g.k,
        "preload_per_roller_N": g.preload_per_roller,
        "preload_approach_delta0_m": g.delta0,
        "feed_speed_m_per_s": u,
        "film_extrapolated_at_y0_m": h_u,
        "film_pan_hamrock_at_y0_m": float(film.steady_film(pan_hamrock, f_u, u)),
        "roller_load_at_y0_N": f_u,
        "rail_mass_kg": body.mass,
        "stiffness_y0_lubricated_N_per_m": k_lub,
        "stiffness_y0_dry_N_per_m": k_dry,
        "natural_frequency_lubricated_Hz": hz(k_lub),
        "natural_frequency_dry_Hz": hz(k_dry),
        "paper_natural_frequency_Hz": PAPER_NATURAL_FREQUENCY,
    }


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


def rig_run(fmu_dir: Path, stop: float, step: float):
    """Unloaded rig of paper 000 through fmpy; returns the Recording."""
    names = {"feed": "FeedKinematics", "contact": "ContactEHL",
             "body": "VerticalDynamics", "friction": "FrictionMixedEHL"}
    inst = {k: FmuInstance(fmu_dir / f"{v}.fmu", k) for k, v in names.items()}
    C = gauss_seidel.Connection
    connections = [C("feed", "u", "contact", "u"), C("feed", "u", "friction", "u"),
                   C("body", "y", "contact", "y"), C("body", "y_dot", "contact", "y_dot"),
                   *[C("contact", v, "body", v) for v in ("F_contact", "K_contact", "C_contact")],
                   *[C("contact", v, "friction", v) for v in ("F_upper", "F_lower", "h_upper", "h_lower")]]
    for name in ("feed", "body", "contact", "friction"):
        for c in connections:
            if c.target == name:
                inst[name].set(c.input, inst[c.source].get(c.output))
        inst[name].initialise(0.0)
    record = ["feed.u", "body.y", "contact.F_upper", "contact.F_lower", "contact.h_upper",
              "contact.K_contact", "friction.F_friction"]
    try:
        return gauss_seidel.run(inst, connections, ["feed", "contact", "body", "friction"],
                                0.0, stop, step, record)
    finally:
        for i in inst.values():
            i.close()


def _plot_stiffness(curves, path: Path) -> None:
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, label, fig_no in zip(axes, ("lubricated", "dry"), (3, 4)):
        ax.plot(curves["y"] * 1e6, curves[f"K_{label}"] / 1e6)
        ax.set(title=f"{label} (paper 000 Fig. {fig_no})", xlabel="y [um]")
    axes[0].set_ylabel("K [N/um]")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _plot_run(rec, path: Path) -> None:
    signals = [("body.y", 1e6, "y [um]"), ("contact.F_upper", 1, "F_upper [N]"),
               ("contact.h_upper", 1e6, "h_upper [um]"), ("friction.F_friction", 1, "friction [N]")]
    fig, axes = plt.subplots(len(signals) + 1, 1, figsize=(8, 10))
    for ax, (name, scale, label) in zip(axes, signals):
        ax.plot(rec.time * 1e3, rec.columns[name] * scale)
        ax.set(ylabel=label)
    axes[-2].set_xlabel("t [ms]")
    y = rec.columns["body.y"] - rec.columns["body.y"].mean()
    freq = np.fft.rfftfreq(len(y), rec.time[1] - rec.time[0])
    axes[-1].semilogy(freq, np.abs(np.fft.rfft(y)) / len(y) * 2 + 1e-18)
    axes[-1].set(xlabel="f [Hz] (paper 000 Fig. 14)", ylabel="|Y| [m]", xlim=(0, 2e4))
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def run_demo(out_dir: Path, fmu_dir: Path, stop: float = 0.02, step: float = 5e-6) -> dict:
    """Build, compute, plot and write everything under ``out_dir``; returns the summary."""
    out_dir.mkdir(parents=True, exist_ok=True)
    build.build(fmu_dir)
    curves = stiffness_curves(fmu_dir, np.linspace(-5e-6, 5e-6, 101))
    stiff_csv = out_dir / "stiffness.csv"
    np.savetxt(stiff_csv, np.column_stack(list(curves.values())), delimiter=",",
               header=",".join(curves), comments="")
    _plot_stiffness(curves, out_dir / "stiffness.png")
    rec = rig_run(fmu_dir, stop, step)
    rec.write_csv(out_dir / "rig_unloaded.csv")
    _plot_run(rec, out_dir / "rig_unloaded.png")
    y = rec.columns["body.y"] - rec.columns["body.y"].mean()
    freq = np.fft.rfftfreq(len(y), step)
    spectrum = np.abs(np.fft.rfft(y))
    band = freq > 1000.0
    summary = {
        "stiffness_at_y0_lubricated_N_per_m": float(np.interp(0.0, curves["y"], curves["K_lubricated"])),
        "stiffness_at_y0_dry_N_per_m": float(np.interp(0.0, curves["y"], curves["K_dry"])),
        "rig_run": {"stop_s": stop, "step_s": step,
                    "dominant_frequency_above_1kHz_Hz": float(freq[band][np.argmax(spectrum[band])]),
                    "h_upper_range_m": [float(rec.columns["contact.h_upper"].min()),
                                        float(rec.columns["contact.h_upper"].max())]},
        "files": sorted(p.name for p in out_dir.iterdir()),
    }
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary
