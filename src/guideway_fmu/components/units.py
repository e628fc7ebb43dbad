"""SI units the components declare, as FMI 2.0 base-unit exponents."""

BASE_UNITS = {  # unit name -> exponents of kg, m, s, rad
    "1": {},
    "kg": {"kg": 1},
    "m": {"m": 1},
    "s": {"s": 1},
    "rad": {"rad": 1},
    "m/s": {"m": 1, "s": -1},
    "m/s2": {"m": 1, "s": -2},
    "N": {"kg": 1, "m": 1, "s": -2},
    "N/m": {"kg": 1, "s": -2},
    "N.s/m": {"kg": 1, "s": -1},
    "Pa": {"kg": 1, "m": -1, "s": -2},
    "Pa.s": {"kg": 1, "m": -1, "s": -1},
    "1/Pa": {"kg": -1, "m": 1, "s": 2},
    "1/m2": {"m": -2},
    "Hz": {"s": -1},
    "N.m": {"kg": 1, "m": 2, "s": -2},
    "kg.m2": {"kg": 1, "m": 2},
    "rad/s": {"rad": 1, "s": -1},
    "W": {"kg": 1, "m": 2, "s": -3},
}
