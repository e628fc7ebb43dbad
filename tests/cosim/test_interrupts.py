"""A run stopped from outside (SIGINT, SIGTERM) or by its step timeout, in child processes
running ``guideway-fmu run``: the rows computed so far are in results.csv, summary.json and
stderr name the cause and the time, the exit status tells which (130, 143, 124), and no folder
an FMU was unpacked into is left in the child's TMPDIR. The step timeout covers every FMI call
(it watched doStep only: a hang in initialisation ran for ever), and one SIGTERM ends a run
whose FMU never returns (it was only noted). The probe FMU `Faulty` is in tests/conftest.py."""
from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import guideway_fmu
from guideway_fmu.cosim.interrupts import GRACE_PERIOD
from support import probe_scenario

@pytest.fixture
def start(tmp_path, faulty):
    """start(fault, stop, step, extra, options): ``guideway-fmu run`` on the probe in a child
    with its own TMPDIR (tmp_path/tmp); killed after the test if it still runs."""
    children = []

    def launch(fault, stop, step, extra="", options=()):
        path = probe_scenario(tmp_path, faulty, fault, stop, step, extra)
        (tmp_path / "tmp").mkdir()
        env = {**os.environ, "TMPDIR": str(tmp_path / "tmp"),
               "PYTHONPATH": str(Path(guideway_fmu.__file__).parents[1])}
        children.append(subprocess.Popen(
            [sys.executable, "-m", "guideway_fmu.cli", "run", str(path), "--out",
             str(tmp_path / "out"), "--no-progress", *options],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL)))  # not ignored
        return children[-1]
    yield launch
    for child in children:
        if child.poll() is None:
            child.kill()
            child.communicate()


def rows_on_disk(tmp_path) -> np.ndarray:
    """The time column of results.csv, checking its header."""
    lines = (tmp_path / "out" / "results.csv").read_text().splitlines()
    assert lines[0] == "time,R.x"
    return np.array([float(line.split(",")[0]) for line in lines[1:]])


def ended(tmp_path, child, status):
    """The child's stderr and summary.json after it ended with ``status``, its TMPDIR empty."""
    _, err = child.communicate(timeout=60)
    assert child.returncode == status, err[-2000:]
    assert "Traceback" not in err
    assert list((tmp_path / "tmp").iterdir()) == []  # no unpacked FMU left behind
    return err, json.loads((tmp_path / "out" / "summary.json").read_text())


@pytest.mark.slow  # child processes
@pytest.mark.parametrize("signum, status", [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_a_signal_stops_the_run_keeping_its_results_and_naming_the_cause(start, tmp_path,
                                                                        signum, status):
    child = start("slow", stop=100.0, step=0.01)  # 10 ms of wall time a step: 100 s
    results, deadline = tmp_path / "out" / "results.csv", time.monotonic() + 60
    while not (results.exists() and len(results.read_text().splitlines()) > 2):
        assert child.poll() is None and time.monotonic() < deadline, "no rows on disk"
        time.sleep(0.05)
    seen = len(rows_on_disk(tmp_path))
    child.send_signal(signum)
    err, summary = ended(tmp_path, child, status)
    name = signal.Signals(signum).name
    found = re.search(rf"guideway-fmu run: probe: interrupted by {name} at t = (\S+) s$", err)
    assert found, err
    t = float(found[1])
    assert summary["error"] == f"probe: interrupted by {name} at t = {found[1]} s"
    times = rows_on_disk(tmp_path)
    assert len(times) >= seen and t < 100.0 and times[-1] == pytest.approx(t, abs=1e-12)
    assert np.allclose(np.diff(times), 0.01) and summary["time_span_s"] == [0.0, times[-1]]


@pytest.mark.slow  # child processes
@pytest.mark.parametrize("extra, options", [("", ("--step-timeout", "0.5")),
                                            ("step_timeout = 0.5", ())])
def test_a_step_that_outlasts_the_step_timeout_ends_the_run_naming_instance_time_and_limit(
        start, tmp_path, extra, options):
    child = start("hang", stop=0.01, step=0.001, extra=extra, options=options)
    err, summary = ended(tmp_path, child, 124)
    message = ("probe: FMU instance 'R' did not return from the step at t = 0.005 s within the "
               "step timeout of 0.5 s")
    assert message in err and summary["error"].startswith(message)
    assert np.allclose(rows_on_disk(tmp_path), np.arange(6) * 0.001)  # t = 0 ... 5 ms


def hanging(child) -> None:
    """Wait until the probe in ``child`` says it hangs."""
    for line in child.stderr:
        if line == "Faulty: hanging\n":
            return
    pytest.fail("the probe never hung")


@pytest.mark.slow  # child processes
def test_an_fmu_that_hangs_in_initialisation_meets_the_step_timeout(start, tmp_path):
    child = start("hang_init", stop=0.01, step=0.001, options=("--step-timeout", "0.5"))
    err, summary = ended(tmp_path, child, 124)
    message = ("probe: FMU instance 'R' did not return from fmi2ExitInitializationMode during "
               "initialisation within the step timeout of 0.5 s; the process ends without "
               "terminating or freeing the FMU instances")
    assert message in err and summary["error"] == message
    assert len(rows_on_disk(tmp_path)) == 0 and summary["results"]["rows"] == 0


@pytest.mark.slow  # child processes, and the grace period
@pytest.mark.parametrize("fault, where", [
    ("hang_init", "fmi2ExitInitializationMode during initialisation"),
    ("hang", "the step at t = 0.005 s")])
def test_one_sigterm_ends_a_run_whose_fmu_never_returns_after_the_grace_period(
        start, tmp_path, fault, where):
    child = start(fault, stop=0.01, step=0.001)
    hanging(child)
    child.send_signal(signal.SIGTERM)  # once, as a scheduler does
    err, summary = ended(tmp_path, child, 143)
    message = (f"probe: interrupted by SIGTERM, and FMU instance 'R' did not return from {where} "
               f"within the grace period of {GRACE_PERIOD:g} s; the process ends without "
               "terminating or freeing the FMU instances")
    assert message in err and summary["error"] == message
    kept = 6 if fault == "hang" else 0  # t = 0 ... 5 ms
    assert np.allclose(rows_on_disk(tmp_path), np.arange(kept) * 0.001)
    assert summary["results"]["rows"] == kept
