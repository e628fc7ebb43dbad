"""Drive the guideway FMUs with fmpy alone, the way you would in your own tool.

Three FMUs (FeedKinematics, VerticalDynamics, ContactEHL) are wired as in
scenarios/soleimanian2020_9000N_4500Hz.toml and stepped with a stabilised Gauss-Seidel loop:

    Feed --u--------------------------> Contact
    Carriage --y, y_dot-------------------> Contact
    Contact --F_contact, C_contact, law_*--> Carriage   (law_*: the contact's force law)

Nothing from guideway_fmu is imported: only fmpy and the .fmu files (which need numpy and scipy
in this interpreter, because they are pythonfmu FMUs).

    python drive_with_fmpy.py                  # 0.01 s, writes ../out/drive_with_fmpy.csv
    python drive_with_fmpy.py --explicit       # without the tangents: watch it blow up
"""
from __future__ import annotations

import argparse
import csv
import math
import shutil
import sys
from pathlib import Path

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

from guideway_fmu.cosim.interrupts import exit_without_finalising

HERE = Path(__file__).resolve().parent
STEP = 2e-6  # s, macro step h (the contact resonance is ~6.6 kHz: omega*h ~ 0.08)
BLOW_UP = 1e-3  # m, |Carriage.y| beyond this is no longer a guideway (normal: ~15 um here)
GROWTH = 2.0  # max |y| of the last fifth of the run over that of the first fifth: "unstable"
JUDGE = 3e-3  # s, shortest run whose growth is judged: the explicit growth e-folds in ~3 ms
LAW = tuple(f"law_{n}" for n in ("force_1um", "exponent", "sine", "approach_upper",
                                 "approach_lower", "rate_upper", "rate_lower"))


class Instance:
    """One FMU instance with its Real variables by name."""

    def __init__(self, path: Path, name: str):
        self.name, self.fmu, self.unzip = name, None, None
        md = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.unzip = extract(str(path))  # a temporary folder: removed in close()
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.unzip,
                             modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        self.fmu.instantiate()  # fmpy's default callbacks print the FMU's log messages

    def set(self, **values: float) -> None:
        self.fmu.setReal([self.vr[k] for k in values], list(values.values()))

    def get(self, *names: str) -> list[float]:
        return self.fmu.getReal([self.vr[n] for n in names])

    def step(self, t: float, h: float) -> None:
        self.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)

    def close(self) -> None:
        """Terminate and free the instance, then delete the extracted files."""
        if self.fmu is not None and getattr(self.fmu, "component", None) is not None:
            try:
                self.fmu.terminate()
            except Exception:  # noqa: BLE001 - a failed instance may refuse; free it anyway
                pass
            self.fmu.freeInstance()
        if self.unzip is not None:
            shutil.rmtree(self.unzip, ignore_errors=True)


