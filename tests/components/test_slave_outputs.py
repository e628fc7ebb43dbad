"""The output guard of every component (components/base.py): outputs are given only when each is
finite, judged from their sum where that is finite and value by value where it is not; else the
getter raises (fmi2Error through the FMU), except after a discarded step."""
from __future__ import annotations

import pytest

from guideway_fmu.components.base import GuidewaySlave


class Doubling(GuidewaySlave):
    """Outputs a = b = 1e308 x: finite for x <= 1 although their sum overflows, infinite above
    x = 1.8 (the largest double is 1.8e308)."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.input("x", 1.0, "1", "scale")
        self.output("a", "1", "1e308 x", ("x",))
        self.output("b", "1", "1e308 x", ("x",))

    def build_model(self):
        return self  # no physics: evaluate below is the whole model

    def evaluate(self):
        return {"a": 1e308 * self.x, "b": 1e308 * self.x}


def _values(slave):
    refs = {v.name: vr for vr, v in slave.vars.items()}
    return slave.get_real([refs["a"], refs["b"]])


def test_limiting_case_finite_outputs_whose_sum_overflows_are_kept():
    slave = Doubling(instance_name="doubling", resources=None)
    assert _values(slave) == [1e308, 1e308]


def _set_x(slave, x):
    slave.set_real([next(vr for vr, v in slave.vars.items() if v.name == "x")], [x])


def test_limiting_case_an_infinite_output_is_an_error_naming_it():
    # before, the getter logged the error and returned the last valid values under fmi2OK
    slave = Doubling(instance_name="doubling", resources=None)
    _values(slave)
    _set_x(slave, 2.0)
    with pytest.raises(ValueError, match=r"outputs \{'a': inf, 'b': inf\} are not finite"):
        _values(slave)


def test_after_a_discarded_step_the_outputs_of_the_last_successful_time_are_read():
    slave = Doubling(instance_name="doubling", resources=None)
    _values(slave)
    _set_x(slave, 2.0)
    assert slave.do_step(0.0, -1.0) is False  # a bad step size: fmi2Discard
    assert _values(slave) == [1e308, 1e308]  # FMI lets the host read them after the discard
    _set_x(slave, 0.5)
    assert slave.do_step(0.0, 1e-3) is True
    assert _values(slave) == [5e307, 5e307]
    _set_x(slave, 2.0)
    with pytest.raises(ValueError, match="not finite"):  # a new error, met by the getter
        _values(slave)
