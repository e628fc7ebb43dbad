"""The model-extension FMUs (HorizontalRig, Friction*) through fmpy: validation, hand values,
the same law as the vectorised physics, and bad parameters refused with a log naming them."""
from __future__ import annotations

import math

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from guideway_fmu.components import registry
from guideway_fmu.cosim.fmu_instance import FmuInstance
from guideway_fmu.physics.rigs import friction_laws as fl

LOADS = {"coefficient": 0.01, "rollers_per_groove": 10, "F_upper": 50.0, "F_lower": 50.0,
         "velocity_tolerance": 0.0}  # Coulomb level 0.01 * 2 * 10 * 100 = 20 N


@pytest.fixture
def instance(fmu_dir):
    opened = []

    def open_(name, **values):
        inst = FmuInstance(fmu_dir / f"{name}.fmu", f"{name}_{len(opened)}")
        opened.append(inst)
        inst.fmu.setupExperiment(startTime=0.0)
        inst.fmu.enterInitializationMode()
        for key, value in values.items():
            inst.set(key, value)
        inst.fmu.exitInitializationMode()
        return inst

    open_.opened = opened
    yield open_
    for inst in opened:
        inst.close()


@pytest.mark.parametrize("name", registry.names("diagnosis"))
def test_extension_fmu_passes_fmpy_validation(fmu_dir, name):
    assert validate_fmu(str(fmu_dir / f"{name}.fmu")) == []


def test_horizontal_rig_hand_calculation(instance):
    rig = instance("HorizontalRig", mass=2.0, drive_offset=0.5, a=3.0, F_friction=-5.0)
    assert rig.get("drive_force") == pytest.approx(2.0 * 3.0 + 5.0 + 0.5)
    assert rig.get("friction_force") == pytest.approx(5.0)


def test_stribeck_fmu_hand_calculation(instance):
    f = instance("FrictionStribeck", **LOADS, static_coefficient=0.015, stribeck_velocity=0.02,
                 viscous=100.0, u=0.02)
    # level 20 + (30 - 20) e^-1, viscous 100 * 0.02, opposing u > 0
    assert f.get("F_friction") == pytest.approx(-(20 + 10 * math.exp(-1) + 2.0), rel=1e-12)


def test_dahl_fmu_steps_like_vectorised_dahl_state(instance):
    x = np.array([0.0, 2e-6, 5e-6, 4e-6, 1e-6, 3e-6])
    f = instance("FrictionDahl", **LOADS, presliding_distance=2e-6, second_distance=1e-5,
                 second_share=0.25, z_start=0.0, x=0.0, u=0.0)
    got = [f.get("F_friction")]
    for k in range(1, x.size):
        f.set("x", float(x[k]))
        f.do_step(k * 1e-3, 1e-3)
        got.append(f.get("F_friction"))
    z = fl.dahl_state(x, np.array([2e-6, 1e-5]))
    np.testing.assert_allclose(got, -20.0 * (0.75 * z[:, 0] + 0.25 * z[:, 1]), rtol=1e-12, atol=1e-12)


def test_dahl_fmu_third_element_steps_like_vectorised_dahl_state(instance):
    x = np.array([0.0, 2e-6, 5e-6, 4e-6, 1e-6, 3e-6, 40e-6])
    f = instance("FrictionDahl", **LOADS, presliding_distance=2e-6, second_distance=1e-5,
                 second_share=0.25, third_distance=3e-5, third_share=0.5, z_start=0.0, x=0.0, u=0.0)
    got = [f.get("F_friction")]
    for k in range(1, x.size):
        f.set("x", float(x[k]))
        f.do_step(k * 1e-3, 1e-3)
        got.append(f.get("F_friction"))
    z = fl.dahl_state(x, np.array([2e-6, 1e-5, 3e-5]))
    np.testing.assert_allclose(got, -20.0 * (0.25 * z[:, 0] + 0.25 * z[:, 1] + 0.5 * z[:, 2]),
                               rtol=1e-12, atol=1e-12)


def test_preload_loss_fmu_accumulates_running_distance(instance):
    f = instance("FrictionPreloadLoss", **LOADS, loss=0.5, wear_distance=0.1, x=0.0, u=0.1)
    for k, x in enumerate([0.1, 0.05, 0.15]):  # running distance 0.1 + 0.05 + 0.1 = 0.25
        f.set("x", x)
        f.do_step(k * 1e-3, 1e-3)
    assert f.get("F_friction") == pytest.approx(-20.0 * (1 - 0.5 * (1 - math.exp(-2.5))), rel=1e-12)


@pytest.mark.parametrize("name, bad, text", [
    ("FrictionStribeck", {"stribeck_velocity": 0.0}, "stribeck_velocity"),
    ("FrictionDahl", {"presliding_distance": -1.0}, "presliding_distance"),
    ("FrictionDahl", {"second_share": 0.6, "third_share": 0.6}, "third_share"),
    ("FrictionPositionDependent", {"factors": "1 x 2"}, "factors"),
    ("FrictionBallToBall", {"table_end": -1.0}, "table_end"),
    ("HorizontalRig", {"mass": -1.0}, "mass"),
])
def test_bad_parameter_fails_initialisation_with_log_naming_it(instance, name, bad, text):
    with pytest.raises(FMICallException) as info:
        instance(name, **bad)
    assert info.value.status == 3  # fmi2Error of exitInitializationMode (before: OK, then a
    assert any(text in line for line in instance.opened[-1].log)  # discarded step)


@pytest.mark.parametrize("name", ["FrictionStribeck", "FrictionDahl", "FrictionPositionDependent",
                                  "FrictionPreloadLoss", "FrictionBallToBall", "FrictionCoulomb"])
@pytest.mark.parametrize("bad", [{"coefficient": math.nan}, {"coefficient": math.inf},
                                 {"coefficient": -0.01}, {"rollers_per_groove": 0},
                                 {"rollers_per_groove": -3}], ids=lambda b: f"{b}")
def test_bad_shared_friction_parameter_fails_initialisation_naming_it(instance, name, bad):
    """The issue-21 probe: these FMUs stepped OK with F_friction 0.0 for the whole run."""
    with pytest.raises(FMICallException) as info:
        instance(name, **bad)
    assert info.value.status == 3  # fmi2Error of exitInitializationMode
    assert any(next(iter(bad)) in line for line in instance.opened[-1].log)
