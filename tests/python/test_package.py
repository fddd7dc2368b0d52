"""The packaged FMU: archive layout, model description (validated by fmpy and by
fmu-manipulation-toolbox), the contract's names, capabilities and units, and agreement with
the variable table modelDescription/variables.json (the single source of truth)."""

import json
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
from fmpy.validation import validate_fmu

from conftest import DEFAULT_PRESET, FMUCHECK, MODEL_IDENTIFIER, PRESETS, REPO, fmu_check_passes

# The contract (shared spec INTERFACE.md): names that must exist, with their causality.
CONTRACT_PARAMETERS = [
    "fidelity", "lubrication", "preload", "slices", "tolerance", "mu", "cage.pocketClearance",
    "oil.eta0", "oil.alpha", "roughness", "skewModel", "clearance", "outer.lobes",
    "outer.waveform", "cageSlipRate",
]
CONTRACT_PER_ROLLER_PARAMETERS = ["dD"]
CONTRACT_INPUTS = ["speed", "xi", "zeta", "Fx", "Fy", "Fz", "axialDisplacement", "cupSpeed"]
CONTRACT_OUTPUTS = [
    "frictionTorque", "frictionTorque.raceway", "frictionTorque.flange", "frictionTorque.cage",
    "powerLoss", "cone.x", "cone.y", "cone.z", "reaction.Fx", "reaction.My", "reaction.Mz",
    "tilt.max", "tilt.mean", "skew.max", "skew.mean", "Qi.max", "Qo.max", "Qf.max",
    "loadedRollers", "cage.speed",
]
CONTRACT_PER_ROLLER_OUTPUTS = ["tilt", "skew", "Qi", "Qo", "Qf", "Qc", "azimuth", "Nit", "Not", "Nft", "Nis", "Nos", "Nfs"]
ROLLERS = {"TRB130x230": 17, "32018X": 26, "32008": 23, "CRB-TRILOBE": 24}


def fmutool_check(path: Path) -> subprocess.CompletedProcess:
    exe = Path(sys.executable).with_name("fmutool")
    cmd = [str(exe)] if exe.exists() else [sys.executable, "-m", "fmu_manipulation_toolbox.cli.fmutool"]
    return subprocess.run([*cmd, "-input", str(path), "-check"], capture_output=True, text=True, timeout=300)


@pytest.mark.skipif(not FMUCHECK.is_file(), reason=f"no FMU Compliance Checker at {FMUCHECK}")
@pytest.mark.parametrize("preset", PRESETS)
def test_fmu_compliance_checker_reports_no_warning_or_error(package_preset, preset, tmp_path):
    """fmuCheck -k cs: the XML checks and a 0.1 s co-simulation at log level 3 (warnings);
    the FMU and the checker must both report zero warnings and errors."""
    fmu_check_passes(package_preset(preset), tmp_path, stop_time=0.1)


def test_archive_layout(fmu_path):
    with zipfile.ZipFile(fmu_path) as z:
        names = set(z.namelist())
        assert z.testzip() is None
    for required in [
        "modelDescription.xml",
        f"binaries/linux64/{MODEL_IDENTIFIER}.so",
        "resources/bearing.json",
        "documentation/index.html",
        "documentation/LICENSE.txt",
        "model.png",
    ]:
        assert required in names, f"{required} missing from {fmu_path}: {sorted(names)}"
    with zipfile.ZipFile(fmu_path) as z:
        icon = z.read("model.png")
        assert "MIT License" in z.read("documentation/LICENSE.txt").decode()
    # a PNG (signature, IHDR first) of 256 x 256 pixels
    assert icon[:8] == b"\x89PNG\r\n\x1a\n" and icon[12:16] == b"IHDR"
    assert int.from_bytes(icon[16:20], "big") == 256 and int.from_bytes(icon[20:24], "big") == 256
    assert not any("\\" in n for n in names)


@pytest.mark.parametrize("preset", PRESETS)
def test_fmpy_validate_fmu_reports_no_problems(package_preset, preset):
    path = package_preset(preset)
    problems = validate_fmu(str(path))
    assert problems == [], f"{preset}: fmpy.validation.validate_fmu found:\n" + "\n".join(problems)


@pytest.mark.parametrize("preset", PRESETS)
def test_fmutool_check_finds_no_error(package_preset, preset):
    """fmutool -check: XSD validation ("compliant with FMI-2.0") and the semantic checks;
    errors are logged at ERROR level and make the exit code non-zero (7)."""
    path = package_preset(preset)
    proc = fmutool_check(path)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, f"fmutool -check exited with {proc.returncode}:\n{out}"
    bad = [line for line in out.splitlines() if re.match(r"\s*(\x1b\[[0-9;]*m)*\s*(ERROR|CRITICAL|FATAL)\b", line)]
    assert not bad, "fmutool -check reported:\n" + "\n".join(bad)
    assert "compliant with FMI-2.0" in out, out
    assert "No semantic error" in out, out


