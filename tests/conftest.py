"""Shared fixtures of the test suite."""
import pytest


@pytest.fixture(scope="session")
def fmu_dir(tmp_path_factory):
    """All FMUs, extensions included (and their README.md), built once per test session into a
    temporary folder."""
    from guideway_fmu.components.build import build

    out = tmp_path_factory.mktemp("fmus")
    build(out)
    return out
