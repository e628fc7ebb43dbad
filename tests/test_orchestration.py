"""The example scripts in orchestration/, run as a user would: in a subprocess, on the FMUs built
for this session (``fmu_dir``), with short stop times."""
from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import pytest

from guideway_fmu import scenarios

pytestmark = pytest.mark.slow  # end-to-end: co-simulation or subprocess runs

ORCHESTRATION = Path(__file__).resolve().parents[1] / "orchestration"
PRELOAD_PER_ROLLER = 36800.0 / 80  # N, F0 shared by 4 grooves x 20 rollers


def _run(script: str, *args, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ORCHESTRATION / script), *map(str, args)],
                          cwd=cwd, capture_output=True, text=True, timeout=120)


def _column(path: Path, name: str) -> list[float]:
    with path.open(newline="") as f:
        return [float(row[name]) for row in csv.DictReader(f)]


def test_drive_with_fmpy_stabilised_starts_at_the_preload(fmu_dir, tmp_path):
    out = tmp_path / "drive.csv"
    proc = _run("drive_with_fmpy.py", "--fmus", fmu_dir, "--stop", 2e-4, "--csv", out, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "Contact.F_upper: min" in proc.stdout
    f_upper = _column(out, "Contact.F_upper")
    assert len(f_upper) == 101  # t = 0 and 100 macro steps of 2 us
    # At t = 0 the 9000 N load (sine) is still zero: the preload plus the film's extra approach
    # (about 144 N on the EHL film), then the rollers unload and reload but stay bounded.
    assert PRELOAD_PER_ROLLER < f_upper[0] < 1.5 * PRELOAD_PER_ROLLER
    assert min(f_upper) >= 0.0 and max(f_upper) < 2000.0


def test_drive_with_fmpy_explicit_coupling_is_reported_unstable(fmu_dir, tmp_path):
    args = ("--fmus", fmu_dir, "--stop", 5e-3)
    explicit = _run("drive_with_fmpy.py", *args, "--explicit", "--csv", tmp_path / "e.csv", cwd=tmp_path)
    stabilised = _run("drive_with_fmpy.py", *args, "--csv", tmp_path / "s.csv", cwd=tmp_path)
    assert explicit.returncode == 0 and stabilised.returncode == 0, explicit.stderr + stabilised.stderr
    assert "UNSTABLE" in explicit.stdout, explicit.stdout
    assert "stable: the displacement stays bounded" in stabilised.stdout, stabilised.stdout
    # the stabilised displacement stays at the ~15 um of the forced response; explicit grows past it
    y_stable = max(abs(y) for y in _column(tmp_path / "s.csv", "Carriage.y"))
    y_explicit = max(abs(y) for y in _column(tmp_path / "e.csv", "Carriage.y"))
    assert y_stable < 3e-5 and y_explicit > 3 * y_stable


def test_run_scenario_unloaded(fmu_dir, tmp_path):
    scenario = scenarios.find("soleimanian2020_unloaded")
    proc = _run("run_scenario.py", scenario, "--fmus", fmu_dir, "--stop", 2e-4,
                "--out", tmp_path / "out", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "soleimanian2020_unloaded: 50 steps (0 rejected)" in proc.stdout, proc.stdout  # 4 us
    # unloaded: every roller carries its preload share plus the film's extra approach (~144 N)
    f_upper = _column(tmp_path / "out" / "results.csv", "Contact.F_upper")
    assert all(PRELOAD_PER_ROLLER < f < 1.5 * PRELOAD_PER_ROLLER for f in f_upper)
    assert (tmp_path / "out" / "time.png").is_file()


def test_reference_sensitivity_reports_a_small_growing_change(fmu_dir, tmp_path):
    scenario = scenarios.find("soleimanian2020_9000N_2500Hz_dry")
    proc = _run("reference_sensitivity.py", scenario, "--fmus", fmu_dir, "--stop", 2e-3, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    report = json.loads(proc.stdout)
    assert report["scenario"] == "soleimanian2020_9000N_2500Hz_dry"
    # a 1e-12 m offset on a ~1 um approach: a change of order 1e-6 of the range, not zero
    assert 0 < report["rms_offset"] < 1e-4
    assert 0 < report["rms_rtol_1e-12"] < 1e-4
    assert 0 < report["rms_rtol_1e-09"] < 1e-3
    assert len(report["rms_offset_per_eighth"]) == 8
