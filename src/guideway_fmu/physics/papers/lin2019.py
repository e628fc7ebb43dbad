"""Lin, Duan and Okwudire (2019), Analytical and low-order numerical modeling of ball-to-ball
contact friction in linear ball bearings and ball screws, J Tribol: the linear ball bearing of
its Tables 1 and 2, SI units (angles in degrees, as printed).

Tables 2 (velocity deviations) and 3 (contact forces) otherwise hold results, which the tests
compare with; Tables 4-5 are the ball screw, which the project does not model.
"""

# Table 1: parameters of the linear ball bearing case studies
BALL_RADIUS = 5e-3  # R_B [m]
CONFORMITY = 0.56  # groove radius / ball diameter
PSI = 5.307e-4  # Psi [(m^2/N)^(1/3)], constant of the semi-major axis length
NORMAL_LOAD = 100.0  # N_y [N], vertical force on each ball
VELOCITY = 10e-3  # v [m/s], of the top groove
FRICTION = 0.1  # mu, metal-to-metal
YOUNGS_MODULUS = 2.1e11  # Pa
POISSON_RATIO = 0.28

# Table 2 (and section 2.4.2): the contact-angle deviations of its cases,
# -Delta beta_BL = Delta beta_BR = theta; case (a) Delta beta_TR = Delta beta_TL = 0,
# case (b) Delta beta_TR = -theta, Delta beta_TL = theta; at the side force ratio rho
DEVIATION_DEG = 2.0  # theta [deg]
SIDE_FORCE_RATIO = -0.6  # rho
