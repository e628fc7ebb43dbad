"""FMI semantics a host relies on: a DefaultExperiment in every FMU (fmpy falls back to 1 s
without one), and outputs in Initialization Mode equal to those right after it."""
from __future__ import annotations

import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Slave

from guideway_fmu.components import registry


@pytest.mark.parametrize("name", registry.names())
def test_every_fmu_declares_a_default_experiment(fmu_dir, name):
    experiment = read_model_description(str(fmu_dir / f"{name}.fmu")).defaultExperiment
    assert experiment is not None
    start, stop, step = (float(experiment.startTime), float(experiment.stopTime),
                         float(experiment.stepSize))
    assert start == 0.0 and stop > start and 0.0 < step < stop - start


def test_fmpy_runs_the_default_experiment_when_given_none(fmu_dir):
    result = simulate_fmu(str(fmu_dir / "FeedKinematics.fmu"))
    assert result["time"][-1] == pytest.approx(0.2, rel=1e-9)  # not fmpy's fallback of 1 s
    # fmpy records about 500 rows, at a whole number of the declared 4 us steps
    steps = (result["time"][1] - result["time"][0]) / 4e-6
    assert steps == pytest.approx(round(steps), abs=1e-6)


def _instance(fmu_dir, name):
    path = str(fmu_dir / f"{name}.fmu")
    md = read_model_description(path)
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=extract(path),
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="semantics")
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    return fmu, {v.name: v.valueReference for v in md.modelVariables}


@pytest.mark.parametrize("y", [0.0, 2e-6])
def test_contact_outputs_in_initialization_mode_are_those_after_it(fmu_dir, y):
    # the films are states set from y and u when initialization ends; a host that records
    # outputs in Initialization Mode (libcosim) read 0 m there and 2.3e-7 m after it
    fmu, vr = _instance(fmu_dir, "ContactEHL")
    names = ["h_upper", "h_lower", "F_upper", "F_lower", "F_contact"]
    try:
        fmu.enterInitializationMode()
        fmu.setReal([vr["y"], vr["u"]], [y, 0.29])
        during = fmu.getReal([vr[n] for n in names])
        fmu.exitInitializationMode()
        after = fmu.getReal([vr[n] for n in names])
        assert during[0] > 1e-7 and during[1] > 1e-7  # films of the rig at 0.29 m/s
        assert during == pytest.approx(after, rel=1e-12, abs=0.0)
    finally:
        fmu.terminate()
        fmu.freeInstance()