def run(fmus: Path, stop: float, explicit: bool, csv_path: Path) -> int:
    instances: list[Instance] = []
    rows: list[tuple] = []  # (time [s], Carriage.y [m], Contact.F_upper [N], Contact.h_upper [m])
    try:
        feed = Instance(fmus / "FeedKinematics.fmu", "Feed")
        instances.append(feed)
        body = Instance(fmus / "VerticalDynamics.fmu", "Carriage")
        instances.append(body)
        contact = Instance(fmus / "ContactEHL.fmu", "Contact")
        instances.append(contact)

        # -- initialisation: sources first, so the contact starts from their outputs ----------
        for inst in instances:
            inst.fmu.setupExperiment(startTime=0.0, stopTime=stop)
            inst.fmu.enterInitializationMode()
        # Feed keeps its defaults: the rig's bi-harmonic feed at 5 Hz (Soleimanian et al. 2020, eq. 1a)
        feed.fmu.exitInitializationMode()
        body.set(load_amplitude=9000.0, load_frequency=4500.0)  # N, Hz: harmonic external load
        body.fmu.exitInitializationMode()
        # The contact's film starts from y, y_dot and u as set before initialisation ends.
        # Stepping after the body, it gets the body's state at the END of each step: with
        # interpolate_inputs its films follow the body's motion over the step (Hermite curve).
        y, y_dot = body.get("y", "y_dot")  # m, m/s
        (u,) = feed.get("u")  # m/s
        contact.set(y=y, y_dot=y_dot, u=u)
        contact.fmu.setBoolean([contact.vr["interpolate_inputs"]], [not explicit])
        contact.fmu.exitInitializationMode()

        outputs = ("F_contact", "C_contact", "F_upper", "h_upper", *LAW)
        f_c, c_c, f_up, h_up, *law = contact.get(*outputs)  # N, N.s/m, N, m, law
        rows.append((0.0, y, f_up, h_up))

        # -- stabilised Gauss-Seidel: each macro step uses the newest outputs -----------------
        # The contact is stiff (K_contact ~ 5.7e9 N/m on 3.3 kg, ~6.6 kHz) and undamped (its
        # `damping` parameter is 0, so C_contact = 0). Holding F_contact constant over a step
        # (explicit coupling: K_contact = C_contact = 0 at the Carriage) feeds energy in every step:
        # a spring-mass split over two FMUs that way is stable only for omega*h < 4*zeta, never
        # for zeta = 0, whatever h. Passing the tangents lets the Carriage integrate
        # F ~ F_contact + K_contact dy + C_contact dy_dot over the step instead: stable for any h
        # (exact for a linear spring). Better still, the contact's own force law (law_*: two
        # opposed rows of rollers whose films move at their present rates) lets the Carriage
        # evaluate the exact frozen-film force at every instant of the step, lift-off and
        # re-contact included. `--explicit` passes none of it to show the difference.
        n = round(stop / STEP)
        for i in range(n):
            t = i * STEP
            feed.step(t, STEP)
            (u,) = feed.get("u")
            if explicit:
                body.set(F_contact=f_c)
            else:
                body.set(F_contact=f_c, C_contact=c_c, **dict(zip(LAW, law)))
            body.step(t, STEP)
            y, y_dot = body.get("y", "y_dot")
            contact.set(y=y, y_dot=y_dot, u=u)
            contact.step(t, STEP)
            f_c, c_c, f_up, h_up, *law = contact.get(*outputs)
            rows.append(((i + 1) * STEP, y, f_up, h_up))
            if not math.isfinite(y) or abs(y) > BLOW_UP:
                print(f"UNSTABLE: |Carriage.y| = {abs(y):.3g} m > {BLOW_UP:g} m at t = {rows[-1][0]:.6g} s "
                      f"after {i + 1} steps; stopped early.")
                break
    except Exception as exc:  # an FMU that rejects a step raises here
        if explicit and rows:
            print(f"UNSTABLE: an FMU failed at t = {rows[-1][0]:.6g} s ({exc}); "
                  f"last |Carriage.y| = {abs(rows[-1][1]):.3g} m.")
        else:
            print(f"error: {exc}", file=sys.stderr)
            return 1
    finally:
        for inst in reversed(instances):
            inst.close()

    csv_path.parent.mkdir(parents=True, exist_ok=True)
    with csv_path.open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["time", "Carriage.y", "Contact.F_upper", "Contact.h_upper"])  # s, m, N, m
        writer.writerows(rows)
    f_upper = [r[2] for r in rows]
    # growth of the displacement: max |y| over the last fifth of the run against the first fifth
    fifth = max(1, len(rows) // 5)
    y_first = max(abs(r[1]) for r in rows[:fifth])
    y_last = max(abs(r[1]) for r in rows[-fifth:])
    print(f"{'explicit' if explicit else 'stabilised'} coupling, {len(rows) - 1} steps of {STEP:g} s "
          f"to t = {rows[-1][0]:.6g} s -> {csv_path}")
    print(f"Contact.F_upper: min {min(f_upper):.2f} N, max {max(f_upper):.2f} N")
    print(f"max |Carriage.y|: {y_first:.3g} m in the first fifth, {y_last:.3g} m in the last fifth")
    if y_last > BLOW_UP or rows[-1][0] >= JUDGE and y_last > GROWTH * y_first:
        print("UNSTABLE: the displacement grows without bound")
    elif rows[-1][0] >= JUDGE:
        print("stable: the displacement stays bounded")
    else:  # in shorter runs the start-up transient can look like growth
        print(f"run shorter than {JUDGE:g} s: too short to judge stability")
    return 0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--fmus", type=Path, default=HERE.parent / "fmus", help="folder of the .fmu files")
    p.add_argument("--stop", type=float, default=0.01, help="simulated time [s] (default 0.01)")
    p.add_argument("--explicit", action="store_true",
                   help="do not pass the contact's law to the Carriage (shows the instability)")
    p.add_argument("--csv", type=Path, default=HERE.parent / "out" / "drive_with_fmpy.csv",
                   help="output CSV (default ../out/drive_with_fmpy.csv)")
    args = p.parse_args(argv)
    if not args.stop >= STEP:
        p.error(f"--stop must be >= {STEP} s")
    return run(args.fmus, args.stop, args.explicit, args.csv)


if __name__ == "__main__":
    exit_without_finalising(main() or 0)  # FMUs loaded: see guideway_fmu.cosim.interrupts
