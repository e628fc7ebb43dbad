"""Soleimanian, Mohammadpour and Ahmadian (2020), Coupled tribo-dynamic modelling of linear
guideways for high precision machining application, Proc IMechE Part J: the values of its
Tables 1-4 and of its rig, SI units, and the project's readings of what it leaves open.

Table 4 repeats Table 3's surface and lubricant (n, beta, sigma, tau_l0, mu0) and adds two
ratios that follow from them: sigma / beta (3e-3) and n beta sigma (printed 0.0367; the Table 3
values give 0.03645).
"""
import math

# Table 2: guideway and roller specifications (INA RUE45-E)
ROLLER_RADIUS = 2.5e-3  # m
ROLLER_LENGTH = 8e-3  # m
PRELOAD = 9200.0  # N, class V3 (high preload); the table does not say over what it is shared
GROOVES = 4
ROLLERS_PER_GROOVE = 20

# Table 3: lubricant, material and surface properties
ASPERITY_DENSITY = 0.54e9  # n [1/m^2]
ASPERITY_RADIUS = 1.5e-4  # beta [m]
ROUGHNESS = 0.45e-6  # sigma [m], composite RMS
E_REDUCED = 2e11  # E' [Pa]
VISCOSITY = 0.195  # mu0 [Pa s], at ambient pressure
PRESSURE_VISCOSITY = 2.2e-8  # alpha [1/Pa]
LIMITING_SHEAR_SLOPE = 0.047  # beta_m [-]
LIMITING_SHEAR_STRESS = 2e6  # tau_l0 [Pa]
FEED_FREQUENCY = 5.0  # f_v [Hz], the horizontal velocity's frequency in every case

# Table 1: the friction model beside Hess and Soom's measurement (Fig. 11, eq. 33). Its sigma,
# E', alpha, beta_m and f_v are Table 3's; the table's extracted layout is garbled, read as:
HESS_SOOM_ASPERITY_DENSITY = 7e9  # n [1/m^2]
HESS_SOOM_ASPERITY_RADIUS = 10e-6  # beta [m]
HESS_SOOM_LIMITING_SHEAR_STRESS = 3.5e6  # tau_l0 [Pa]
HESS_SOOM_MEAN_SPEED = 0.2375  # u_bar [m/s] of eq. 33
HESS_SOOM_SPEED_AMPLITUDE = 0.25  # a_u [m/s] of eq. 33
HESS_SOOM_LOAD = 250.0  # N, w of Fig. 11

# The rig (section "Experimental rig"): the bi-harmonic fit of the measured rail velocity used
# in eq. 1a, u = A1 sin(2 pi f_v t + phi1) + A2 sin(2 pi 3 f_v t + phi2)
RIG_AMPLITUDE_1 = 0.2919  # A1 [m/s]
RIG_AMPLITUDE_2 = 0.0178  # A2 [m/s]
RIG_PHASE_1 = 2.0588  # phi1 [rad]
RIG_PHASE_2 = 1.2679  # phi2 [rad]
NATURAL_FREQUENCY = 6590.0  # Hz, f_n of the unloaded rig (section "Unloaded case")

# The project's readings (not printed in the tables)
#: rad, 45 deg: the INA RUE45-E's, and the one angle at which the published eq. 3 is consistent
#: (physics/roller_guide/four_rows.py)
CONTACT_ANGLE = math.pi / 4
#: N, F0 shared by all 4 N rollers: Table 2's 9200 N read per groove (Q0 = 460 N), the reading
#: that reproduces the most of the paper's statements (analysis/soleimanian2020.py)
GUIDEWAY_PRELOAD = GROOVES * PRELOAD
#: kg, the moving rail: the paper gives none; about 0.3 m of a 45 mm x 38 mm steel rail
#: (about 11 kg/m), the mass that puts the unloaded natural frequency of the default guideway
#: at NATURAL_FREQUENCY (to the gram; analysis/soleimanian2020.py)
RAIL_MASS = 3.302
#: m/s, the rig's feed speed: A1 to two digits, the amplitude of the bi-harmonic feed
RIG_SPEED = 0.29
