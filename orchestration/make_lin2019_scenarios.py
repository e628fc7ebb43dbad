"""Write the ball-to-ball friction scenario of Lin, Duan and Okwudire (2019) into the package
(src/guideway_fmu/scenarios/).

The 5-DOF ball carriage of Wu et al. (2012) under a yaw moment, moved 40 mm at 0.3 m/s, with
the ball-to-ball friction of one of its rows (BallToBallFriction, fed the row's normal load by
the carriage) driving a horizontal rig: the drive force shows the friction the balls' contacts
add as the rail groove's contact-angle wave (1 deg, 12 mm) makes them catch up and part.
Built in code and written by the package's one scenario writer (``cosim.system.dump``).

    python orchestration/make_lin2019_scenarios.py   # then: guideway-fmu run lin2019_ball_to_ball_friction
"""
import math
from pathlib import Path

from guideway_fmu.cosim.system import Builder, dump
from guideway_fmu.scenarios import FOLDER

HEADER = "Written by orchestration/make_lin2019_scenarios.py; edit that script, not this file."
GRAVITY = 9.80665  # m/s^2
MASS = 0.313  # kg, carriage of Wu et al. (2012) Table 1
YAW = 0.3  # N m


def scenarios() -> dict:
    """Every shipped scenario of this paper by name."""
    return {"lin2019_ball_to_ball_friction": scenario()}


def scenario():
    b = Builder("lin2019_ball_to_ball_friction",
                "Lin, Duan and Okwudire (2019): ball-to-ball contact friction of one ball row of "
                "the Wu et al. (2012) carriage under M_z = 0.3 N m, moved 40 mm at 0.3 m/s; the "
                "rig's drive force carries the friction the balls' contacts add.")
    b.experiment(start=0.0, stop=0.14, step=1e-5, algorithm="gauss-seidel")
    b.component("Feed", Path("FeedKinematics.fmu"), profile="trapezoid", distance=0.04,
                v_max=0.3, a_max=30.0, t_start=0.005)
    b.component("Carriage", Path("BallCarriage5DOF.fmu"), static_M_z=YAW,
                static_F_z=-MASS * GRAVITY)
    b.component("Row", Path("BallToBallFriction.fmu"), deviation_BL=math.radians(-1.0),
                deviation_BR=math.radians(1.0), wave_amplitude=math.radians(1.0),
                wavelength=12e-3, M_yaw=YAW / 2)
    b.component("Rig", Path("HorizontalRig.fmu"), mass=MASS)
    b.connect("Feed.u", "Carriage.u_feed")
    b.connect("Feed.u", "Row.u")
    b.connect("Feed.x", "Row.x")
    b.connect("Carriage.row_load_1", "Row.F_normal")
    b.connect("Feed.a", "Rig.a")
    b.connect("Row.F_friction", "Rig.F_friction")
    b.record(["Feed.u", "Carriage.row_load_1", "Row.F_friction", "Row.contact_force",
              "Row.groups", "Row.epsilon_mean", "Rig.drive_force"])
    b.plots(time=["Row.F_friction", "Row.groups", "Rig.drive_force"],
            spectrum=["Row.F_friction"])
    return b.system(check_fmus=False)


if __name__ == "__main__":
    for name, system in scenarios().items():
        print(dump(system, FOLDER / f"{name}.toml", HEADER))
