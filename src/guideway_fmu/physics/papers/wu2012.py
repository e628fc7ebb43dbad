"""Wu et al. (2012), The effect of bending loads on the dynamic behaviors of a rolling guide,
J Mech Sci Tech: the values of its Tables 1 and 2 and of its steel, SI units (angles in
degrees, as printed), and the project's readings of what it leaves open.

Table 3 (the natural frequencies) is a result, not a parameter: the tests compare with it.
"""

# Table 1: specifications of the linear guide system
CARRIAGE_LENGTH = 65.9e-3  # m
CARRIAGE_WIDTH = 59e-3  # m
CARRIAGE_HEIGHT = 22e-3  # m
RAIL_LENGTH = 0.5  # m
RAIL_WIDTH = 20e-3  # m
RAIL_HEIGHT = 15.5e-3  # m
BALL_DIAMETER = 4.763e-3  # m
BALLS = 50  # total number of balls
ROWS = 2
CONTACT_ANGLE_DEG = 45.0  # beta [deg]
LOAD_ZONE_LENGTH = 43e-3  # l_L [m]
MASS = 0.313  # M [kg], of the carriage
INERTIA = (9.938e-5, 6.136e-5, 1.394e-4)  # J_x, J_y, J_z [kg m^2]
OFFSET_D = 7.37e-3  # d [m], contact points from the x-y plane
OFFSET_E = 10.3e-3  # e [m], contact points from the x-z plane

# Section 4: the steel of ball, carriage and rail
YOUNGS_MODULUS = 206e9  # E [Pa]
POISSON_RATIO = 0.3  # nu

# Table 2: normal stiffness K_n1..K_n9 [N/m] of the balls of a row under the moment M_y [N m]
BALL_STIFFNESS = {
    0.0: (17.8e6,) * 9,
    1.45: (15.7e6, 16.3e6, 16.8e6, 17.3e6, 17.8e6, 18.2e6, 18.6e6, 19.0e6, 19.4e6),
    2.90: (12.9e6, 14.5e6, 15.7e6, 16.8e6, 17.8e6, 18.6e6, 19.4e6, 20.2e6, 20.8e6),
    4.35: (7.6e6, 12.0e6, 14.5e6, 16.3e6, 17.8e6, 19.0e6, 20.2e6, 21.2e6, 22.1e6),
}

# The project's readings (docs/ball-guides.md)
#: balls in the load zone of each row: Table 2 lists nine, and nine over LOAD_ZONE_LENGTH
#: reproduce Table 3's point-to-point frequencies within 0.4 %
BALLS_PER_ROW = 9
#: groove radius / ball diameter and the preload of each ball [N]: not stated; with the rest
#: stiffness of 17.8 MN/m only their combination counts, fitted to Table 2's row at 1.45 N m
#: (rest approach 3.93 um)
CONFORMITY = 0.534
PRELOAD = 46.6
