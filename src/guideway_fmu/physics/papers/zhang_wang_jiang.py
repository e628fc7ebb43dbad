"""Zhang, Wang and Jiang, Fractal-creep wear model and accuracy degradation simulation of linear
ball guide: the LG20 guide of its Table 1 and the material, surface and wear values of its
sections 3-4, SI units (angles in degrees, as printed), and the project's readings of what the
extracted text leaves open (docs/wear.md).
"""

# Table 1: the main parameters of the LG20-type guide
PRELOAD_DEFORMATION = 4e-6  # delta_0 [m], initial deformation (0.004 mm)
BALL_DIAMETER = 3.969e-3  # D_a [m]
CONFORMITY = 0.51  # f, curvature ratio
BALLS_PER_ROW = 12  # n_s, bearing balls
CONTACT_ANGLE_DEG = 45.0  # alpha [deg]

# Section 4.1: slider and balls of GCr15 bearing steel; the wear coefficient after Su et al.
E_STAR = 1.143e11  # E* [Pa] (1.143e5 MPa)
YIELD_STRENGTH = 518.4e6  # sigma_s [Pa]
WEAR_COEFFICIENT = 5e-4  # K_f

# Sections 3 and 4: the fractal surface, its wear and the creep
FRACTAL_SCALE = 2.38e-8  # G [m], measured over 675 um of raceway
FREQUENCY_RATIO = 1.5  # gamma of the W-M series
PATCH_AREA = 64e-12  # A_alpha [m^2], the 8 x 8 um differential surface
HARDNESS_PER_YIELD = 2.8  # H / sigma_s
HYSTERESIS = 0.9  # tau of eq. 37, 3 x 0.3 for a slender contact ellipse

# The project's readings
#: E [Pa] and nu of balls and raceways: steel's nu with the E that gives the printed E*
#: (1/E* = 2 (1 - nu^2) / E)
YOUNGS_MODULUS = 2.08e11
POISSON_RATIO = 0.3
#: D of the raceway surface, lost from the extracted text: 2.8 makes the measured G describe a
#: profile of 0.29 um RMS over the 675 um, a ground raceway, where 2.4 would mean 9 um
FRACTAL_DIMENSION = 2.8
