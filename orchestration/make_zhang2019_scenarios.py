"""Write the feed-unit scenario of Zhang, Wang and Le (2019) into the package
(src/guideway_fmu/scenarios/).

A slot milled in aluminium on a four-slider ball-guide feed unit: a three-tooth end mill at
12000 rpm (200 rev/s) and 2 mm depth (MillingForce) presses on the workpiece at a tool point
150 mm above the ball rows while the table moves under the standing tool at 0.1 m/s
(FeedKinematics), so the load point travels 100 mm along the table, from 50 mm ahead of its
centre to 50 mm behind (FeedUnitErrors, the size-25 guide of
src/guideway_fmu/examples/ball_guides/zhang2019_vertical_10kN.toml). The errors pulse at the
tooth-passing frequency of 600 Hz, and the tool point's errors drift as the load point travels
(the paper's Figs. 15, 16). Built in code and written by the package's one scenario writer
(``cosim.system.dump``).

    python orchestration/make_zhang2019_scenarios.py   # then: guideway-fmu run zhang2019_feed_unit_milling
"""
from pathlib import Path

from guideway_fmu.cosim.system import Builder, dump
from guideway_fmu.scenarios import FOLDER

HEADER = "Written by orchestration/make_zhang2019_scenarios.py; edit that script, not this file."


def scenarios() -> dict:
    """Every shipped scenario of this paper by name."""
    return {"zhang2019_feed_unit_milling": scenario()}


def scenario():
    b = Builder("zhang2019_feed_unit_milling",
                "Zhang, Wang and Le (2019): the five errors of a four-slider ball-guide feed unit "
                "while an end mill slots at 600 teeth/s and the table carries the load point "
                "100 mm under the standing tool.")
    b.experiment(start=0.0, stop=1.0, step=1e-4, algorithm="gauss-seidel")
    b.component("Feed", Path("FeedKinematics.fmu"), profile="constant", velocity=0.1)
    # start_angle keeps the tooth entries (a step in the edge force) off the sampling grid
    b.component("Mill", Path("MillingForce.fmu"), spindle_speed=200.0, teeth=3,
                axial_depth=2e-3, start_angle=0.1)
    b.component("Unit", Path("FeedUnitErrors.fmu"), point_x=0.05, point_y=0.08, point_z=0.15)
    b.connect("Feed.u", "Mill.u_feed")
    b.connect("Feed.x", "Unit.x_feed")
    for axis in "xyz":
        b.connect(f"Mill.F_{axis}", f"Unit.F_{axis}")
    b.record(["Feed.x", "Mill.F_x", "Mill.F_y", "Mill.F_z", "Unit.delta_y", "Unit.delta_z",
              "Unit.epsilon_x", "Unit.epsilon_y", "Unit.epsilon_z", "Unit.tool_d_y",
              "Unit.tool_d_z", "Unit.max_ball_load"])
    b.plots(time=["Mill.F_y", "Unit.tool_d_y", "Unit.tool_d_z", "Unit.epsilon_y"],
            spectrum=["Unit.tool_d_y"])
    return b.system(check_fmus=False)


if __name__ == "__main__":
    for name, system in scenarios().items():
        print(dump(system, FOLDER / f"{name}.toml", HEADER))
