"""The output guard of every component (components/base.py): outputs are kept only when each is
finite, judged from their sum where that is finite and value by value where it is not."""
from __future__ import annotations

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


def test_limiting_case_an_infinite_output_keeps_the_last_valid_values():
    slave = Doubling(instance_name="doubling", resources=None)
    _values(slave)
    slave.set_real([next(vr for vr, v in slave.vars.items() if v.name == "x")], [2.0])
    assert _values(slave) == [1e308, 1e308]
