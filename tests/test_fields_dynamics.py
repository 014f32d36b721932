"""Numerical behaviour of assistbot.fields, on both stepping paths."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from assistbot.fields import Network
from assistbot.fields.demo import demo_spec

BACKENDS = ["numpy", "numba"]
ITEMS = ["a", "b", "c", "d"]


def one_field(A: float, w_inhib: float, dt: float = 0.005, **extra) -> Network:
    spec = {"items": ITEMS, "tau": 0.05, "h": -3.0, "beta": 4.0,
            "kernel": {"A": A, "sigma": 2.0, "w_inhib": w_inhib}, "input_sigma": 2.0}
    spec.update(extra)
    backend = extra.pop("backend", None)
    spec.pop("backend", None)
    return Network.from_dict({"dt": dt, "fields": {"F": spec}}, backend=backend or "numpy")


MEMORY = dict(A=3.0, w_inhib=1.0)  # self-sustained regime
DRIVEN = dict(A=1.0, w_inhib=1.0)  # input-driven regime


@pytest.mark.parametrize("backend", BACKENDS)
def test_resting_state_without_input_is_h(backend):
    net = one_field(**MEMORY, backend=backend)
    net.state_u[:] += np.linspace(-1, 1, net.state_u.size)  # start away from rest
    net.run(1.0)
    assert np.allclose(net.u("F"), -3.0, atol=1e-3)


@pytest.mark.parametrize("backend", BACKENDS)
def test_peak_persists_in_memory_regime_and_decays_when_input_driven(backend):
    mem, drv = one_field(**MEMORY, backend=backend), one_field(**DRIVEN, backend=backend)
    for net in (mem, drv):
        net.set_stimulus("F", "b", 5.0)
        net.run(1.0)
        assert net.peaks("F") == ["b"]
        net.clear_stimuli()
        net.run(2.0)
    assert mem.activity("F", "b") > 2.0, "memory peak lost after the input was removed"
    assert mem.peaks("F") == ["b"]
    assert drv.activity("F", "b") < -2.5 and drv.peaks("F") == []


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("regime", [MEMORY, DRIVEN])
def test_two_inputs_give_one_winner_the_stronger(backend, regime):
    net = one_field(**regime, backend=backend)
    net.set_stimulus("F", "a", 4.0)
    net.set_stimulus("F", "c", 5.0)
    net.run(2.0)
    assert net.peaks("F") == ["c"]
    assert net.activity("F", "a") < -1.0


@pytest.mark.parametrize("backend", BACKENDS)
def test_hysteresis_detection_and_reverse_detection_differ(backend):
    # bistable but not self-sustained at zero input: the peak forms at a higher
    # input than the one at which it is lost
    net = one_field(A=1.0, w_inhib=0.0, backend=backend)
    levels = np.round(np.arange(0.0, 4.01, 0.05), 2)
    up = down = None
    for s in levels:
        net.set_stimulus("F", "b", s)
        net.run(0.4)
        if up is None and net.activity("F", "b") > 0:
            up = s
    for s in levels[::-1]:
        net.set_stimulus("F", "b", s)
        net.run(0.4)
        if net.activity("F", "b") <= 0:
            down = s
            break
    assert up is not None and down is not None
    assert down < up - 0.5, f"no hysteresis: detection at {up}, reverse detection at {down}"


@pytest.mark.parametrize("backend", BACKENDS)
def test_dt_convergence(backend):
    traces = {}
    for dt in (0.004, 0.001):
        net = one_field(**MEMORY, dt=dt, backend=backend)
        net.set_stimulus("F", "a", 4.0)
        net.set_stimulus("F", "c", 5.0)
        net.run(0.2)
        traces[dt] = net.u("F").copy()
    err = np.max(np.abs(traces[0.004] - traces[0.001]))
    assert err < 0.25, f"dt and dt/4 differ by {err:.3f} (tolerance 0.25 on activity of range ~15)"


def coincidence_net(backend: str) -> Network:
    spec = demo_spec()
    return Network.from_dict(spec, backend=backend)


@pytest.mark.parametrize("backend", BACKENDS)
def test_weak_coupling_one_source_stays_below_threshold_two_make_a_peak(backend):
    net = coincidence_net(backend)
    net.set_stimulus("source_1", "B", 5.0)
    net.run(1.5)
    assert net.peaks("source_1") == ["B"]
    assert net.presence("source_1")[1] > 0.99
    assert -2.0 < net.activity("target", "B") < -0.5, "one scaled source must lift the target, but not over threshold"
    net.clear_stimuli()
    net.reset_field("source_1")
    net.set_stimulus("source_2", "C", 5.0)
    net.run(1.5)
    assert net.peaks("target") == []
    net.set_stimulus("source_1", "B", 5.0)
    net.run(1.5)
    assert net.peaks("target") == ["B"]


def test_agrees_with_solve_ivp_reference():
    """Independent reference: the dense, untruncated eq. (1)-(3) integrated by scipy."""
    N, dx, tau, h, beta, u0 = 41, 0.5, 0.05, -2.0, 3.0, 0.0
    A, sigma, w_inh = 2.5, 1.5, 0.3
    net = Network.from_dict({"dt": 0.0005, "fields": {"F": {
        "size": N, "dx": dx, "tau": tau, "h": h, "beta": beta, "u0": u0,
        "kernel": {"A": A, "sigma": sigma, "w_inhib": w_inh}}}}, backend="numpy")
    net.set_stimulus_at("F", "s", position=8.0, amplitude=4.0, sigma=1.0)
    x = np.arange(N) * dx
    W = (A * np.exp(-((x[:, None] - x[None, :]) ** 2) / (2 * sigma**2)) - w_inh) * dx
    S = 4.0 * np.exp(-((x - 8.0) ** 2) / 2.0)

    def rhs(_t, u):
        return (-u + S + W @ (1 / (1 + np.exp(-beta * (u - u0)))) + h) / tau

    ref = solve_ivp(rhs, (0, 0.3), np.full(N, h), rtol=1e-9, atol=1e-9, t_eval=[0.1, 0.3])
    net.run(0.1)
    at_01 = net.u("F").copy()
    net.run(0.2)
    assert np.max(np.abs(at_01 - ref.y[:, 0])) < 0.02
    assert np.max(np.abs(net.u("F") - ref.y[:, 1])) < 0.02
    assert net.u("F").max() > 1.0  # a peak did form: the comparison is not of two resting fields


def test_numba_and_numpy_paths_agree_on_a_coupled_network():
    nets = {b: coincidence_net(b) for b in BACKENDS}
    for net in nets.values():
        net.set_stimulus("source_1", "B", 5.0)
        net.set_stimulus("source_2", "C", 5.0)
        net.set_stimulus_at("memory", "p", 12.0, 3.0)
        net.run(1.0)
    for name in nets["numpy"].field_names:
        assert np.allclose(nets["numpy"].u(name), nets["numba"].u(name), atol=1e-9), name
        assert np.allclose(nets["numpy"].input(name), nets["numba"].input(name), atol=1e-9), name


@pytest.mark.parametrize("backend", BACKENDS)
def test_periodic_field_interacts_across_its_ends(backend):
    lin = one_field(**MEMORY, backend=backend)
    per = one_field(**MEMORY, periodic=True, backend=backend)
    for net in (lin, per):
        net.set_stimulus_at("F", "edge", position=0.0, amplitude=6.0, sigma=2.0)
        net.run(1.0)
    # the peak at x=0 excites the last positions only when the field wraps around
    assert per.u("F")[-1] > lin.u("F")[-1] + 1.0
    assert per.u("F")[-1] > 0.0


@pytest.mark.parametrize("backend", BACKENDS)
def test_noise_is_scaled_with_sqrt_dt(backend):
    # without interaction, tau du = (-u + h) dt + q dW has stationary variance q^2 / (2 tau)
    variances = []
    for dt in (0.004, 0.001):
        net = Network.from_dict({"dt": dt, "fields": {"F": {"size": 400, "tau": 0.05, "h": -3.0, "noise": 0.2}}},
                                backend=backend, seed=3)
        net.run(0.5)
        samples = []
        for _ in range(20):
            net.run(0.1)
            samples.append(net.u("F").copy())
        variances.append(np.var(np.concatenate(samples)))
    expected = 0.2**2 / (2 * 0.05)
    for v in variances:
        assert abs(v - expected) / expected < 0.15, (variances, expected)


def test_same_seed_same_noisy_run_different_seed_differs():
    def run(seed):
        net = Network.from_dict({"dt": 0.005, "fields": {"F": {"size": 50, "tau": 0.05, "h": -3.0, "noise": 0.5}}}, seed=seed)
        net.run(0.5)
        return net.u("F").copy()

    assert np.array_equal(run(1), run(1))
    assert not np.array_equal(run(1), run(2))


def test_parameters_change_by_path_while_running_and_keep_activity():
    net = one_field(**MEMORY)
    net.set_stimulus("F", "b", 5.0)
    net.run(1.0)
    before = net.u("F").copy()
    net.set("fields.F.kernel.A", 3.5)
    assert net.get("fields.F.kernel.A") == 3.5
    assert np.array_equal(net.u("F"), before)
    assert net.activities("F")["b"] > 0
    net.set("fields.F.h", -5.0)
    net.clear_stimuli()
    net.set("fields.F.kernel.A", 0.5)
    net.run(2.0)
    assert np.allclose(net.u("F"), -5.0, atol=0.05)


def test_coupling_k_by_path_switches_the_target():
    net = coincidence_net("numpy")
    net.set("couplings.source_1->target.k", 1.5)  # now one source alone is enough
    net.set_stimulus("source_1", "B", 5.0)
    net.run(1.5)
    assert net.peaks("target") == ["B"]
    assert "couplings.source_1->target.table.B.B" in net.parameter_paths()


def test_recording_and_plot(tmp_path):
    net = coincidence_net("numpy")
    rec = net.record(["target", "source_1"], every=2)
    net.set_stimulus("source_1", "B", 5.0)
    net.run(0.5)
    assert rec.u["target"].shape == (1 + 50, 40)
    assert np.allclose(rec.times[1:] - rec.times[:-1], 0.01)
    assert rec.item_traces("source_1")["B"][-1] > 0
    from assistbot.fields import plot_history

    png = plot_history(rec, "source_1", tmp_path / "s1.png")
    assert png.stat().st_size > 10_000
    assert png.read_bytes()[:4] == b"\x89PNG"


def test_table_prints_readably():
    text = coincidence_net("numpy").describe_table("source_2->target")
    lines = text.splitlines()
    assert lines[0] == "source_2->target (k=0.6)"
    row_b = [line for line in lines if line.strip().startswith("B |")][0]
    assert row_b.split("|")[1].split() == [".", ".", "3", "."]


def test_compiled_sigmoid_matches_the_exact_one_over_the_whole_range():
    from scipy.special import expit

    from assistbot.fields.stepping import numba_sigmoid

    u = np.concatenate([np.linspace(-400, 400, 200_001), [-1e6, 1e6, 0.0]])
    got = numba_sigmoid(u, 4.0, 0.5)
    want = expit(4.0 * (u - 0.5))
    assert not np.isnan(got).any()
    assert np.max(np.abs(got - want)) < 1e-15
    tiny = want > 1e-300
    assert np.max(np.abs(got - want)[tiny] / want[tiny]) < 1e-14


def test_item_state_indices_address_items_in_the_state_vector():
    net = coincidence_net("numpy")
    net.set_stimulus("target", "C", 5.0)
    net.run(0.5)
    idx = net.item_state_indices("target")
    assert np.array_equal(net.state_u[idx], net.u("target")[net.field("target").item_indices])
    assert net.state_u[idx[2]] == net.activity("target", "C")
