"""The FMU's log messages: declared categories, FMI statuses, the instance name, and text
free of stray format characters (the FMU passes each message as a printf format string with
'%' escaped as '%%' and '#' as '##', as FMI 2.0 requires; fmpy's proxy formats it with
vsnprintf, and FMI's '##' -> '#' is the importer's last step)."""

import re

import pytest
from fmpy import simulate_fmu

from conftest import FMI2_ERROR, FMI2_OK, LogRecord, call_status, initialize

# A printf conversion that survived formatting, or a Rust format placeholder.
STRAY = re.compile(r"%[-+ #0-9.*]*[diouxXeEfFgGaAcspn%]|\{\}|\{:[^}]*\}|\{[a-z_]+\}")


def fmi_unescape(message: str) -> str:
    return message.replace("##", "#")


def check_record(r, categories, instance):
    assert r.category in categories, f"undeclared category {r.category!r}: {r.message}"
    assert r.status in (0, 1, 2, 3, 4), r
    assert r.instance == instance, r
    assert r.message and r.message == r.message.strip(), repr(r.message)
    assert not any(ord(c) < 32 for c in r.message), repr(r.message)
    assert "%" not in r.message and not STRAY.search(r.message), f"stray format characters: {r.message!r}"
    # '#' must come escaped as '##' (a single '#' starts an FMI value-reference reference).
    assert "#" not in r.message.replace("##", ""), f"unescaped '#': {r.message!r}"
    # Status categories carry their status.
    expect = {"logStatusWarning": 1, "logStatusDiscard": 2, "logStatusError": 3, "logStatusFatal": 4}
    if r.category in expect:
        assert r.status == expect[r.category], r
    else:
        assert r.status == FMI2_OK, r


# simulate_fmu wraps this in a ctypes thunk of its own and makes fmpy's C proxy call it; the
# test hands the proxy back to the session hub afterwards (see conftest.LogHub).
RECEIVED = []


def fmpy_logger(component, instance_name, status, category, message):
    RECEIVED.append((instance_name, status, category, message))


def test_simulate_fmu_debug_logging(fmu_path, model, hub):
    """fmpy's `logger` and `debug_logging`: every category on, messages arrive formatted."""
    RECEIVED.clear()
    try:
        simulate_fmu(
            str(fmu_path),
            stop_time=0.005,
            output_interval=0.001,
            start_values={"Fy": 5000.0},
            debug_logging=True,
            logger=fmpy_logger,
        )
    finally:
        hub.install()  # take fmpy's global proxy back (simulate_fmu's ctypes thunk is gone)

    records = [
        LogRecord(i.decode(), int(s), c.decode(), m.decode("utf-8", "replace")) for i, s, c, m in RECEIVED
    ]
    assert records, "no message arrived with debug logging on"
    categories = {c.name for c in model.md.logCategories}
    for r in records:
        check_record(r, categories, model.md.coSimulation.modelIdentifier)
    seen = {r.category for r in records}
    assert {"logEvents", "logSolver"} <= seen, seen
    text = "\n".join(r.message for r in records)
    for expected in ["fmi2Instantiate", "fmi2ExitInitializationMode", "Newton iterations", "fmi2Terminate"]:
        assert expected in text, f"{expected!r} not logged:\n{text}"
    # One solver message per solve: initialization and each of the 5 steps.
    assert sum(r.category == "logSolver" for r in records) >= 6


def test_logging_off_by_default_but_errors_always_arrive(slaves, model, hub):
    mark = hub.mark()
    fmu = slaves.new(model, name="quiet", logging_on=False)
    initialize(fmu, inputs={"Fy": 5000.0})
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    fmu.terminate()
    assert hub.since(mark) == [], hub.since(mark)
    fmu.reset()
    assert call_status(fmu.doStep, 0.0, 1e-3) == FMI2_ERROR
    errs = hub.since(mark)
    assert errs and all(r.category == "logStatusError" for r in errs)
    categories = {c.name for c in model.md.logCategories}
    for r in errs:
        check_record(r, categories, "quiet")


def test_set_debug_logging_by_category(slaves, model, hub):
    fmu = slaves.new(model, name="solver-only", logging_on=False)
    fmu.setDebugLogging(True, ["logSolver"])
    mark = hub.mark()
    initialize(fmu)
    for k in range(3):
        fmu.doStep(currentCommunicationPoint=k * 1e-3, communicationStepSize=1e-3)
    got = hub.since(mark)
    assert got and {r.category for r in got} == {"logSolver"}, got
    assert len(got) == 4
    fmu.setDebugLogging(False, ["logSolver"])
    mark = hub.mark()
    fmu.doStep(currentCommunicationPoint=3e-3, communicationStepSize=1e-3)
    assert hub.since(mark) == []
    # All categories at once (an empty list means all).
    fmu.setDebugLogging(True, [])
    mark = hub.mark()
    fmu.terminate()
    assert [r.category for r in hub.since(mark)] == ["logEvents"]


@pytest.mark.parametrize("name", ["no%dsuch%%cat#1#", "100% sure", "##", "%s%s%s%n"])
def test_message_text_is_escaped_for_printf_and_fmi(slaves, model, hub, name):
    """An unknown category is echoed in the error message: after vsnprintf (fmpy's proxy)
    and FMI's '##' -> '#', the text is exactly what was passed in."""
    fmu = slaves.new(model, name="escape")
    mark = hub.mark()
    assert call_status(fmu.setDebugLogging, True, [name]) == FMI2_ERROR
    errs = hub.since(mark)
    assert len(errs) == 1 and errs[0].category == "logStatusError"
    message = fmi_unescape(errs[0].message)
    assert f'"{name}"' in message, f"{errs[0].message!r} does not quote {name!r}"
    assert "logEvents" in message  # the known categories are listed


# Rust's Debug form of Option (`Some(0.1)`, `None`) leaking into a user-facing message.
RUST_DEBUG = re.compile(r"\bSome\(|\bNone\b")


@pytest.mark.parametrize("stop", [0.005, None], ids=["stop-time", "no-stop-time"])
def test_messages_have_no_rust_debug_syntax(slaves, model, hub, stop):
    fmu = slaves.new(model, name="debug-syntax", logging_on=True)
    mark = hub.mark()
    initialize(fmu, stop=stop)
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    fmu.terminate()
    bad = [r.message for r in hub.since(mark) if RUST_DEBUG.search(r.message)]
    assert not bad, bad
