"""Bad input never yields NaN outputs or a crash:
- a NaN or infinite input makes the next doStep fail (fmi2Error or fmi2Discard), with the
  input named in the log, and the outputs read afterwards are finite;
- a bearing file with a missing field or a wrong type makes `trb fmu --bearing FILE` exit
  non-zero naming the field;
- an FMU whose resources/bearing.json was corrupted fails to instantiate, and the log message
  names the field."""

import json
import math
import zipfile

import pytest
from fmpy import extract

from conftest import (
    FMI2_DISCARD,
    FMI2_ERROR,
    FMI2_OK,
    REPO,
    Model,
    all_outputs,
    call_status,
    cargo_run,
    get_integer_raw,
    get_real_raw,
    initialize,
    run_cli,
)

H = 1e-3


def read_outputs(fmu):
    m = fmu.model
    names = all_outputs(m)
    reals = [n for n in names if m.vars[n].type == "Real"]
    ints = [n for n in names if m.vars[n].type == "Integer"]
    s1, rv = get_real_raw(fmu, [m.vr(n) for n in reals])
    s2, iv = get_integer_raw(fmu, [m.vr(n) for n in ints])
    return max(s1, s2), dict(zip(reals, rv)), dict(zip(ints, iv))


@pytest.mark.parametrize("value", [float("nan"), float("inf"), float("-inf")], ids=["nan", "inf", "-inf"])
@pytest.mark.parametrize("name", ["Fy", "Fx", "speed", "xi"])
def test_non_finite_input_fails_the_step_and_outputs_stay_finite(slaves, model, hub, name, value):
    fmu = slaves.new(model, name="nan")
    initialize(fmu, inputs={"Fy": 10000.0})
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
    _, good, _ = read_outputs(fmu)

    mark = hub.mark()
    fmu.setReal([model.vr(name)], [value])  # accepted; rejected by the next solve or step
    status = call_status(fmu.doStep, H, H)
    assert status in (FMI2_ERROR, FMI2_DISCARD), f"doStep with {name} = {value} returned {status}"
    logged = [r for r in hub.since(mark) if r.status in (FMI2_ERROR, FMI2_DISCARD)]
    assert logged and any(name in r.message for r in logged), [r.message for r in hub.since(mark)]
    assert all(r.category in ("logStatusError", "logStatusDiscard") for r in logged)

    status, reals, ints = read_outputs(fmu)
    bad = {n: v for n, v in reals.items() if not math.isfinite(v)}
    assert not bad, f"non-finite outputs after {name} = {value}: {bad}"
    # What is returned is the last valid solution, not garbage.
    assert reals["frictionTorque"] == good["frictionTorque"]
    assert 0 <= ints["loadedRollers"] <= model.z

    # fmi2Reset brings the instance back.
    assert call_status(fmu.reset) == FMI2_OK
    initialize(fmu)
    assert call_status(fmu.doStep, 0.0, H) == FMI2_OK


def test_non_finite_input_read_back_before_stepping(slaves, model):
    """Direct feedthrough: reading outputs after a NaN input re-solves, which fails; the
    returned values are still the last valid ones."""
    fmu = slaves.new(model, name="nan-get")
    initialize(fmu)
    _, good, _ = read_outputs(fmu)
    fmu.setReal([model.vr("Fy")], [float("nan")])
    status, reals, _ = read_outputs(fmu)
    assert status == FMI2_ERROR
    assert all(math.isfinite(v) for v in reals.values())
    assert reals["Qo.max"] == good["Qo.max"]
    # Setting a valid value again recovers.
    fmu.setReal([model.vr("Fy")], [0.0])
    status, reals, _ = read_outputs(fmu)
    assert status == FMI2_OK and reals["Qo.max"] == good["Qo.max"]


@pytest.mark.parametrize("value", [float("nan"), float("inf")], ids=["nan", "inf"])
def test_non_finite_parameter_is_rejected_when_set(slaves, model, hub, value):
    fmu = slaves.new(model, name="nan-param")
    mark = hub.mark()
    assert call_status(fmu.setReal, [model.vr("mu")], [value]) == FMI2_ERROR
    assert any("mu" in r.message for r in hub.since(mark))
    # The instance is still usable, with the parameter unchanged.
    initialize(fmu)
    assert fmu.getReal([model.vr("mu")]) == [model.start("mu")]


def test_out_of_range_parameter_fails_initialization(slaves, model, hub):
    fmu = slaves.new(model, name="bad-param")
    fmu.setupExperiment(startTime=0.0)
    fmu.setReal([model.vr("tolerance")], [0.5])  # max is 0.1
    fmu.enterInitializationMode()
    mark = hub.mark()
    status = call_status(fmu.exitInitializationMode)
    assert status == FMI2_ERROR
    assert any("tolerance" in r.message for r in hub.since(mark))


# ---------------------------------------------------------------------------------------
# Bad bearing files
# ---------------------------------------------------------------------------------------


