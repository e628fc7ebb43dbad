import math

import numpy as np

from guideway_fmu.physics.roller_guide import hertz_line


def test_half_width_hand_calculation():
    # 115 N over 8 mm: w' = 14375 N/m; b = sqrt(8 * 14375 * 2.5e-3 / (pi * 2e11)) = 2.1393e-5 m
    b = hertz_line.half_width(115.0, 8e-3, 2.5e-3, 2e11)
    assert math.isclose(b, math.sqrt(8 * 14375 * 2.5e-3 / (math.pi * 2e11)), rel_tol=1e-12)
    assert math.isclose(b, 2.1393e-5, rel_tol=1e-4)


def test_contact_area_is_two_b_l_and_zero_without_load():
    loads = np.array([-5.0, 0.0, 115.0])
    area = hertz_line.contact_area(loads, 8e-3, 2.5e-3, 2e11)
    assert area[0] == 0.0 and area[1] == 0.0
    assert math.isclose(area[2], 2 * hertz_line.half_width(115.0, 8e-3, 2.5e-3, 2e11) * 8e-3)


def test_half_width_scales_with_square_root_of_load_limiting_law():
    b1, b4 = hertz_line.half_width(np.array([100.0, 400.0]), 8e-3, 2.5e-3, 2e11)
    assert math.isclose(b4 / b1, 2.0, rel_tol=1e-12)