@pytest.mark.parametrize("preset", PRESETS)
def test_bearing_resource_is_the_preset_text(package_preset, preset):
    with zipfile.ZipFile(package_preset(preset)) as z:
        packaged = z.read("resources/bearing.json").decode()
    assert packaged == (REPO / "presets" / f"{preset}.json").read_text()
    assert json.loads(packaged)["name"] == preset


def test_guids_differ_between_presets(models):
    guids = {p: models(p).md.guid for p in PRESETS}
    assert len(set(guids.values())) == len(PRESETS), guids


def test_capabilities(model):
    cs = model.md.coSimulation
    assert model.md.fmiVersion == "2.0"
    assert model.md.modelExchange is None
    assert cs.modelIdentifier == MODEL_IDENTIFIER
    assert cs.canHandleVariableCommunicationStepSize is True
    assert cs.canGetAndSetFMUstate is True
    assert cs.canSerializeFMUstate is True
    assert cs.canNotUseMemoryManagementFunctions is True
    assert cs.canBeInstantiatedOnlyOncePerProcess is False


def test_units_and_display_units(model):
    units = {u.name: [d.name for d in u.displayUnits] for u in model.md.unitDefinitions}
    assert "rpm" in units["rad/s"]
    assert "deg" in units["rad"]
    for v in model.md.modelVariables:
        if v.type != "Real":
            continue
        assert v.unit in units, f"{v.name}: unit {v.unit!r} not in <UnitDefinitions>"
        if v.unit == "rad/s":
            assert v.displayUnit == "rpm", v.name
        if v.unit == "rad":
            assert v.displayUnit == "deg", v.name
    assert model.vars["speed"].unit == "rad/s"
    assert model.vars["Fx"].unit == "N"
    assert model.vars["frictionTorque"].unit == "N.m"


@pytest.mark.parametrize("preset", PRESETS)
def test_contract_names_exist_with_their_causality(models, preset):
    m = models(preset)
    z = ROLLERS[preset]
    assert m.z == z
    want = {n: "parameter" for n in CONTRACT_PARAMETERS}
    want.update({n: "input" for n in CONTRACT_INPUTS})
    want.update({n: "output" for n in CONTRACT_OUTPUTS})
    for j in range(1, z + 1):
        want.update({f"roller[{j}].{s}": "parameter" for s in CONTRACT_PER_ROLLER_PARAMETERS})
        want.update({f"roller[{j}].{s}": "output" for s in CONTRACT_PER_ROLLER_OUTPUTS})
    assert f"roller[{z + 1}].tilt" not in m.vars
    for name, causality in want.items():
        assert name in m.vars, f"{preset}: contract variable {name} missing"
        assert m.vars[name].causality == causality, f"{preset}: {name} is {m.vars[name].causality}"
    for name in CONTRACT_INPUTS:
        assert m.vars[name].variability == "continuous" and m.vars[name].type == "Real"
    # The modes are Enumerations (a drop-down in importers), accessed as Integers.
    for name, n_items in [("fidelity", 3), ("lubrication", 2), ("preload", 2), ("traction", 2), ("oil.piezoviscosity", 2), ("integrator", 4)]:
        v = m.vars[name]
        assert v.type == "Enumeration", f"{name} is {v.type}"
        assert v.declaredType in m.md.typeDefinitions, name
        items = v.declaredType.items
        assert [int(i.value) for i in items] == list(range(n_items)), name
        assert int(v.min) == 0 and int(v.max) == n_items - 1 and int(v.start) in range(n_items)


