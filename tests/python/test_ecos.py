"""The FMU in Ecos (ecospy, a third-party co-simulation engine that cannot set Enumerations):
packaged with `trb fmu --enumerations-as-integers`, run at fidelities 0 and 2 from Ecos's
parameter set, and compared with the same steps through fmpy, bit for bit.

Ecos's library needs Debian's libtbb12; scripts/test.sh installs it where it can (as root
with apt-get). Where it is missing these tests are skipped, and the reason says so."""

import math
from pathlib import Path

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

from conftest import run_cli

try:
    from ecospy import EcosLib, EcosSimulation, EcosSimulationStructure

    ECOS = None
except (ImportError, OSError) as e:  # libtbb.so.12 missing: OSError from the library's loader
    ECOS = f"ecospy cannot load its library ({e}); install Debian's libtbb12 (apt-get install libtbb12)"

pytestmark = pytest.mark.skipif(ECOS is not None, reason=ECOS or "")

STEP = 1e-3
STEPS = 30
INPUTS = {"speed": 3000 * math.pi / 30, "Fx": 20e3, "Fy": 10e3}
OUTPUTS = ["frictionTorque", "skew.mean", "cage.speed", "Qi.max", "reaction.Fy"]


@pytest.fixture(scope="module")
def integers_fmu(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("ecos") / "TaperedRollerBearing.fmu"
    run_cli("fmu", "--enumerations-as-integers", "--out", out)
    return out


def in_ecos(fmu: Path, fidelity: int) -> dict:
    EcosLib.set_log_level("warn")
    structure = EcosSimulationStructure()
    structure.add_model("trb", str(fmu))
    structure.add_parameter_set("start", {**{f"trb::{k}": v for k, v in INPUTS.items()}, "trb::fidelity": fidelity})
    with EcosSimulation(structure=structure, step_size=STEP) as sim:
        sim.init(parameter_set="start")
        sim.step(STEPS)
        values = {name: sim.get_real(f"trb::{name}") for name in OUTPUTS}
        values["fidelity"] = sim.get_integer("trb::fidelity")
        values["time"] = sim.get_time()
        sim.terminate()
    return values


def in_fmpy(fmu: Path, fidelity: int) -> dict:
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    slave = FMU2Slave(
        guid=md.guid,
        unzipDirectory=extract(str(fmu)),
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="trb",
    )
    slave.instantiate()
    slave.setInteger([vr["fidelity"]], [fidelity])
    for name, value in INPUTS.items():
        slave.setReal([vr[name]], [value])
    slave.setupExperiment(startTime=0.0)
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    t = 0.0
    for _ in range(STEPS):
        slave.doStep(t, STEP)
        t += STEP
    values = dict(zip(OUTPUTS, slave.getReal([vr[n] for n in OUTPUTS])))
    slave.terminate()
    slave.freeInstance()
    return values


@pytest.mark.parametrize("fidelity", [0, 2])
def test_ecos_runs_the_fmu_at_the_fidelity_it_sets(integers_fmu, fidelity):
    ecos = in_ecos(integers_fmu, fidelity)
    assert ecos["fidelity"] == fidelity
    assert math.isclose(ecos["time"], STEPS * STEP, rel_tol=1e-12)
    reference = in_fmpy(integers_fmu, fidelity)
    for name in OUTPUTS:
        assert ecos[name] == reference[name], f"{name}: Ecos {ecos[name]!r}, fmpy {reference[name]!r}"
    # the quasi-dynamic model computes the lubricated skew; the quasi-static one reports none
    assert (ecos["skew.mean"] != 0.0) == (fidelity == 2)
