"""What a run leaves in its folder says what happened and cannot be misread: summary.json carries
the error of any failure (it said ``"error": null, "steps": 0`` when instantiation failed), is
strict JSON (it held ``"max_step": Infinity``) replaced whole, and records what results.csv
holds, so that a file cut by a full disk or a file-size limit is refused by the reader
(run.read) instead of parsing as a wrong value; a write that fails names the file. The probe FMU
`Faulty` is in tests/conftest.py."""
from __future__ import annotations

import errno
import json
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

import guideway_fmu
from guideway_fmu.cosim import master, run as run_module, system
from guideway_fmu.cosim.run import read, run, write_json
from support import probe_scenario


def strict(text: str) -> dict:
    """``text`` parsed as strict JSON: NaN, Infinity and -Infinity are refused."""
    def refuse(constant):
        raise ValueError(f"not strict JSON: {constant}")
    return json.loads(text, parse_constant=refuse)


def test_a_failed_instantiation_is_the_error_of_the_summary(tmp_path, faulty):
    broken = tmp_path / "Broken.fmu"  # the probe without its binaries
    with zipfile.ZipFile(faulty) as src, zipfile.ZipFile(broken, "w") as dst:
        for item in src.infolist():
            if not item.filename.startswith("binaries/"):
                dst.writestr(item, src.read(item))
    with pytest.raises(master.SimulationError, match="probe: cannot instantiate R from"):
        run(system.load(probe_scenario(tmp_path, broken, stop=0.03)), tmp_path / "out", progress=False)
    summary = strict((tmp_path / "out" / "summary.json").read_text())
    assert summary["error"].startswith(f"probe: cannot instantiate R from {broken}")
    assert summary["steps"] == 0 and summary["results"] == {"rows": 0, "bytes": 10}  # the header


def test_the_summary_is_strict_json_with_non_finite_numbers_as_strings(tmp_path, faulty):
    run(system.load(probe_scenario(tmp_path, faulty, stop=0.03)), tmp_path / "out", progress=False)
    summary = strict((tmp_path / "out" / "summary.json").read_text())
    assert summary["experiment"]["max_step"] == "inf"  # the defaults: no bound, no timeout
    assert summary["experiment"]["step_timeout"] == "inf"
    assert summary["error"] is None and summary["steps"] == 30
    assert [p.name for p in (tmp_path / "out").iterdir() if p.name.startswith(".summary")] == []


def test_a_summary_that_cannot_be_written_names_it_and_leaves_the_former_one_whole(
        tmp_path, monkeypatch):
    path = tmp_path / "summary.json"
    write_json(path, {"steps": 1})

    def full(fd):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(run_module.os, "fsync", full)
    with pytest.raises(OSError, match=f"cannot write {path}: No space left on device"):
        write_json(path, {"steps": 2})
    assert strict(path.read_text()) == {"steps": 1}
    assert [p.name for p in tmp_path.iterdir()] == ["summary.json"]  # no temporary file left


def test_read_gives_the_recording_back_and_refuses_a_cut_or_changed_results_file(tmp_path,
                                                                                faulty):
    result = run(system.load(probe_scenario(tmp_path, faulty, stop=0.03)), tmp_path / "out", progress=False)
    out = tmp_path / "out"
    recording, summary = read(out)
    assert np.array_equal(recording.time, result.recording.time)
    assert np.array_equal(recording.columns["R.x"], result.recording.columns["R.x"])
    assert summary["results"]["rows"] == 31 and recording.units == {"R.x": ""}
    whole = (out / "results.csv").read_bytes()
    for cut in (whole[:-1], whole[:whole.rindex(b"\n", 0, len(whole) - 1) + 1]):
        (out / "results.csv").write_bytes(cut)  # mid-number, and at a row's end
        with pytest.raises(ValueError, match=rf"{out / 'results.csv'}: {len(cut)} bytes, but "
                                             rf"the run wrote {len(whole)} \(31 rows\): the file "
                                             r"was cut"):
            read(out)
    (out / "results.csv").write_bytes(whole.replace(b"0.001,", b"0.001;"))  # same size
    with pytest.raises(ValueError, match="results.csv: not rows of numbers"):
        read(out)
    (out / "summary.json").unlink()
    with pytest.raises(FileNotFoundError, match="summary.json not found"):
        read(out)


LIMIT = 8192  # bytes: RLIMIT_FSIZE of the child's run, results.csv needs ~4 times that
CHILD = f"""
import resource
import sys
from guideway_fmu import cli
from guideway_fmu.cosim import recording

recording.FLUSH_ROWS = 100
started = recording.Recorder.started


def limited(recorder, system, bus):  # the FMU is unpacked by now
    resource.setrlimit(resource.RLIMIT_FSIZE, ({LIMIT}, resource.RLIM_INFINITY))
    started(recorder, system, bus)


recording.Recorder.started = limited
sys.exit(cli.main(sys.argv[1:]))
"""


def test_a_file_size_limit_ends_the_run_naming_the_file_and_the_summary_says_what_it_holds(
        tmp_path, faulty):
    out = tmp_path / "out"
    env = {**os.environ, "PYTHONPATH": str(Path(guideway_fmu.__file__).parents[1])}
    child = subprocess.run(
        [sys.executable, "-c", CHILD, "run", str(probe_scenario(tmp_path, faulty, stop=2.0)), "--out",
         str(out), "--no-progress"], capture_output=True, text=True, env=env, timeout=120)
    assert child.returncode == 2, child.stderr[-2000:]
    assert f"guideway-fmu run: error: probe: cannot write {out / 'results.csv'}: File too large; " \
           "it keeps the first " in child.stderr and "Traceback" not in child.stderr
    summary = strict((out / "summary.json").read_text())
    kept = summary["results"]["rows"]
    assert 100 <= kept < 2001 and kept % 100 == 0  # whole flushes of 100 rows
    assert summary["error"].startswith(f"probe: cannot write {out / 'results.csv'}")
    recording, _ = read(out)  # what is there is whole, and says so
    assert np.allclose(recording.time, np.arange(kept) * 0.001)
    assert (out / "results.csv").stat().st_size <= LIMIT
