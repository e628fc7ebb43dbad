"""Write the wear scenario of Zhang, Wang and Jiang (fractal-creep wear of a linear ball guide)
into the package (src/guideway_fmu/scenarios/).

The 5-DOF ball carriage of Wu et al. (2012) (BallCarriage5DOF) carries 300 N and its weight while
its raceways wear (Wear, the same balls in a four-row slider under the same load): the Wear FMU's
preload feeds the carriage's preload input, so the carriage sinks and softens as the preload
goes. Two time scales meet by compressing service time: the Service clock (FeedKinematics at
a constant 2e10 m/s) turns each co-simulation second into 2e10 m of running, so 0.1 s covers
2e9 m, past the preload loss at about 1.8e9 m. That is sound while the preload changes slowly
against the carriage's fastest period (0.2 ms): here by 0.1 N, 0.2 % of it, per period, and the
balls' damping lets the carriage settle; it then sits in the static equilibrium of the preload
of the moment (tests/cosim/test_wear_scenario.py checks it).
Built in code and written by the package's one scenario writer (``cosim.system.dump``).

    python orchestration/make_wear_scenarios.py   # then: guideway-fmu run wear_preload_loss
"""
from pathlib import Path

from guideway_fmu.cosim.system import Builder, dump
from guideway_fmu.physics.ball_guides import hertz_point
from guideway_fmu.scenarios import FOLDER

HEADER = "Written by orchestration/make_wear_scenarios.py; edit that script, not this file."
GRAVITY = 9.80665  # m/s^2
MASS = 0.313  # kg, the carriage of Wu et al. (2012) Table 1
BALL, CONFORMITY, BALLS, PRELOAD = 4.763e-3, 0.534, 9, 46.6  # the carriage's FMU defaults
LOAD = 300.0  # N toward the rail
RUNNING_SPEED = 2e10  # m of running per second of co-simulation


def scenarios() -> dict:
    """Every shipped scenario of this paper by name."""
    return {"wear_preload_loss": scenario()}


def scenario():
    deformation = float(hertz_point.approach(
        hertz_point.ball_constant(hertz_point.BallGroove(BALL, CONFORMITY)), PRELOAD))
    b = Builder("wear_preload_loss",
                "Zhang, Wang and Jiang: raceway wear takes the preload of the Wu et al. (2012) "
                "carriage under 300 N; service time compressed, 1 s = 2e10 m of running, the "
                "preload is lost near 1.8e9 m (0.09 s).")
    b.experiment(start=0.0, stop=0.1, step=1e-4, algorithm="gauss-seidel")
    b.component("Service", Path("FeedKinematics.fmu"), profile="constant",
                velocity=RUNNING_SPEED)
    youngs_modulus, poisson_ratio = hertz_point.STEEL  # the carriage's balls
    b.component("Wear", Path("Wear.fmu"), ball_diameter=BALL, conformity=CONFORMITY,
                balls_per_row=BALLS, initial_deformation=deformation, F_load=LOAD,
                youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio)
    b.component("Carriage", Path("BallCarriage5DOF.fmu"), static_F_z=-LOAD - MASS * GRAVITY)
    b.connect("Service.x", "Wear.distance")
    b.connect("Wear.preload", "Carriage.preload")
    b.record(["Service.x", "Wear.wear_depth", "Wear.preload_deformation", "Wear.preload",
              "Wear.vertical_displacement", "Carriage.v", "Carriage.row_load_1"])
    b.plots(time=["Wear.wear_depth", "Wear.preload", "Carriage.v", "Carriage.row_load_1"])
    return b.system(check_fmus=False)


if __name__ == "__main__":
    for name, system in scenarios().items():
        print(dump(system, FOLDER / f"{name}.toml", HEADER))
