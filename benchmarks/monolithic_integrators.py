"""Wall time, nfev and accuracy of the monolithic reference's integrators.

Runs the unloaded rig and the rig under a 9000 N / 4500 Hz harmonic load over 0.01 s with
LSODA, Radau and DOP853 at rtol 1e-8 and 1e-10, and prints for each run the wall time (the least of a few runs), the
wall time per simulated second, nfev and the RMS difference of Contact.F_upper from a DOP853 run
at rtol 1e-12, relative to the range of F_upper. Usage:
``python benchmarks/monolithic_integrators.py [FMU folder, default fmus]``.
"""
import sys
import tempfile
from pathlib import Path

import numpy as np

from guideway_fmu.reference import monolithic
from guideway_fmu.cosim import system

REPEAT = 2  # further runs of those shorter than 3 s: the wall time printed is the least

RIG = """
[experiment]
start = 0.0
stop = 0.01
step = 2e-6
[components.Feed]
fmu = "{fmus}/FeedKinematics.fmu"
[components.Contact]
fmu = "{fmus}/ContactEHL.fmu"
[components.Carriage]
fmu = "{fmus}/VerticalDynamics.fmu"
parameters = {{ load_amplitude = {amplitude}, load_frequency = 4500.0 }}
[components.Friction]
fmu = "{fmus}/FrictionMixedEHL.fmu"
""" + "".join(f'[[connections]]\nfrom = "{a}"\nto = "{b}"\n' for a, b in [
    ("Feed.u", "Contact.u"), ("Feed.u", "Friction.u"), ("Carriage.y", "Contact.y"),
    ("Carriage.y_dot", "Contact.y_dot"), ("Contact.F_contact", "Carriage.F_contact"),
    *((f"Contact.{v}", f"Friction.{v}") for v in ("F_upper", "F_lower", "h_upper", "h_lower"))])


def main(fmus: Path) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        for label, amplitude in (("unloaded", 0.0), ("9000 N / 4500 Hz", 9000.0)):
            path = Path(tmp) / "rig.toml"
            path.write_text(RIG.format(fmus=fmus.resolve().as_posix(), amplitude=amplitude))
            rig = system.load(path)
            best = monolithic.simulate(rig, rtol=1e-12, method="DOP853").columns["Contact.F_upper"]
            span = np.ptp(best)
            print(f"{label}: F_upper range {span:.4g} N")
            print(f"{'method':8} {'rtol':>6} {'wall [s]':>9} {'wall/sim s':>11} {'nfev':>8} {'rms diff':>9}")
            for method in ("LSODA", "Radau", "DOP853"):
                for rtol in (1e-8, 1e-10):
                    r = monolithic.simulate(rig, rtol=rtol, method=method)
                    wall = min([r.wall_time] + [monolithic.simulate(rig, rtol=rtol, method=method)
                                                .wall_time for _ in range(REPEAT if r.wall_time < 3 else 0)])
                    rms = np.sqrt(np.mean((r.columns["Contact.F_upper"] - best) ** 2)) / span
                    sim = r.time[-1] - r.time[0]
                    print(f"{method:8} {rtol:6.0e} {wall:9.3f} {wall / sim:11.1f} "
                          f"{r.nfev:8d} {rms:9.1e}")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "fmus"))
