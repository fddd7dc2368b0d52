"""Illegal call sequences return fmi2Error (fmpy raises FMICallException with status 3) and
log the reason in category logStatusError; instances that are still usable stay usable."""

import ctypes
from pathlib import Path

import pytest
from fmpy.fmi2 import FMU2Slave, fmi2CoSimulation, fmi2ModelExchange, fmi2Real

from conftest import FMI2_ERROR, FMI2_OK, call_status, get_real_raw, initialize

H = 1e-3


@pytest.fixture
def fmu(slaves, model):
    return slaves.new(model, name="illegal")


def errors_since(hub, mark):
    return [r for r in hub.since(mark) if r.status == FMI2_ERROR]


def assert_error_logged(hub, mark, *words):
    errs = errors_since(hub, mark)
    assert errs, "no error was logged"
    for r in errs:
        assert r.category == "logStatusError", r
    text = " | ".join(r.message for r in errs)
    for w in words:
        assert w in text, f"{w!r} not in the logged errors: {text}"


def test_do_step_before_initialization(fmu, hub):
    mark = hub.mark()
    assert call_status(fmu.doStep, 0.0, H) == FMI2_ERROR
    assert_error_logged(hub, mark, "fmi2DoStep", "Instantiated")
    # Still usable.
    initialize(fmu)
    assert call_status(fmu.doStep, 0.0, H) == FMI2_OK


def test_do_step_in_initialization_mode(fmu, hub):
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    mark = hub.mark()
    assert call_status(fmu.doStep, 0.0, H) == FMI2_ERROR
    assert_error_logged(hub, mark, "fmi2DoStep", "InitializationMode")


def test_get_real_before_initialization(fmu, model, hub):
    mark = hub.mark()
    status, _ = get_real_raw(fmu, [model.vr("frictionTorque")])
    assert status == FMI2_ERROR
    assert_error_logged(hub, mark, "fmi2GetReal")


@pytest.mark.parametrize(
    "name, value",
    [("mu", 0.2), ("tolerance", 1e-8), ("roller[3].dD", 1e-6), ("fidelity", 1), ("slices", 10), ("skewModel", True)],
)
def test_setting_a_fixed_parameter_after_initialization(fmu, model, hub, name, value):
    initialize(fmu)
    v = model.vars[name]
    before = {"Real": fmu.getReal, "Integer": fmu.getInteger, "Enumeration": fmu.getInteger, "Boolean": fmu.getBoolean}[v.type]([v.valueReference])
    setter = {"Real": fmu.setReal, "Integer": fmu.setInteger, "Enumeration": fmu.setInteger, "Boolean": fmu.setBoolean}[v.type]
    mark = hub.mark()
    assert call_status(setter, [v.valueReference], [value]) == FMI2_ERROR
    assert_error_logged(hub, mark, name)
    after = {"Real": fmu.getReal, "Integer": fmu.getInteger, "Enumeration": fmu.getInteger, "Boolean": fmu.getBoolean}[v.type]([v.valueReference])
    assert after == before
    # The instance goes on.
    assert call_status(fmu.doStep, 0.0, H) == FMI2_OK


def test_inputs_may_be_set_after_initialization(fmu, model):
    initialize(fmu)
    fmu.setReal([model.vr("Fy")], [1000.0])
    assert fmu.getReal([model.vr("Fy")]) == [1000.0]
    assert call_status(fmu.doStep, 0.0, H) == FMI2_OK


def test_setting_an_output_or_an_unknown_reference(fmu, model, hub):
    mark = hub.mark()
    assert call_status(fmu.setReal, [model.vr("frictionTorque")], [1.0]) == FMI2_ERROR
    assert_error_logged(hub, mark, "frictionTorque")
    initialize(fmu)
    mark = hub.mark()
    assert call_status(fmu.setReal, [999999], [1.0]) == FMI2_ERROR
    assert call_status(fmu.getReal, [999999]) == FMI2_ERROR
    assert call_status(fmu.getInteger, [model.vr("frictionTorque")]) == FMI2_ERROR  # a Real, not an Integer
    assert_error_logged(hub, mark, "999999")


