"""A field's input split by source: each incoming coupling's part, summing with the stimuli to the S the step
uses (both stepping paths), and recorded at the items for the inspector."""

from __future__ import annotations

import numpy as np
import pytest

from assistbot.fields import Network

SPEC = {"dt": 0.005, "fields": {
    "A": {"items": ["a", "b"], "spacing": 10, "tau": 0.05, "h": -2.0},
    "B": {"items": ["x", "y", "z"], "spacing": 10, "tau": 0.05, "h": -2.0}},
    "couplings": [{"source": "A", "target": "B", "k": 2.0, "table": {"x": {"a": 1.0}, "y": {"a": 0.5, "b": 1.0}}},
                  {"source": "B", "target": "B", "name": "self", "k": 0.5, "table": {"z": {"x": 1.0}}}]}


@pytest.mark.parametrize("backend", ["numpy", "numba"])
def test_the_couplings_parts_and_the_stimuli_make_the_input_of_the_next_step(backend):
    net = Network.from_dict(SPEC, backend=backend)
    net.set_stimulus("A", "a", 5.0)
    net.set_stimulus("B", "z", 1.5)
    net.step(100)
    rests = []      # S of the next step beyond the couplings' parts: the stimulus, the same each step
    for _ in range(3):
        parts = net.coupling_inputs("B")
        net.step(1)
        rests.append(net.input("B") - sum(parts.values()))
    assert set(parts) == {"A->B", "self"}
    np.testing.assert_allclose(rests[0], rests[1], atol=1e-9)
    np.testing.assert_allclose(rests[0], rests[2], atol=1e-9)
    at = net.spec.fields["B"].item_indices
    assert rests[0][at[2]] == pytest.approx(1.5, rel=0.05) and abs(rests[0][at[0]]) < 1e-3
    assert parts["A->B"][at[0]] > 1.0 and parts["self"][at[0]] == pytest.approx(0.0, abs=1e-6)
    assert net.coupling_inputs("A") == {}


def test_a_recording_keeps_each_couplings_part_at_the_items_of_the_fields_asked_for():
    net = Network.from_dict(SPEC, backend="numpy")
    net.set_stimulus("A", "a", 5.0)
    rec = net.record(every=10, couplings=["B"])
    net.step(100)
    parts = rec.coupling_items
    assert set(parts) == {"B"} and set(parts["B"]) == {"A->B", "self"}
    assert parts["B"]["A->B"].shape == (len(rec.times), 3)
    # x gets a's output through A->B (k 2, weight 1); y a half of it and all of b's
    last = parts["B"]["A->B"][-1]
    assert last[0] > last[2] == pytest.approx(0.0, abs=1e-9)
