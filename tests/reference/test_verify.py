"""verify: its choice of criterion on a chaotic scenario and the load cycle its statistics use (guideway_fmu.reference.verify)."""
from types import SimpleNamespace

import numpy as np
import pytest

from guideway_fmu import scenarios
from guideway_fmu.analysis import soleimanian2020 as paper
from guideway_fmu.cosim import system
from guideway_fmu.reference.verify import excitation_period, format_table, verify


@pytest.mark.slow
def test_dry_9000N_2500Hz_under_the_light_preload_is_judged_by_statistics(fmu_dir):
    # under the light reading (9200 N over 80 rollers) the dry rig's rows lift off every cycle
    # and the response is chaotic (as shipped it is not: its reference moves by 1e-6 of the
    # range at most). Measured over its 0.2 s: the reference moves by 16 % of the range with its
    # start disturbed by 1e-9 and by 17 % at rtol 1e-9, the co-simulation (2 us) differs by 17 %; its
    # statistics stay within 3 spreads of the reference's (peak 2's amplitude the nearest, 8.9
    # of 10.8 N allowed). Over 0.1 s the disturbed references have not yet parted for most of
    # the run, their spread is too narrow a yardstick and the co-simulation fails on peaks 2-3
    light = {r.name: r for r in paper.readings()}["carriage"]
    rig = system.load(scenarios.find("soleimanian2020_9000N_2500Hz_dry"), fmu_dir).with_changes(
        step=2e-6, parameters=light.parameters())
    report = verify(rig)
    assert report["criterion"] == "statistics", report["predictability"]
    assert min(report["predictability"]["spread"].values()) > 0.1
    judged = report["statistics"]["signals"]["Contact.F_upper"]
    assert report["rms_error"]["Contact.F_upper"] > 0.01  # pointwise, it would fail
    assert report["passed"] is True, judged
    assert "criterion: statistics" in format_table(report)


def test_a_load_cycle_without_frequency_or_spectral_peak_is_a_named_error():
    rig = SimpleNamespace(name="still_rig", components={"Body": SimpleNamespace(parameters={})})
    t = np.linspace(0.0, 0.01, 101)
    with pytest.raises(ValueError, match="still_rig: no load_frequency parameter and no spectral peak"):
        excitation_period(rig, t, np.full_like(t, 3.0))
    # the hand value where a sine gives its own: 1 / 500 Hz
    assert excitation_period(rig, t, np.sin(2 * np.pi * 500.0 * t)) == pytest.approx(2e-3, rel=0.02)
