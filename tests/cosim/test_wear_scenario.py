"""The shipped wear scenario: the Wear FMU's preload fed to the ball carriage on compressed
service time, against the wear physics and the carriage's statics."""
import numpy as np
import pytest

from guideway_fmu import scenarios
from guideway_fmu.components.ball_guides.carriage_5dof import BallCarriage5DOF
from guideway_fmu.cosim import master, system
from guideway_fmu.physics.ball_guides import carriage_5dof as bc
from guideway_fmu.physics.wear import raceway_wear
from guideway_fmu.reference import monolithic


@pytest.fixture(scope="module")
def run(fmu_dir):
    scenario = system.load(scenarios.find("wear_preload_loss"), fmu_dir=fmu_dir)
    return scenario, master.simulate(scenario).recording


@pytest.mark.slow
def test_preload_is_lost_where_the_wear_physics_puts_it(run):
    scenario, rec = run
    wear_parameters = scenario.components["Wear"].parameters
    guide = raceway_wear.Guide(ball_diameter=wear_parameters["ball_diameter"],
                       conformity=wear_parameters["conformity"],
                       balls_per_row=wear_parameters["balls_per_row"],
                       preload_deformation=wear_parameters["initial_deformation"],
                       youngs_modulus=wear_parameters["youngs_modulus"],
                       poisson_ratio=wear_parameters["poisson_ratio"])
    expected = raceway_wear.simulate(guide, wear_parameters["F_load"], 2e9, 3).preload_lost_at
    distance, preload = rec.columns["Service.x"], rec.columns["Wear.preload"]
    lost = distance[np.flatnonzero(preload == 0.0)[0]]
    step = np.diff(distance)[0]
    assert lost == pytest.approx(expected, abs=step)
    assert rec.columns["Wear.preload"][0] == pytest.approx(46.6, rel=1e-6)
    assert np.all(np.diff(preload) <= 0)


@pytest.mark.slow
def test_fast_carriage_follows_the_slow_preload_in_static_equilibrium(run):
    # the time compression is sound if the carriage sits where its statics put it for the
    # preload of the moment: its vertical displacement against the equilibrium of that preload
    scenario, rec = run
    parameters = {**BallCarriage5DOF(instance_name="c", resources=None).parameter_values(),
                  **scenario.components["Carriage"].parameters}
    parameters = {k: v for k, v in parameters.items() if k != "preload"}
    model = bc.from_parameters(**parameters)
    inputs = dict.fromkeys(bc.LOADS, 0.0) | {"u_feed": 0.0}
    for i in np.linspace(10, len(rec.time) - 1, 6).astype(int):
        preload = rec.columns["Wear.preload"][i - 1]  # held over the step that ended at i
        if preload <= 0.0:
            continue  # no equilibrium start without preload; the v after the loss is held
        static = model.initial_state(0.0, inputs | {"preload": preload})[1]
        assert rec.columns["Carriage.v"][i] == pytest.approx(static, rel=0.01)


def test_reference_refuses_the_distance_driven_wear_fmu_by_name(fmu_dir):
    scenario = system.load(scenarios.find("wear_preload_loss"), fmu_dir=fmu_dir)
    with pytest.raises(ValueError, match="'Wear'.*running-distance input"):
        monolithic.check(scenario)