def test_do_step_after_terminate(fmu, hub):
    initialize(fmu)
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
    fmu.terminate()
    mark = hub.mark()
    assert call_status(fmu.doStep, H, H) == FMI2_ERROR
    assert_error_logged(hub, mark, "fmi2DoStep", "Terminated")
    # Outputs can still be read after terminate.
    status, values = get_real_raw(fmu, [fmu.model.vr("frictionTorque")])
    assert status == FMI2_OK and values[0] > 0


def test_mismatched_communication_point(fmu, model, hub):
    initialize(fmu)
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
    mark = hub.mark()
    assert call_status(fmu.doStep, 0.5, H) == FMI2_ERROR
    assert_error_logged(hub, mark, "currentCommunicationPoint")
    # The instance is in the Error state now: only reset (or free) helps.
    assert call_status(fmu.doStep, H, H) == FMI2_ERROR
    assert call_status(fmu.reset) == FMI2_OK
    initialize(fmu)
    assert call_status(fmu.doStep, 0.0, H) == FMI2_OK


def test_a_step_that_repeats_the_last_one_is_a_mismatch(fmu):
    initialize(fmu)
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
    assert call_status(fmu.doStep, 0.0, H) == FMI2_ERROR


@pytest.mark.parametrize("h", [0.0, -H, float("nan"), float("inf")])
def test_bad_step_size(fmu, h):
    initialize(fmu)
    assert call_status(fmu.doStep, 0.0, h) == FMI2_ERROR


def test_step_past_the_stop_time(fmu):
    initialize(fmu, stop=2 * H)
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
    assert call_status(fmu.doStep, H, 5 * H) == FMI2_ERROR


def test_variable_step_sizes_are_accepted(fmu, model):
    initialize(fmu, stop=0.01)
    t = 0.0
    for h in [1e-3, 2.5e-4, 3e-3, 1e-6, 0.01 - 4.251e-3]:
        assert call_status(fmu.doStep, t, h) == FMI2_OK
        t += h
    value = fmi2Real()
    fmu.fmi2GetRealStatus(fmu.component, 2, ctypes.byref(value))  # fmi2LastSuccessfulTime
    assert value.value == pytest.approx(0.01, rel=1e-12)


@pytest.mark.parametrize(
    "call",
    ["enter-twice", "exit-before-enter", "terminate-before-init", "setup-after-init"],
)
def test_life_cycle_out_of_order(fmu, call):
    if call == "enter-twice":
        fmu.enterInitializationMode()
        assert call_status(fmu.enterInitializationMode) == FMI2_ERROR
    elif call == "exit-before-enter":
        assert call_status(fmu.exitInitializationMode) == FMI2_ERROR
    elif call == "terminate-before-init":
        assert call_status(fmu.terminate) == FMI2_ERROR
    elif call == "setup-after-init":
        initialize(fmu)
        assert call_status(fmu.setupExperiment, None, 0.0, None) == FMI2_ERROR


def test_instantiate_rejects_a_wrong_guid_or_model_exchange(model, hub):
    fmu = FMU2Slave(guid=model.md.guid, unzipDirectory=model.unzipdir, modelIdentifier="TaperedRollerBearing")
    try:
        uri = Path(model.unzipdir, "resources").as_uri().encode()
        cb = hub.callbacks
        mark = hub.mark()
        c = fmu.fmi2Instantiate(b"wrong-guid", fmi2CoSimulation, b"{00000000-0000-0000-0000-000000000000}", uri, ctypes.byref(cb), 0, 0)
        assert not c
        assert any("fmuGUID" in r.message and r.status == FMI2_ERROR for r in hub.since(mark))
        c = fmu.fmi2Instantiate(b"me", fmi2ModelExchange, model.md.guid.encode(), uri, ctypes.byref(cb), 0, 0)
        assert not c
        c = fmu.fmi2Instantiate(b"ok", fmi2CoSimulation, model.md.guid.encode(), uri, ctypes.byref(cb), 0, 0)
        assert c
        fmu.fmi2FreeInstance(c)
    finally:
        fmu.freeLibrary()
