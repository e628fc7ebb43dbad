"""An FMU that ends in fmi2Fatal (pythonfmu turns any Python exception inside a call into one):
the master reports it with the FMU's message and the time, writes what it recorded, and makes no
further call into any instance, which FMI forbids and which crashed the process (exit 139,
20 of 20 runs) after every file was written. Runs in child processes: a crash is the failure.
The probe FMU `Faulty` is in tests/conftest.py."""
from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import pytest

CHILD = '''
import sys
from pathlib import Path
from guideway_fmu.cosim import master, system

s = (system.Builder("fatal").experiment(start=0.0, stop=0.01, step=0.001, algorithm="{algorithm}")
     .component("R", "{fmu}", fault="{fault}").component("Feed", "{feed}").system())
try:
    master.simulate(s)
except master.SimulationError as exc:
    rows = len(exc.result.recording.time)
    print(f"ROWS {{rows}}")
    print(exc, file=sys.stderr)
    sys.exit(3)
'''


def fatal_run(faulty, fmu_dir, tmp_path, algorithm, fault, message, at="0.005"):
    """One child run failing after 5 ms of t = 0 ... 5 ms recorded: its report (failed at t =
    ``at`` s), and no unpacked FMU left in its TMPDIR."""
    script = textwrap.dedent(CHILD.format(algorithm=algorithm, fmu=faulty, fault=fault,
                                          feed=fmu_dir / "FeedKinematics.fmu"))
    scratch = tmp_path / "tmp"
    scratch.mkdir(exist_ok=True)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=120, env={**os.environ, "TMPDIR": str(scratch)})
    assert run.returncode == 3, (run.returncode, run.stderr[-2000:])
    assert f"FMU instance 'R' failed at t = {at} s" in run.stderr
    assert message in run.stderr
    assert "ROWS 6" in run.stdout  # t = 0 ... 5 ms recorded before the failure
    assert list(scratch.iterdir()) == []


@pytest.mark.slow  # child processes, five runs each
@pytest.mark.parametrize("algorithm", ["jacobi", "stabilised"])
def test_fatal_fmu_is_reported_and_the_process_exits_cleanly(faulty, fmu_dir, tmp_path, algorithm):
    for _ in range(5):
        fatal_run(faulty, fmu_dir, tmp_path, algorithm, "raise", "the faulty model broke at 5 ms")


@pytest.mark.parametrize("algorithm", ["jacobi", "stabilised"])
def test_a_getter_failing_mid_run_names_the_instance_and_the_step(faulty, fmu_dir, tmp_path,
                                                                  algorithm):
    # reported as "FMU instance None failed during initialisation" before; R.x is recorded
    # only, so it is first read (and fails) after the step from 5 ms (with the exchanged
    # outputs, every step being recorded): the values at 6 ms
    fatal_run(faulty, fmu_dir, tmp_path, algorithm, "get", "the faulty model's output broke",
              at="0.006")


def test_a_terminate_that_fails_after_a_run_that_went_well_fails_the_run(faulty, fmu_dir,
                                                                        tmp_path):
    # the run was reported a success: the failed fmi2Terminate was passed over in silence
    script = textwrap.dedent(CHILD.format(algorithm="jacobi", fmu=faulty, fault="terminate",
                                          feed=fmu_dir / "FeedKinematics.fmu"))
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=120, env={**os.environ, "TMPDIR": str(scratch)})
    assert run.returncode == 3, (run.returncode, run.stderr[-2000:])
    assert ("fatal: FMU instance 'R' failed at t = 0.01 s: fmi2Terminate failed with status 4 "
            "(fatal)") in run.stderr
    assert "the faulty model could not terminate" in run.stderr
    assert "ROWS 11" in run.stdout  # t = 0 ... 10 ms: every row
    assert list(scratch.iterdir()) == []


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


def test_the_progress_bar_of_a_failed_run_ends_where_it_stopped(faulty, capsys):
    from guideway_fmu.cosim import master, system

    s = (system.Builder("bar").experiment(start=0.0, stop=0.01, step=0.001, algorithm="jacobi")
         .component("S", faulty, fault="nan").system())
    with pytest.raises(master.SimulationError):
        master.simulate(s, progress=True)
    bar = capsys.readouterr().err
    assert "0.004/0.01 s" in bar and "0.01/0.01 s" not in bar  # last accepted step: 4 ms
