"""Co-simulation against the monolithic reference: error of every shared output, wall times."""
from __future__ import annotations

import numpy as np

from . import monolithic
from ..cosim import master
from ..cosim.system import System


def compare(time, columns: dict, reference) -> tuple[dict, dict]:
    """RMS and peak error of each column against the reference's column of the same name at the
    same times, relative to the reference's range (max - min); columns it lacks are skipped."""
    rms, peak = {}, {}
    for name, values in columns.items():
        if name not in reference.columns:
            continue
        ref = np.interp(time, reference.time, reference.columns[name])
        span = float(np.ptp(ref))
        err = np.asarray(values) - ref
        scale = span if span > 0 else max(float(np.max(np.abs(ref))), 1e-300)
        rms[name] = float(np.sqrt(np.mean(err**2)) / scale)
        peak[name] = float(np.max(np.abs(err)) / scale)
    return rms, peak


def verify(system: System) -> dict:
    """Run the co-simulation and the reference on the same time grid and compare them; a system
    the reference cannot model is refused before the co-simulation runs."""
    monolithic.check(system)
    result = master.simulate(system)
    rec = result.recording
    reference = monolithic.simulate(system, times=rec.time)
    rms, peak = compare(rec.time, rec.columns, reference)
    return {"scenario": system.name, "algorithm": system.experiment.algorithm,
            "step": system.experiment.step, "steps": result.steps, "rejected": result.rejected,
            "rms_error": rms, "peak_error": peak,
            "wall_time_cosim": result.wall_time, "wall_time_reference": reference.wall_time,
            "fmi_call_time_cosim": result.fmi_time,
            "reference": {"method": reference.method, "rtol": reference.rtol, "nfev": reference.nfev}}


def format_table(report: dict) -> str:
    lines = [f"{report['scenario']}: {report['algorithm']}, step {report['step']:g} s, "
             f"{report['steps']} steps ({report['rejected']} rejected)",
             f"{'variable':32s} {'rms error':>10s} {'peak error':>10s}   (relative to range)"]
    for name, value in report["rms_error"].items():
        lines.append(f"{name:32s} {value:10.2e} {report['peak_error'][name]:10.2e}")
    ratio = report["wall_time_cosim"] / report["wall_time_reference"]
    lines.append(f"wall time: co-simulation {report['wall_time_cosim']:.2f} s, reference "
                 f"{report['wall_time_reference']:.2f} s ({report['reference']['method']}, rtol "
                 f"{report['reference']['rtol']:g}): ratio {ratio:.2f}")
    return "\n".join(lines)
