"""Sweep files over the shipped 9000 N / 4500 Hz lubricated scenario, on the session's FMUs."""
import pytest

SCENARIO = "soleimanian2020_9000N_4500Hz"


@pytest.fixture
def write_sweep(tmp_path):
    """write_sweep(design_toml, stop=2e-3, outputs=...) -> path of a sweep file in tmp_path."""
    def write(design: str, stop: float = 2e-3, name: str = "sweep.toml", outputs: str = OUTPUTS):
        path = tmp_path / name
        path.write_text(f'scenario = "{SCENARIO}"\n\n[experiment]\nstop = {stop}\n\n'
                        f"{design}\n{outputs}")
        return path
    return write


OUTPUTS = """
[[outputs]]
variable = "Contact.F_upper"
reduce = "envelope"
settle = 0.0005

[[outputs]]
variable = "Carriage.y"
reduce = "rms"

[[outputs]]
variable = "Carriage.y"
reduce = "dominant_frequency"
"""
