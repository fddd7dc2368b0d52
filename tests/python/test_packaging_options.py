"""FMUs packaged with options of `trb fmu`: `--enumerations-as-integers` (for importers
that cannot set Enumerations, such as Ecos) and `--set NAME=VALUE` (start values), checked in
fmpy against the plain FMU; FMUs of different bearings, each with its own model identifier,
side by side in one process."""

from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from conftest import FMUCHECK, fmu_check_passes, run_cli

OUTPUTS = ["frictionTorque", "powerLoss", "cage.speed", "skew.max", "Qi.max", "loadedRollers"]


def package(tmp_path: Path, name: str, *options) -> Path:
    out = tmp_path / name
    run_cli("fmu", *options, "--out", out)
    return out


def simulate(path: Path, start_values: dict, stop: float = 0.004) -> np.ndarray:
    return simulate_fmu(str(path), start_values=start_values, stop_time=stop, output_interval=1e-3, output=OUTPUTS)


def assert_identical(a: np.ndarray, b: np.ndarray):
    for name in ["time", *OUTPUTS]:
        assert np.array_equal(a[name], b[name]), f"{name}: {a[name]} != {b[name]}"


def test_enumerations_as_integers_validates_and_simulates_like_the_enumerations(fmu_path, tmp_path):
    ints = package(tmp_path, "ints.fmu", "--enumerations-as-integers")
    assert validate_fmu(str(ints)) == []
    md = read_model_description(str(ints))
    plain = {v.name: v for v in read_model_description(str(fmu_path)).modelVariables}
    enumerations = [n for n, v in plain.items() if v.type == "Enumeration"]
    assert {"fidelity", "supply", "causality", "lubrication", "defect.ring"} <= set(enumerations)
    for v in md.modelVariables:
        p = plain[v.name]
        assert v.valueReference == p.valueReference and v.start == p.start, v.name
        if v.name in enumerations:
            assert v.type == "Integer" and v.declaredType is None, v.name
            assert (v.min, v.max) == (p.min, p.max), v.name
            assert "(values: 0 " in v.description, v.description
        else:
            assert v.type == p.type, v.name
    # fidelity and supply set as Integers give the plain FMU's numbers bit for bit
    starts = {"fidelity": 2, "supply": 2, "Fy": 5e3}
    assert_identical(simulate(ints, starts), simulate(fmu_path, starts))


@pytest.mark.skipif(not FMUCHECK.is_file(), reason=f"no FMU Compliance Checker at {FMUCHECK}")
def test_enumerations_as_integers_passes_the_compliance_checker(tmp_path):
    ints = package(tmp_path, "ints.fmu", "--enumerations-as-integers", "--set", "supply=grease")
    fmu_check_passes(ints, tmp_path, stop_time=0.01)


def test_set_start_values_are_declared_and_simulated_without_setting_them(fmu_path, tmp_path):
    """An FMU packaged with --set fidelity=2 --set supply=grease runs, with no start value
    given, exactly what the plain FMU runs with fidelity 2 and supply 2 set."""
    fmu = package(tmp_path, "set.fmu", "--set", "fidelity=2", "--set", "supply=grease", "--set", "cageSlipRate=0.002")
    assert validate_fmu(str(fmu)) == []
    starts = {v.name: v.start for v in read_model_description(str(fmu)).modelVariables}
    assert (starts["fidelity"], starts["supply"], starts["cageSlipRate"]) == ("2", "2", "0.002")
    packaged = simulate(fmu, {})
    explicit = simulate(fmu_path, {"fidelity": 2, "supply": 2, "cageSlipRate": 0.002})
    assert_identical(packaged, explicit)
    assert not np.array_equal(packaged["frictionTorque"], simulate(fmu_path, {})["frictionTorque"])
    # the importer may still set another value
    assert_identical(simulate(fmu, {"fidelity": 0, "supply": 0, "cageSlipRate": 0.0}), simulate(fmu_path, {"cageSlipRate": 0.0}))


def test_bad_set_is_refused_naming_the_variable(tmp_path):
    proc = run_cli("fmu", "--set", "supply=honey", "--out", tmp_path / "x.fmu", check=False)
    assert proc.returncode == 2, proc.stderr
    assert "`supply`: expected an item of Supply: 0 flooded, 1 oilBath, 2 grease, 3 oilAir" in proc.stderr
    assert not (tmp_path / "x.fmu").exists()


def test_two_bearings_load_side_by_side_in_one_process(models, slaves):
    """The default bearing's FMU and 32008's (modelIdentifier TRB_32008) instantiated in one
    process step together, each as it does alone."""
    pair = [models("TRB130x230"), models("32008")]
    assert [m.md.coSimulation.modelIdentifier for m in pair] == ["TaperedRollerBearing", "TRB_32008"]
    alone = [simulate(m.path, {}) for m in pair]
    fmus = [slaves.new(m) for m in pair]
    for fmu in fmus:
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
    for k in range(4):
        for fmu in fmus:
            fmu.doStep(currentCommunicationPoint=k * 1e-3, communicationStepSize=1e-3)
    torques = [fmu.getReal([m.vr("frictionTorque")])[0] for fmu, m in zip(fmus, pair)]
    assert torques == [a["frictionTorque"][-1] for a in alone]
    assert torques[0] != torques[1]
