"""Write the ball-guide scenario of Wu et al. (2012) into the package (src/guideway_fmu/scenarios/).

The carriage of the paper's Table 1 (BallCarriage5DOF, Hertz balls preloaded to its Table 2
stiffness at rest) under the pitch moment M_y = 2.90 N m, a yaw moment of 0.3 N m and its own weight, carried by a
point-to-point feed move of 30 mm at 0.3 m/s: the balls roll through the load zone at half the
feed velocity, and the pitch and vertical motion show the ball-passage frequency
u / (2 pitch) = 31 Hz while the carriage cruises, on top of the static tilt the moment gives.
Built in code and written by the package's one scenario writer (``cosim.system.dump``).

    python orchestration/make_wu2012_scenarios.py   # then: guideway-fmu run wu2012_ball_carriage_moment
"""
from pathlib import Path

from guideway_fmu.cosim.system import Builder, dump
from guideway_fmu.scenarios import FOLDER

HEADER = "Written by orchestration/make_wu2012_scenarios.py; edit that script, not this file."
GRAVITY = 9.80665  # m/s^2
MASS = 0.313  # kg, Table 1


def scenarios() -> dict:
    """Every shipped scenario of this paper by name."""
    return {"wu2012_ball_carriage_moment": scenario()}


def scenario():
    b = Builder("wu2012_ball_carriage_moment",
                "Wu et al. (2012): the 5-DOF ball carriage under M_y = 2.90 N m, M_z = 0.3 N m and its weight, "
                "moved 30 mm at 0.3 m/s; swap BallCarriage5DOF for VerticalDynamics plus a "
                "contact FMU to run a roller guide instead.")
    b.experiment(start=0.0, stop=0.14, step=1e-5, algorithm="gauss-seidel")
    b.component("Feed", Path("FeedKinematics.fmu"), profile="trapezoid", distance=0.03,
                v_max=0.3, a_max=6.0, t_start=0.01)
    b.component("Carriage", Path("BallCarriage5DOF.fmu"), static_M_y=2.90, static_M_z=0.3,
                static_F_z=-MASS * GRAVITY)
    b.connect("Feed.u", "Carriage.u_feed")
    b.record(["Feed.u", "Carriage.v", "Carriage.theta", "Carriage.psi", "Carriage.u",
              "Carriage.phi", "Carriage.row_load_1", "Carriage.row_load_2"])
    b.plots(time=["Carriage.v", "Carriage.theta", "Carriage.row_load_1"],
            spectrum=["Carriage.theta"])
    return b.system(check_fmus=False)


if __name__ == "__main__":
    for name, system in scenarios().items():
        print(dump(system, FOLDER / f"{name}.toml", HEADER))
