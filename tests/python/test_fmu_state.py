"""FMU states: get/set restores the instance exactly; serialized states round-trip, also into
a second instance; the serialization is deterministic."""

import ctypes
import math

import pytest

from conftest import FMI2_ERROR, all_outputs, call_status, initialize

H = 1e-3
LOADED = {"Fy": 20000.0, "xi": 3e-5}  # a moving load zone: every step solves anew


def snapshot(fmu, names):
    """All outputs (exact values) and the FMU's time."""
    m = fmu.model
    reals = [n for n in names if m.vars[n].type == "Real"]
    ints = [n for n in names if m.vars[n].type == "Integer"]
    return tuple(fmu.getReal([m.vr(n) for n in reals])) + tuple(fmu.getInteger([m.vr(n) for n in ints]))


def two_steps(fmu, t, names, fy_second=None):
    """Step, optionally change Fy, step again; outputs after each step."""
    fmu.doStep(currentCommunicationPoint=t, communicationStepSize=H)
    a = snapshot(fmu, names)
    if fy_second is not None:
        fmu.setReal([fmu.model.vr("Fy")], [fy_second])
    fmu.doStep(currentCommunicationPoint=t + H, communicationStepSize=H)
    b = snapshot(fmu, names)
    return a, b


@pytest.fixture
def running(slaves, model):
    """An instance initialized with a radial load and deflection, stepped to t = 3 ms."""
    fmu = slaves.new(model, name="state")
    initialize(fmu, inputs=LOADED)
    for k in range(3):
        fmu.doStep(currentCommunicationPoint=k * H, communicationStepSize=H)
    return fmu


def test_get_set_fmu_state_replays_exactly(running, model):
    names = all_outputs(model)
    fmu = running
    t = 3 * H
    state = fmu.getFMUstate()
    first = two_steps(fmu, t, names, fy_second=25000.0)
    assert first[0] != first[1]
    fmu.setFMUstate(state)
    # The restored instance is back at t (a step from t + 2H would be a mismatch now).
    second = two_steps(fmu, t, names, fy_second=25000.0)
    assert second == first
    # Restoring also restores the input changed after the snapshot.
    fmu.setFMUstate(state)
    assert fmu.getReal([model.vr("Fy")]) == [LOADED["Fy"]]
    # Overwrite the snapshot in place (getFMUstate with an existing state), then free it.
    fmu.fmi2GetFMUstate(fmu.component, ctypes.byref(state))
    fmu.freeFMUstate(state)
    assert not state


def test_serialized_state_round_trips_in_the_same_and_a_second_instance(running, model, slaves):
    names = all_outputs(model)
    fmu = running
    t = 3 * H
    state = fmu.getFMUstate()
    blob = fmu.serializeFMUstate(state)
    assert len(blob) > 0
    assert fmu.serializeFMUstate(state) == blob, "serialization is not deterministic"
    reference = two_steps(fmu, t, names, fy_second=15000.0)

    # Same instance: deserialize into a new state, set it, replay.
    restored = fmu.deSerializeFMUstate(blob)
    fmu.setFMUstate(restored)
    assert two_steps(fmu, t, names, fy_second=15000.0) == reference
    assert fmu.serializeFMUstate(restored) == blob
    fmu.freeFMUstate(restored)
    fmu.freeFMUstate(state)

    # A second instance, only instantiated: the state carries parameters, inputs, time and
    # the state machine, so after setting it the instance continues from t.
    other = slaves.new(model, name="other")
    other_state = other.deSerializeFMUstate(blob)
    other.setFMUstate(other_state)
    assert two_steps(other, t, names, fy_second=15000.0) == reference
    other.freeFMUstate(other_state)


def test_state_of_an_uninitialized_instance_resets_it(slaves, model):
    """A state taken right after instantiation brings an initialized instance back there."""
    names = all_outputs(model)
    fmu = slaves.new(model, name="fresh")
    state = fmu.getFMUstate()
    initialize(fmu, inputs=LOADED)
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
    first = snapshot(fmu, names)
    fmu.setFMUstate(state)
    # Instantiated again: stepping is illegal, initialization works and gives the same result.
    assert call_status(fmu.doStep, 0.0, H) == FMI2_ERROR
    initialize(fmu, inputs=LOADED)
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
    assert snapshot(fmu, names) == first
    fmu.freeFMUstate(state)


