"""One writer per output folder (cosim/folder_lock.py): two runs into one ``--out`` both exited
0 over a results.csv with NUL bytes and rows of 10 and 11 fields. A second run, sweep or
diagnosis into a folder another one holds is refused naming the folder and leaves it as it was;
the lock is released on every way out. The probe FMU `Faulty` is in tests/conftest.py."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import guideway_fmu
from guideway_fmu import cli
from guideway_fmu.cosim import master, system
from guideway_fmu.cosim.folder_lock import LOCK_FILE, FolderInUse, folder_lock
from guideway_fmu.cosim.run import run
from support import probe_scenario


def test_a_run_into_a_folder_another_holds_is_refused_naming_it_and_leaves_it_intact(
        tmp_path, faulty, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "results.csv").write_text("time,R.x\n0.0,0.0\n")  # the other run's rows
    with folder_lock(out):
        assert cli.main(["run", str(probe_scenario(tmp_path, faulty)), "--out", str(out),
                         "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"guideway-fmu run: error: {out}: another run writes into this folder "
                          f"(process {os.getpid()} holds {out / LOCK_FILE})")
    assert (out / "results.csv").read_text() == "time,R.x\n0.0,0.0\n"
    assert sorted(p.name for p in out.iterdir()) == [LOCK_FILE, "results.csv"]


@pytest.mark.parametrize("fault", ["none", "raise"])
def test_the_lock_is_released_when_a_run_ends_or_fails(tmp_path, faulty, fault):
    s = system.load(probe_scenario(tmp_path, faulty, fault))
    if fault == "none":
        run(s, tmp_path / "out", progress=False)
    else:
        with pytest.raises(master.SimulationError):
            run(s, tmp_path / "out", progress=False)
    with folder_lock(tmp_path / "out"):  # free again
        pass


def test_a_sweep_and_a_diagnosis_into_a_held_folder_are_refused_before_writing(tmp_path):
    from guideway_fmu import examples
    from guideway_fmu.diagnose.workflow import diagnose
    from guideway_fmu.sweep.run import run_sweep

    out = tmp_path / "out"
    with folder_lock(out):
        with pytest.raises(FolderInUse, match=f"{out}: another run writes into this folder"):
            run_sweep(None, out, None)  # refused before it looks at the sweep or the cluster
        with pytest.raises(FolderInUse, match=f"{out}: another run writes into this folder"):
            diagnose(examples.FOLDER / "measured_run", out)  # read, then refused
    assert [p.name for p in out.iterdir()] == [LOCK_FILE]


@pytest.mark.slow  # child processes
def test_two_runs_started_into_one_folder_one_runs_the_other_is_refused(tmp_path, faulty):
    path = probe_scenario(tmp_path, faulty, "slow", stop=100.0)  # 10 ms of wall time a step
    env = {**os.environ, "PYTHONPATH": str(Path(guideway_fmu.__file__).parents[1])}
    command = [sys.executable, "-m", "guideway_fmu.cli", "run", str(path), "--out",
               str(tmp_path / "out"), "--no-progress"]
    first = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             env=env)
    try:
        results, deadline = tmp_path / "out" / "results.csv", time.monotonic() + 60
        while not (results.exists() and len(results.read_text().splitlines()) > 2):
            assert first.poll() is None and time.monotonic() < deadline, "no rows on disk"
            time.sleep(0.05)
        second = subprocess.run(command, capture_output=True, text=True, env=env, timeout=120)
        assert second.returncode == 2
        assert f"another run writes into this folder (process {first.pid} holds" in second.stderr
        first.send_signal(signal.SIGTERM)
        _, err = first.communicate(timeout=60)
        assert first.returncode == 143, err
    finally:
        if first.poll() is None:
            first.kill()
            first.communicate()
    lines = results.read_text().splitlines()
    assert lines[0] == "time,R.x" and all(len(line.split(",")) == 2 for line in lines[1:])
    assert "\0" not in results.read_text()
