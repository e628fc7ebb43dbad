"""An FMU keeps its own code and pythonfmu runtime in a process shared with other pythonfmu FMUs,
instantiates without limit and without megabytes per kind, and the process exits cleanly.
Each case runs in a child process (a crash at exit is the failure)."""
from __future__ import annotations

import subprocess
import sys
import textwrap
import zipfile

import pytest
from pythonfmu.builder import FmuBuilder

from guideway_fmu.fmu_build import exit_patch

PROBE = '''
from pythonfmu import Fmi2Causality, Fmi2Slave, Real


class MarkedProbe(Fmi2Slave):
    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.y = 1.0
        self.register_variable(Real("y", causality=Fmi2Causality.output))

    def do_step(self, current_time, step_size):
        return True
'''
#: appended to the probe's bundled pythonfmu: another version, whose getters answer 42
MARK = '''
__version__ = "0.0-marked"
Fmi2Slave.get_real = lambda self, vrs: [42.0] * len(vrs)
'''

FEED = '''
import fmpy
r = fmpy.simulate_fmu({feed!r}, step_size=1e-4, stop_time=1e-3, output=["x", "u"])
print("FEED", repr(float(r["x"][-1])), repr(float(r["u"][-1])))
'''


@pytest.fixture(scope="module")
def marked_probe(tmp_path_factory):
    folder = tmp_path_factory.mktemp("marked")
    # a plain pythonfmu FMU's slave module is process-wide by its file name: not "probe", which
    # test_master_refuses.py's probe uses in the same test process
    (folder / "marked_probe.py").write_text(PROBE)
    built = FmuBuilder.build_FMU(folder / "marked_probe.py", dest=folder / "Built.fmu")
    marked = folder / "MarkedProbe.fmu"
    with zipfile.ZipFile(built) as source, zipfile.ZipFile(marked, "w") as target:
        for entry in source.infolist():
            data = source.read(entry)
            if entry.filename == "resources/pythonfmu/fmi2slave.py":
                data += MARK.encode()
            target.writestr(entry, data)
    return exit_patch.patch_fmu(marked)  # its own exit defect would make the child flaky


def child(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], capture_output=True,
                          text=True, timeout=300)


@pytest.mark.slow
def test_fmu_keeps_its_runtime_when_a_marked_pythonfmu_was_loaded_first(fmu_dir, marked_probe):
    feed = str(fmu_dir / "FeedKinematics.fmu")
    alone = child(FEED.format(feed=feed))
    first = child(textwrap.dedent(f'''
        import sys
        import fmpy
        from fmpy.fmi2 import FMU2Slave
        md = fmpy.read_model_description({str(marked_probe)!r})
        probe = FMU2Slave(guid=md.guid, unzipDirectory=fmpy.extract({str(marked_probe)!r}),
                          modelIdentifier=md.coSimulation.modelIdentifier, instanceName="probe")
        probe.instantiate()
        print("MARKED", sys.modules["pythonfmu.fmi2slave"].__version__, probe.getReal([0]))
        ''') + FEED.format(feed=feed))
    assert alone.returncode == 0 and first.returncode == 0, alone.stderr + first.stderr
    assert "MARKED 0.0-marked [42.0]" in first.stdout  # the shared name holds the marked runtime
    feed_line = [line for line in alone.stdout.splitlines() if line.startswith("FEED")]
    assert feed_line and feed_line[0] in first.stdout.splitlines()


@pytest.mark.slow
def test_many_instantiations_cost_no_megabytes_and_the_process_exits_cleanly(fmu_dir):
    done = child(textwrap.dedent(f'''
        import fmpy, numpy, scipy.integrate, scipy.optimize
        from fmpy.fmi2 import FMU2Slave

        def rss():
            return int(open("/proc/self/statm").read().split()[1]) * 4096

        for name in ("FeedKinematics", "ContactEHL", "VerticalDynamics", "FrictionCoulomb"):
            path = "{fmu_dir}/" + name + ".fmu"
            md, unzipped = fmpy.read_model_description(path), fmpy.extract(path)
            before = rss()
            for i in range(100):
                fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, instanceName=f"i{{i}}",
                                modelIdentifier=md.coSimulation.modelIdentifier)
                fmu.instantiate()
                fmu.setupExperiment(startTime=0.0)
                fmu.enterInitializationMode()
                fmu.exitInitializationMode()
                fmu.doStep(0.0, 1e-5)
                fmu.terminate()
                fmu.freeInstance()
            print("GROWTH", name, rss() - before)
        '''))
    assert done.returncode == 0, done.stderr  # the interpreter was finalised: no corruption
    growth = {line.split()[1]: int(line.split()[2]) for line in done.stdout.splitlines()
              if line.startswith("GROWTH")}
    assert len(growth) == 4
    # before: 8.4 MB per kind (a list of a million references to the slave's namespace); the
    # first kind also loads the code all of them share (fmpy's and pythonfmu's parts)
    later = {k: g for k, g in growth.items() if k != "FeedKinematics"}
    assert all(g < 3e6 for g in later.values()), growth
