"""The converters of public friction records (orchestration/real_data/convert_*.py) write runs that
load as measured runs.

The raw files are found through GUIDEWAY_FMU_REAL_RAW: a folder with one subfolder per data set,
named like the converter's short name (``mnich_rack_pinion/``, ``tud_pneumatic_seals/``), each
holding that data set as fetched (orchestration/real_data/README.md says from where). Without the
variable or the subfolder the test skips and says which. No diagnosis here: only conversion and
loading, which take a few seconds.
"""
from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np
import pytest

from guideway_fmu.diagnose.run_io import load_run
from support import ORCHESTRATION, load_script

CONVERTERS = ORCHESTRATION / "real_data"
RAW = os.environ.get("GUIDEWAY_FMU_REAL_RAW")

#: short name -> (least number of runs, output channel, moving_mass, stated friction sign)
EXPECTED = {
    "mnich_rack_pinion": (1, "drive_force", 24.7, None),
    "tud_pneumatic_seals": (50, "friction_force", 0.0, "along_motion"),
}


def converter(short_name: str):
    """The converter of the data set ``short_name`` as a module."""
    return load_script(CONVERTERS / f"convert_{short_name}.py")


def raw_folder(short_name: str) -> Path:
    if not RAW:
        pytest.skip("GUIDEWAY_FMU_REAL_RAW is not set (a folder with one subfolder of raw files "
                    "per data set; see orchestration/real_data/README.md)")
    folder = Path(RAW) / short_name
    if not folder.is_dir():
        pytest.skip(f"no raw files for {short_name}: {folder} is not a folder")
    return folder


def test_every_converter_is_listed():
    found = {p.stem.removeprefix("convert_") for p in CONVERTERS.glob("convert_*.py")}
    assert found == set(EXPECTED)


@pytest.mark.parametrize("short_name", sorted(EXPECTED))
def test_converted_runs_load(short_name, tmp_path):
    raw = raw_folder(short_name)
    least, channel, mass, sign = EXPECTED[short_name]
    module = converter(short_name)
    assert module.SHORT_NAME == short_name
    runs = module.convert(raw, tmp_path)
    assert len(runs) >= least
    for run_dir in runs:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # every column is in the vocabulary
            run = load_run(run_dir)
        assert run.kind == "horizontal_drive"
        assert run.model == {"friction": "coulomb"}
        assert run.channel == channel
        assert run.moving_mass == pytest.approx(mass)
        assert run.friction_sign == sign
        assert run.time.size >= 500 and np.all(np.diff(run.time) > 0)
        motion = run.columns.get("feed_position", run.columns.get("feed_velocity"))
        assert np.ptp(motion) > 0
        force = run.columns[channel]
        assert 1.0 < np.ptp(force) < 1e4  # newtons, not volts or grams


def test_converter_refuses_a_folder_without_its_files(tmp_path):
    for short_name in EXPECTED:
        with pytest.raises(FileNotFoundError, match=str(tmp_path)):
            converter(short_name).convert(tmp_path, tmp_path / "out")


def test_report_refuses_to_run_without_the_real_records_folder_naming_the_setting(monkeypatch,
                                                                                 capsys):
    monkeypatch.delenv("GUIDEWAY_FMU_DATA", raising=False)
    with pytest.raises(SystemExit) as exit_:
        load_script(CONVERTERS / "report.py").main([])
    assert exit_.value.code == 2
    assert "set GUIDEWAY_FMU_DATA (or --data)" in capsys.readouterr().err


def test_report_recovers_the_level_and_the_even_slope_of_a_known_record(tmp_path):
    """report.py's own numbers beside the workflow's: the authors' friction range (2 Fc) and the
    slope of a force that does not turn with the motion, on strokes with both known."""
    report = load_script(CONVERTERS / "report.py")
    time = np.arange(0.0, 8.0, 0.01)
    position = 0.02 * (1.0 - np.cos(2.0 * np.pi * time / 2.0))  # 40 mm strokes
    moving_out = np.sin(2.0 * np.pi * time / 2.0) > 0.0
    force = np.where(moving_out, 5.0, -5.0) + 1.5 + 0.2 * position * 1e3  # Fc 5 N, 0.2 N/mm
    run = tmp_path / "run"
    run.mkdir()
    np.savetxt(run / "data.csv", np.c_[time, position, force], delimiter=",",
               header="time,feed_position,friction_force", comments="")
    assert report.authors_range(run) == pytest.approx(10.0, rel=0.1)
    assert report.even_slope(run) == pytest.approx(0.2, rel=1e-6)
