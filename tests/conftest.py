"""Shared fixtures of the test suite."""
import os
from pathlib import Path

import pytest


def real_data_folder() -> Path:
    """The folder of real records (emps-identification/, emps-validation/): the one setting
    GUIDEWAY_FMU_DATA, by default data/real of the shared folder beside the repository."""
    default = Path(__file__).resolve().parents[2] / "shared" / "data" / "real"
    return Path(os.environ.get("GUIDEWAY_FMU_DATA", default))


@pytest.fixture(scope="session")
def fmu_dir(tmp_path_factory):
    """All FMUs, extensions included (and their README.md), built once per test session into a
    temporary folder."""
    from guideway_fmu.components.build import build

    out = tmp_path_factory.mktemp("fmus")
    build(out)
    return out