def corrupt(kind: str) -> tuple[str, str]:
    """(JSON text of a broken TRB130x230 bearing, the field the error must name)."""
    b = json.loads((REPO / "presets" / "TRB130x230.json").read_text())
    if kind == "missing-field":
        del b["rollers"]["count"]
        return json.dumps(b, indent=2), "count"
    if kind == "wrong-type":
        b["pitch_diameter_mm"] = "177.91 mm"
        return json.dumps(b, indent=2), "pitch_diameter_mm"
    if kind == "wrong-type-nested":
        b["materials"]["roller"]["E_GPa"] = [201.0]
        return json.dumps(b, indent=2), "E_GPa"
    if kind == "not-json":
        return (REPO / "presets" / "TRB130x230.json").read_text()[:300], "EOF"
    raise ValueError(kind)


@pytest.mark.parametrize("kind", ["missing-field", "wrong-type", "wrong-type-nested", "not-json"])
def test_bad_bearing_file_is_refused_by_the_packager(tmp_path, kind):
    text, field = corrupt(kind)
    bad = tmp_path / "bad.json"
    bad.write_text(text)
    out = tmp_path / "bad.fmu"
    proc = cargo_run("fmu", "--bearing", bad, "--out", out)
    assert proc.returncode != 0, proc.stdout
    assert field in proc.stderr, proc.stderr
    assert "panicked" not in proc.stderr, proc.stderr
    assert not out.exists()


def test_unknown_bearing_name_is_refused(tmp_path):
    proc = run_cli("fmu", "--bearing", "NO-SUCH-BEARING", "--out", tmp_path / "x.fmu", check=False)
    assert proc.returncode != 0
    assert "NO-SUCH-BEARING" in proc.stderr and "panicked" not in proc.stderr


def repack(src, dst, bearing_json: str | None):
    """Copy FMU `src` to `dst` with resources/bearing.json replaced (None: removed)."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            if item.filename == "resources/bearing.json":
                if bearing_json is not None:
                    zout.writestr(item, bearing_json)
            else:
                zout.writestr(item, zin.read(item.filename))
    return dst


@pytest.mark.parametrize("kind", ["missing-field", "wrong-type", "wrong-type-nested", "not-json"])
def test_fmu_with_corrupt_bearing_resource_fails_to_instantiate(fmu_path, tmp_path, slaves, hub, kind):
    text, field = corrupt(kind)
    path = repack(fmu_path, tmp_path / "corrupt.fmu", text)
    model = Model(path, extract(str(path), unzipdir=str(tmp_path / "unzipped")))
    mark = hub.mark()
    with pytest.raises(Exception, match="instantiate"):
        slaves.new(model, name="corrupt")
    errors = [r for r in hub.since(mark) if r.status == FMI2_ERROR]
    assert errors, "no error was logged"
    assert all(r.category == "logStatusError" for r in errors)
    text = " | ".join(r.message for r in errors)
    assert "bearing.json" in text and field in text, text


def test_fmu_with_another_bearing_resource_fails_the_guid_check(fmu_path, tmp_path, slaves, hub):
    other = (REPO / "presets" / "32008.json").read_text()
    path = repack(fmu_path, tmp_path / "swapped.fmu", other)
    model = Model(path, extract(str(path), unzipdir=str(tmp_path / "unzipped")))
    mark = hub.mark()
    with pytest.raises(Exception, match="instantiate"):
        slaves.new(model, name="swapped")
    assert any("fmuGUID" in r.message for r in hub.since(mark))


def test_fmu_without_bearing_resource_falls_back_to_the_default_with_a_warning(fmu_path, tmp_path, slaves, hub):
    path = repack(fmu_path, tmp_path / "nobearing.fmu", None)
    model = Model(path, extract(str(path), unzipdir=str(tmp_path / "unzipped")))
    mark = hub.mark()
    fmu = slaves.new(model, name="fallback")
    warnings = [r for r in hub.since(mark) if r.category == "logStatusWarning"]
    assert warnings and "bearing.json" in warnings[0].message, hub.since(mark)
    initialize(fmu)
    assert math.isfinite(fmu.getReal([model.vr("frictionTorque")])[0])


def test_an_impossible_load_discards_the_step_and_keeps_the_last_solution(slaves, model, hub):
    """No equilibrium (a radial load far beyond the bearing's capacity): fmi2Discard, logged
    in logStatusDiscard; outputs stay those of the last successful step; the last successful
    time is reported; terminate and reset still work."""
    import ctypes

    from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Real

    fmu = slaves.new(model, name="overload")
    initialize(fmu)
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
    _, good, _ = read_outputs(fmu)
    fmu.setReal([model.vr("Fy")], [1e8])
    mark = hub.mark()
    status = call_status(fmu.doStep, H, H)
    assert status == FMI2_DISCARD, status
    logged = hub.since(mark)
    assert logged and logged[0].category == "logStatusDiscard" and "equilibrium" in logged[0].message, logged
    status, reals, _ = read_outputs(fmu)
    assert all(math.isfinite(v) for v in reals.values())
    assert reals["Qo.max"] == good["Qo.max"]
    t = fmi2Real()
    fmu.fmi2GetRealStatus(fmu.component, fmi2LastSuccessfulTime, ctypes.byref(t))
    assert t.value == pytest.approx(H, rel=1e-12)
    assert call_status(fmu.terminate) == FMI2_OK
    assert call_status(fmu.reset) == FMI2_OK
    initialize(fmu)
    assert call_status(fmu.doStep, 0.0, H) == FMI2_OK
