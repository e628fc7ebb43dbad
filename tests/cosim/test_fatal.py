"""An FMU that ends in fmi2Fatal (pythonfmu turns any Python exception inside a call into one):
the master reports it with the FMU's message and the time, writes what it recorded, and makes no
further call into any instance, which FMI forbids and which crashed the process (exit 139,
20 of 20 runs) after every file was written. Runs in child processes: a crash is the failure."""
from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest
from pythonfmu.builder import FmuBuilder

FAULTY = '''
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real, String


class Faulty(Fmi2Slave):
    """x = t; as `fault` says, raises inside the doStep that starts at 5 ms ("raise") or
    outputs NaN with status OK from the one that ends there ("nan")."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.x, self.fault = 0.0, "raise"
        self.register_variable(Real("x", causality=Fmi2Causality.output))
        self.register_variable(String("fault", causality=Fmi2Causality.parameter,
                                      variability=Fmi2Variability.tunable))

    def do_step(self, current_time, step_size):
        end = current_time + step_size
        if self.fault == "raise" and current_time >= 0.005 - 1e-12:
            raise RuntimeError("the faulty model broke at 5 ms")
        self.x = float("nan") if self.fault == "nan" and end >= 0.005 - 1e-12 else end
        return True
'''

CHILD = '''
import sys
from pathlib import Path
from guideway_fmu.cosim import master, system

s = (system.Builder("fatal").experiment(start=0.0, stop=0.01, step=0.001, algorithm="{algorithm}")
     .component("R", "{fmu}", fault="raise").component("Feed", "{feed}").system())
try:
    master.simulate(s)
except master.SimulationError as exc:
    rows = len(exc.result.recording.time)
    print(f"ROWS {{rows}}")
    print(exc, file=sys.stderr)
    sys.exit(3)
'''


@pytest.fixture(scope="module")
def faulty(tmp_path_factory):
    folder = tmp_path_factory.mktemp("faulty")
    (folder / "faulty.py").write_text(FAULTY)
    return FmuBuilder.build_FMU(folder / "faulty.py", dest=folder / "Faulty.fmu")


@pytest.mark.parametrize("algorithm", ["jacobi", "stabilised"])
def test_fatal_fmu_is_reported_and_the_process_exits_cleanly(faulty, fmu_dir, algorithm):
    script = textwrap.dedent(CHILD.format(algorithm=algorithm, fmu=faulty,
                                          feed=fmu_dir / "FeedKinematics.fmu"))
    for _ in range(5):
        run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                             timeout=120)
        assert run.returncode == 3, (run.returncode, run.stderr[-2000:])
        assert "FMU instance 'R' failed at t = 0.005 s" in run.stderr
        assert "the faulty model broke at 5 ms" in run.stderr
        assert "ROWS 6" in run.stdout  # t = 0 ... 5 ms recorded before the failure


def test_an_fmu_that_cannot_be_instantiated_leaves_no_extracted_folder(fmu_dir, tmp_path,
                                                                       monkeypatch):
    import tempfile
    import zipfile

    from guideway_fmu.cosim.fmu_instance import FmuInstance

    broken = tmp_path / "Broken.fmu"  # its modelIdentifier names no binary in the archive
    with zipfile.ZipFile(fmu_dir / "FeedKinematics.fmu") as src, \
            zipfile.ZipFile(broken, "w") as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename == "modelDescription.xml":
                data = data.replace(b'modelIdentifier="FeedKinematics"',
                                    b'modelIdentifier="NoSuchBinary"')
            dst.writestr(item, data)
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    with pytest.raises(Exception, match="NoSuchBinary"):  # fmpy names the missing library
        FmuInstance(broken, "B")
    assert list(scratch.iterdir()) == []


def test_nan_from_a_third_party_fmu_stops_the_run_naming_it(faulty, fmu_dir):
    from guideway_fmu.cosim import master, system

    s = (system.Builder("nan").experiment(start=0.0, stop=0.01, step=0.001, algorithm="jacobi")
         .component("S", faulty, fault="nan").component("Feed", fmu_dir / "FeedKinematics.fmu")
         .connect("S.x", "Feed.u_cmd").system())
    with pytest.raises(master.SimulationError,
                       match=r"FMU instance 'S' failed at t = 0.005 s: output x is nan"):
        master.simulate(s)
