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

RAISER = '''
from pythonfmu import Fmi2Causality, Fmi2Slave, Real


class Raiser(Fmi2Slave):
    """x = t; raises inside doStep once t reaches 5 ms."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.x = 0.0
        self.register_variable(Real("x", causality=Fmi2Causality.output))

    def do_step(self, current_time, step_size):
        if current_time >= 0.005:
            raise RuntimeError("the raiser's model broke at 5 ms")
        self.x = current_time + step_size
        return True
'''

CHILD = '''
import sys
from pathlib import Path
from guideway_fmu.cosim import master, system

s = (system.Builder("fatal").experiment(start=0.0, stop=0.01, step=0.001, algorithm="{algorithm}")
     .component("R", "{fmu}").component("Feed", "{feed}").system())
try:
    master.simulate(s)
except master.SimulationError as exc:
    rows = len(exc.result.recording.time)
    print(f"ROWS {{rows}}")
    print(exc, file=sys.stderr)
    sys.exit(3)
'''


@pytest.fixture(scope="module")
def raiser(tmp_path_factory):
    folder = tmp_path_factory.mktemp("raiser")
    (folder / "raiser.py").write_text(RAISER)
    return FmuBuilder.build_FMU(folder / "raiser.py", dest=folder / "Raiser.fmu")


@pytest.mark.parametrize("algorithm", ["jacobi", "stabilised"])
def test_fatal_fmu_is_reported_and_the_process_exits_cleanly(raiser, fmu_dir, algorithm):
    script = textwrap.dedent(CHILD.format(algorithm=algorithm, fmu=raiser,
                                          feed=fmu_dir / "FeedKinematics.fmu"))
    for _ in range(5):
        run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                             timeout=120)
        assert run.returncode == 3, (run.returncode, run.stderr[-2000:])
        assert "FMU instance 'R' failed at t = 0.005 s" in run.stderr
        assert "the raiser's model broke at 5 ms" in run.stderr
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


NAN_SOURCE = '''
from pythonfmu import Fmi2Causality, Fmi2Slave, Real


class NanSource(Fmi2Slave):
    """x = t until 5 ms, then NaN, with status OK."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.x = 0.0
        self.register_variable(Real("x", causality=Fmi2Causality.output))

    def do_step(self, current_time, step_size):
        end = current_time + step_size
        self.x = end if end < 0.005 - 1e-12 else float("nan")
        return True
'''


def test_nan_from_a_third_party_fmu_stops_the_run_naming_it(tmp_path, fmu_dir):
    from guideway_fmu.cosim import master, system

    (tmp_path / "nan_source.py").write_text(NAN_SOURCE)
    fmu = FmuBuilder.build_FMU(tmp_path / "nan_source.py", dest=tmp_path / "NanSource.fmu")
    s = (system.Builder("nan").experiment(start=0.0, stop=0.01, step=0.001, algorithm="jacobi")
         .component("S", fmu).component("Feed", fmu_dir / "FeedKinematics.fmu")
         .connect("S.x", "Feed.u_cmd").system())
    with pytest.raises(master.SimulationError,
                       match=r"FMU instance 'S' failed at t = 0.005 s: output x is nan"):
        master.simulate(s)
