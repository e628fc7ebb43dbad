from pathlib import Path

import pytest

from guideway_fmu.cosim import gauss_seidel
from guideway_fmu.cosim.fmu_instance import FmuInstance


def test_fmu_instance_refuses_missing_file_and_unknown_variable(fmu_dir, tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.fmu"):
        FmuInstance(tmp_path / "nope.fmu", "x")
    inst = FmuInstance(fmu_dir / "FrictionCoulomb.fmu", "fric")
    with pytest.raises(KeyError, match="F_magic"):
        inst.get("F_magic")
    inst.close()


def test_fmu_instance_close_removes_extracted_files(fmu_dir):
    inst = FmuInstance(fmu_dir / "FrictionCoulomb.fmu", "fric")
    unzipped = inst._unzip
    inst.close()
    assert not Path(unzipped).exists()


def test_run_names_the_failing_instance_and_time(fmu_dir):
    body = FmuInstance(fmu_dir / "VerticalDynamics.fmu", "body")
    body.initialise(0.0)
    body.set("K_contact", -1.0)  # refused by the FMU: doStep discards
    with pytest.raises(RuntimeError, match=r"'body' failed its step at t = 0 s"):
        gauss_seidel.run({"body": body}, [], ["body"], 0.0, 1e-3, 1e-4, ["body.y"])
    body.close()


def test_run_refuses_bad_step(fmu_dir):
    body = FmuInstance(fmu_dir / "VerticalDynamics.fmu", "body")
    body.initialise(0.0)
    with pytest.raises(ValueError, match="step > 0"):
        gauss_seidel.run({"body": body}, [], ["body"], 0.0, 1e-3, -1e-4, ["body.y"])
    body.close()
