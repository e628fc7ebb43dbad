"""The converters of public friction records (orchestration/real_data/convert_*.py) write runs that
load as measured runs.

The raw files are found through GUIDEWAY_FMU_REAL_RAW: a folder with one subfolder per data set,
named like the converter's short name (``mnich_rack_pinion/``, ``tud_pneumatic_seals/``), each
holding that data set as fetched (orchestration/real_data/README.md says from where). Without the
variable or the subfolder the test skips and says which. No diagnosis here: only conversion and
loading, which take a few seconds.
"""
from __future__ import annotations

import importlib.util
import os
import warnings
from pathlib import Path

import numpy as np
import pytest

from guideway_fmu.diagnose.run_io import load_run

CONVERTERS = Path(__file__).resolve().parents[2] / "orchestration" / "real_data"
RAW = os.environ.get("GUIDEWAY_FMU_REAL_RAW")

#: short name -> (least number of runs, output channel, moving_mass, stated friction sign)
EXPECTED = {
    "mnich_rack_pinion": (1, "drive_force", 24.7, None),
    "tud_pneumatic_seals": (50, "friction_force", 0.0, "along_motion"),
}


def converter(short_name: str):
    path = CONVERTERS / f"convert_{short_name}.py"
    spec = importlib.util.spec_from_file_location(f"convert_{short_name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


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