@pytest.mark.parametrize("preset", ["TRB130x230", "32008"])
def test_model_description_matches_the_variable_table(models, preset):
    """Every row of modelDescription/variables.json (per-roller rows expanded to Z) is in the
    XML with the same value reference, type, causality, variability and unit, and nothing
    else is."""
    m = models(preset)
    table = json.loads((REPO / "modelDescription" / "variables.json").read_text())["variables"]
    expected = {}
    for row in table:
        rows = [(row["name"].replace("{j}", str(j)), row["vr"] + j - 1) for j in range(1, m.z + 1)] if row.get("per_roller") else [(row["name"], row["vr"])]
        for name, vr in rows:
            expected[name] = (vr, row)
    assert set(m.vars) == set(expected), (
        f"only in XML: {sorted(set(m.vars) - set(expected))}; only in the table: {sorted(set(expected) - set(m.vars))}"
    )
    vrs_by_type = {}
    for name, (vr, row) in expected.items():
        v = m.vars[name]
        assert v.valueReference == vr, name
        assert v.type == ("Enumeration" if "enumeration" in row else row["type"]), name
        assert v.causality == row["causality"], name
        assert v.variability == row["variability"], name
        if "unit" in row:
            assert v.unit == row["unit"], name
        if "displayUnit" in row:
            assert v.displayUnit == row["displayUnit"], name
        key = (v.type, v.valueReference)
        assert key not in vrs_by_type, f"{name} and {vrs_by_type.get(key)} share a value reference"
        vrs_by_type[key] = name
    # Outputs are listed in <ModelStructure><Outputs> exactly.
    outputs = {u.variable.name for u in m.md.outputs}
    assert outputs == {n for n, v in m.vars.items() if v.causality == "output"}


def test_default_experiment_and_start_values(models):
    """Start values of the inputs are the preset's operating point (in SI)."""
    import math

    for preset in PRESETS:
        m = models(preset)
        op = json.loads((REPO / "presets" / f"{preset}.json").read_text())["operating_point"]
        assert math.isclose(m.start("speed"), op["speed_rpm"] * math.pi / 30, rel_tol=1e-15), preset
        assert m.start("Fx") == op["Fx_N"], preset
        assert m.start("Fy") == op["Fy_N"], preset
        assert math.isclose(m.start("axialDisplacement"), op["axial_displacement_um"] * 1e-6, rel_tol=1e-15), preset
        assert m.start("slices") == json.loads((REPO / "presets" / f"{preset}.json").read_text())["solver"]["slices"]


def test_metadata_and_model_structure_a_strict_importer_reads(models):
    """Generation date, copyright, license, a default tolerance; every output with explicit
    dependencies: the integrator counters and roller azimuths on no input (a master may cut
    an algebraic loop there), the physical outputs on the inputs (the quasi-static model is
    algebraic in them); azimuths are discrete (they wrap at 2 pi)."""
    import datetime

    m = models(DEFAULT_PRESET)
    md = m.md
    datetime.datetime.strptime(md.generationDateAndTime, "%Y-%m-%dT%H:%M:%SZ")
    assert "contributors" in md.copyright and "MIT" in md.license
    assert md.defaultExperiment.tolerance is not None and float(md.defaultExperiment.tolerance) > 0
    inputs = {n for n, v in m.vars.items() if v.causality == "input"}
    parameters = {n for n, v in m.vars.items() if v.causality == "parameter"}
    deps = {u.variable.name: {d.name for d in u.dependencies} for u in md.outputs}
    init = {u.variable.name: {d.name for d in u.dependencies} for u in md.initialUnknowns}
    assert set(deps) == set(init) == {n for n, v in m.vars.items() if v.causality == "output"}
    for name in ["integrator.steps", "integrator.rhs", "integrator.rejected"]:
        assert deps[name] == set() and init[name] == set(), name
    for j in range(1, m.z + 1):
        assert deps[f"roller[{j}].azimuth"] == set()
        # at initialization roller 1 is at cage.angle0; at fidelity 1 the run-in puts the
        # rollers where running does within their pockets, which depends on every known
        assert init[f"roller[{j}].azimuth"] == inputs | parameters
        assert m.vars[f"roller[{j}].azimuth"].variability == "discrete"
    assert deps["cage.speed"] == {"speed", "cupSpeed"}
    for name in ["frictionTorque", "cone.x", "reaction.Fx", "roller[1].tilt", "roller[1].skew", "solver.iterations"]:
        assert deps[name] == inputs, name
        assert init[name] == inputs | parameters, name


@pytest.mark.parametrize("preset", PRESETS)
def test_start_values_in_the_xml_are_the_instance_values(models, slaves, preset):
    """In initialization mode, every parameter and input reads back as its XML start value
    (the XML is generated from a freshly instantiated model, so they cannot disagree)."""
    m = models(preset)
    fmu = slaves.new(m, name=f"start-{preset}")
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    getters = {"Real": fmu.getReal, "Integer": fmu.getInteger, "Enumeration": fmu.getInteger, "Boolean": fmu.getBoolean}
    mismatches = []
    for v in m.md.modelVariables:
        if v.causality not in ("parameter", "input"):
            continue
        assert v.start is not None, f"{v.name} has no start value"
        got = getters[v.type]([v.valueReference])[0]
        want = m.start(v.name)
        if v.type == "Boolean":
            got = bool(got)
        if got != want:
            mismatches.append(f"{v.name}: XML {v.start!r}, instance {got!r}")
    assert not mismatches, "\n".join(mismatches)