def test_corrupt_or_foreign_serialized_state_is_rejected(running, models, slaves):
    fmu = running
    state = fmu.getFMUstate()
    blob = fmu.serializeFMUstate(state)
    fmu.freeFMUstate(state)
    for bad in [b"", b"garbage", blob[:-7], b"X" + blob[1:]]:
        status = call_status(fmu.deSerializeFMUstate, bad)
        assert status == FMI2_ERROR, f"{len(bad)} bytes accepted"
    # The instance still works.
    fmu.doStep(currentCommunicationPoint=3 * H, communicationStepSize=H)
    out = fmu.getReal([fmu.model.vr("frictionTorque")])[0]
    assert math.isfinite(out)
    # A state of another bearing (32008, 23 rollers) does not fit this instance.
    other = slaves.new(models("32008"), name="other-bearing")
    initialize(other)
    s = other.getFMUstate()
    foreign = other.serializeFMUstate(s)
    other.freeFMUstate(s)
    assert call_status(fmu.deSerializeFMUstate, foreign) == FMI2_ERROR


def test_fmu_states_survive_reset(running, model):
    names = all_outputs(model)
    fmu = running
    state = fmu.getFMUstate()
    reference = two_steps(fmu, 3 * H, names)
    fmu.reset()
    fmu.setFMUstate(state)
    assert two_steps(fmu, 3 * H, names) == reference
    fmu.freeFMUstate(state)


def test_restoring_a_state_taken_before_a_failed_step_recovers(running, model):
    """A snapshot before an impossible load lets the master retry the step with a smaller load."""
    names = all_outputs(model)
    fmu = running
    before = fmu.getFMUstate()
    fmu.setReal([model.vr("Fy")], [1e8])
    assert call_status(fmu.doStep, 3 * H, H) != 0
    fmu.setFMUstate(before)
    fmu.setReal([model.vr("Fy")], [30000.0])
    fmu.doStep(currentCommunicationPoint=3 * H, communicationStepSize=H)
    out = snapshot(fmu, names)
    assert all(math.isfinite(v) for v in out)
    fmu.freeFMUstate(before)


@pytest.mark.parametrize(
    "fidelity,integrator",
    [(0, 0), (1, 0), (1, 1), (1, 2), (1, 3)],
    ids=["quasi-static", "dormand-prince", "milne-hamming", "rosenbrock-w", "automatic"],
)
def test_serialized_state_replays_bit_for_bit_at_every_fidelity(slaves, model, fidelity, integrator):
    """serialize -> deserialize (the same instance after it stepped on, and a fresh one) ->
    step gives the uninterrupted run's outputs bit for bit, step counters included."""
    h = 1e-4
    params = {"fidelity": fidelity, "integrator": integrator}
    if integrator == 1:
        params["maxStep"] = 1e-6  # a fixed step that resolves the contact modes
    names = all_outputs(model)
    if fidelity == 1:
        assert "integrator.steps" in names and "integrator.rhs" in names

    def steps(fmu, t0, n):
        out = []
        for k in range(n):
            fmu.setReal([model.vr("Fy")], [20000.0 + 500.0 * k])
            fmu.doStep(currentCommunicationPoint=t0 + k * h, communicationStepSize=h)
            out.append(snapshot(fmu, names))
        return out

    fmu = slaves.new(model, name=f"serial{fidelity}{integrator}")
    initialize(fmu, params=params, inputs=LOADED)
    steps(fmu, 0.0, 3)
    state = fmu.getFMUstate()
    blob = fmu.serializeFMUstate(state)
    fmu.freeFMUstate(state)
    t = 3 * h
    reference = steps(fmu, t, 4)

    restored = fmu.deSerializeFMUstate(blob)
    fmu.setFMUstate(restored)
    fmu.freeFMUstate(restored)
    assert steps(fmu, t, 4) == reference, "same instance"

    fresh = slaves.new(model, name=f"fresh{fidelity}{integrator}")
    restored = fresh.deSerializeFMUstate(blob)
    fresh.setFMUstate(restored)
    fresh.freeFMUstate(restored)
    assert steps(fresh, t, 4) == reference, "fresh instance"
