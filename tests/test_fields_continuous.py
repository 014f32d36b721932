"""Continuous couplings, 2-D fields and projections: the two stepping paths agree, the dense equation agrees,
and the DFT behaviours they exist for (a 2-D peak read out along an axis, two 1-D cues meeting in a plane)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from assistbot.fields import FieldError, Network

BACKENDS = ["numpy", "numba"]


def field(size=40, periodic=False, A=2.0, sigma=2.0, w_inhib=0.1, **extra):
    d = {"size": size, "tau": 0.05, "h": -3.0, "beta": 4.0, "periodic": periodic,
         "kernel": {"A": A, "sigma": sigma, "w_inhib": w_inhib}}
    d.update(extra)
    return d


def plane(ny=12, nx=16, periodic=False, **extra):
    d = {"shape": [ny, nx], "tau": 0.05, "h": -3.0, "beta": 4.0, "periodic": periodic,
         "kernel": {"A": 3.0, "sigma": 1.5, "w_inhib": 0.02}}
    d.update(extra)
    return d


def mixed_spec() -> dict:
    """Every kind of term at once: lateral kernels that share their shape with a coupling (summed before one
    convolution on the compiled path) and ones that do not, both boundaries, an inhibitory and a
    position-to-position coupling, normalised and cut-off kernels, sum and max projections over both axes,
    expansions along both axes, and an item coupling beside them."""
    same = {"A": 2.0, "sigma": 2.0}
    return {"dt": 0.005, "fields": {
        "a": field(), "b": field(), "ring": field(periodic=True, kernel={"A": 2.0, "sigma": 3.0, "w_inhib": 0.1,
                                                                          "normalize": True, "cutoff": 3}),
        "P": plane(), "Q": plane(periodic=True), "along_x": field(size=16), "along_y": field(size=12),
        "items": {"items": ["p", "q", "r", "s"], "spacing": 10, "tau": 0.05, "h": -3.0,
                  "kernel": {"A": 1.0, "sigma": 2.0, "w_inhib": 0.5}},
    }, "couplings": [
        {"source": "a", "target": "b", "kernel": same},
        {"source": "b", "target": "a", "kernel": {"A": -1.5, "sigma": 4.0}, "boundary": "circular"},
        {"source": "a", "target": "ring", "kernel": {"A": 1.0, "sigma": 0}},
        {"source": "ring", "target": "b", "kernel": {"A": 0.8, "sigma": 3.0, "normalize": True, "cutoff": 2}},
        {"source": "P", "target": "along_x", "kernel": {"A": 0.5, "sigma": 1.0}, "project": {"op": "sum", "over": "y"}},
        {"source": "P", "target": "along_y", "kernel": {"A": 2.0, "sigma": 1.0}, "project": {"op": "max", "over": "x"}},
        {"source": "Q", "target": "along_x", "kernel": {"A": 2.0, "sigma": 0}, "project": {"op": "max", "over": "y"}},
        {"source": "Q", "target": "along_y", "kernel": {"A": 0.3, "sigma": 1.0}, "project": {"op": "sum", "over": "x"}},
        {"source": "along_x", "target": "Q", "kernel": {"A": 1.5, "sigma": 1.5}, "expand": "y"},
        {"source": "along_y", "target": "Q", "kernel": {"A": 1.5, "sigma": 1.0}, "expand": "x"},
        {"source": "P", "target": "Q", "kernel": {"A": 1.0, "sigma": 1.5}},
        {"source": "along_x", "target": "along_x", "name": "self", "kernel": {"A": 0.5, "sigma": 2.0}},
        {"source": "items", "target": "items", "name": "items-loop", "k": 1.0, "table": {"q": {"p": 2.0}}},
    ]}


def drive(net: Network) -> None:
    net.set_stimulus_at("a", "s", 12.0, 5.0, 2.0)
    net.set_stimulus_at("ring", "s", 38.0, 5.0, 2.0)
    net.set_stimulus_at("P", "s", (5.0, 4.0), 6.0, 1.5)
    net.set_stimulus_at("Q", "s", (14.5, 10.5), 6.0, 1.5)
    net.set_stimulus("items", "p", 5.0)


def test_both_stepping_paths_compute_the_same_sums():
    nets = {b: Network.from_dict(mixed_spec(), backend=b) for b in BACKENDS}
    for net in nets.values():
        drive(net)
        net.run(0.5)
    ref, fast = nets["numpy"], nets["numba"]
    assert fast.backend == "numba"
    for name in ref.field_names:
        assert np.max(np.abs(ref.u(name) - fast.u(name))) < 1e-10, name
        assert np.max(np.abs(ref.input(name) - fast.input(name))) < 1e-10, name
        assert np.abs(ref.u(name) + 3.0).max() > 0.5, f"{name} is at rest: the comparison would test nothing"
    assert sum(ref.u(name).max() > 0 for name in ref.field_names) >= 6


def test_terms_sharing_a_kernel_are_summed_before_one_convolution():
    """Sharing a kernel shape merges a lateral kernel and a coupling into one convolution; that is the
    sum of the two convolutions, which the per-term numpy path computes apart."""
    spec = mixed_spec()
    spec["couplings"][0]["kernel"] = {"A": 2.0, "sigma": 2.0000001}  # a different shape: two convolutions
    nets = {b: Network.from_dict(spec, backend=b) for b in BACKENDS}
    merged = Network.from_dict(mixed_spec(), backend="numba")
    for net in (*nets.values(), merged):
        drive(net)
        net.run(0.5)
    assert np.max(np.abs(nets["numpy"].state_u - nets["numba"].state_u)) < 1e-10
    assert np.max(np.abs(merged.state_u - nets["numba"].state_u)) < 1e-4  # sigma differs by 1e-7


def dense_conv(n: int, dx: float, A: float, sigma: float, circular: bool) -> np.ndarray:
    """Untruncated A dx g(x_i - x_j), the integral of eq. (1) as a sum."""
    x = np.arange(n) * dx
    d = x[:, None] - x[None, :]
    if circular:
        d = (d + n * dx / 2) % (n * dx) - n * dx / 2
    return A * dx * np.exp(-d**2 / (2 * sigma**2))


@pytest.mark.parametrize("backend", BACKENDS)
def test_agrees_with_solve_ivp_on_the_dense_equation(backend):
    """Independent reference: two 1-D fields and a 2-D field coupled through a kernel, a projection and an
    expansion, written as dense matrices and integrated by scipy. The difference is Euler's own error: it
    falls in proportion to dt (a wrong term would leave a floor)."""
    errors = [euler_error(backend, dt) for dt in (0.0005, 0.0001)]
    assert errors[1] < 0.02
    assert 4.0 < errors[0] / errors[1] < 6.0, errors


def euler_error(backend: str, dt: float) -> float:
    n, ny, nx, dx, tau, h, beta = 24, 8, 10, 0.5, 0.05, -2.0, 3.0
    common = {"dx": dx, "tau": tau, "h": h, "beta": beta}
    spec = {"dt": dt, "fields": {
        "a": {"size": n, "kernel": {"A": 2.5, "sigma": 1.5, "w_inhib": 0.3}, **common},
        "b": {"size": n, "periodic": True, "kernel": {"A": 2.0, "sigma": 1.0, "w_inhib": 0.2}, **common},
        "P": {"shape": [ny, nx], "kernel": {"A": 2.0, "sigma": 1.0, "w_inhib": 0.05}, **common},
        "c": {"size": nx, "kernel": {"A": 1.0, "sigma": 1.0}, **common},
    }, "couplings": [
        {"source": "a", "target": "b", "kernel": {"A": 1.2, "sigma": 2.0}},
        {"source": "b", "target": "a", "kernel": {"A": -0.8, "sigma": 1.0}},
        {"source": "P", "target": "c", "kernel": {"A": 0.6, "sigma": 1.0}, "project": {"op": "sum", "over": "y"}},
        {"source": "c", "target": "P", "kernel": {"A": 0.7, "sigma": 1.0}, "expand": "y"},
    ]}
    net = Network.from_dict(spec, backend=backend)
    net.set_stimulus_at("a", "s", 4.0, 4.5, 1.0)
    net.set_stimulus_at("P", "s", (2.0, 1.5), 4.5, 1.0)

    x = np.arange(n) * dx
    xs, ys = np.arange(nx) * dx, np.arange(ny) * dx
    S_a = 4.5 * np.exp(-(x - 4.0) ** 2 / 2.0)
    S_P = 4.5 * np.outer(np.exp(-(ys - 1.5) ** 2 / 2.0), np.exp(-(xs - 2.0) ** 2 / 2.0)).ravel()
    W_aa = dense_conv(n, dx, 2.5, 1.5, False) - 0.3 * dx
    W_bb = dense_conv(n, dx, 2.0, 1.0, True) - 0.2 * dx
    W_ab = dense_conv(n, dx, 1.2, 2.0, True)  # a -> b takes b's boundary, circular
    W_ba = dense_conv(n, dx, -0.8, 1.0, False)
    # 2-D: the kernel's matrix is the Kronecker product of the two axes' (A and dx^2 once)
    W_PP = np.kron(dense_conv(ny, dx, 1.0, 1.0, False), dense_conv(nx, dx, 2.0, 1.0, False)) - 0.05 * dx * dx
    W_cc = dense_conv(nx, dx, 1.0, 1.0, False)
    W_Pc = dense_conv(nx, dx, 0.6, 1.0, False) @ np.kron(np.ones((1, ny)), np.eye(nx))   # sum over y, then smooth
    W_cP = np.kron(dense_conv(ny, dx, 1.0, 1.0, False), dense_conv(nx, dx, 0.7, 1.0, False)) @ np.kron(np.ones((ny, 1)), np.eye(nx))
    sl = np.cumsum([0, n, n, ny * nx, nx])

    def rhs(_t, u):
        f = 1 / (1 + np.exp(-beta * u))
        fa, fb, fP, fc = (f[sl[i]:sl[i + 1]] for i in range(4))
        interaction = np.concatenate([W_aa @ fa + W_ba @ fb + S_a, W_bb @ fb + W_ab @ fa,
                                      W_PP @ fP + W_cP @ fc + S_P, W_cc @ fc + W_Pc @ fP])
        return (-u + h + interaction) / tau

    ref = solve_ivp(rhs, (0, 0.3), np.full(sl[-1], h), rtol=1e-9, atol=1e-9, t_eval=[0.1, 0.3])
    error = 0.0
    for k, seconds in enumerate((0.1, 0.2)):
        net.run(seconds)
        got = np.concatenate([net.u(name).ravel() for name in ("a", "b", "P", "c")])
        error = max(error, float(np.max(np.abs(got - ref.y[:, k]))))
    assert net.u("a").max() > 1.0 and net.u("P").max() > 1.0 and net.u("c").max() > 0.0  # peaks, not rest
    return error


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_plane_peak_is_read_out_along_each_axis(backend):
    """2-D -> 1-D: the max over y of the plane's output puts a peak in the x field at the peak's x."""
    net = Network.from_dict({"dt": 0.005, "fields": {
        "plane": plane(ny=20, nx=30), "x": field(size=30, A=1.0, w_inhib=0.5), "y": field(size=20, A=1.0, w_inhib=0.5),
    }, "couplings": [
        {"source": "plane", "target": "x", "kernel": {"A": 5.0, "sigma": 1.0, "normalize": True}, "project": {"op": "max", "over": "y"}},
        {"source": "plane", "target": "y", "kernel": {"A": 5.0, "sigma": 1.0, "normalize": True}, "project": {"op": "max", "over": "x"}},
    ]}, backend=backend)
    net.set_stimulus_at("plane", "object", (21.0, 6.0), 6.0, 1.5)
    net.run(0.5)
    x, y, _ = net.peak_xy("plane")
    assert abs(x - 21.0) < 0.5 and abs(y - 6.0) < 0.5
    assert net.peak_positions("x") == [21.0]
    assert net.peak_positions("y") == [6.0]
    assert set(net.coupling_inputs("x")) == {"plane->x"}
    net.clear_stimuli("plane")
    net.reset_field("plane")
    net.run(0.5)
    assert net.peak_positions("x") == [] and net.peak_positions("y") == []


@pytest.mark.parametrize("backend", BACKENDS)
def test_two_one_d_cues_meet_in_the_plane_only_where_they_cross(backend):
    """1-D -> 2-D: each expanded cue alone lifts a ridge below threshold; together they make one peak at
    the crossing, which a lone cue cannot."""
    net = Network.from_dict({"dt": 0.005, "fields": {
        "cue_x": field(size=30, A=1.0, w_inhib=0.5), "cue_y": field(size=20, A=1.0, w_inhib=0.5),
        "plane": plane(ny=20, nx=30, kernel={"A": 0.4, "sigma": 1.5, "w_inhib": 0.01}),
    }, "couplings": [
        {"source": "cue_x", "target": "plane", "kernel": {"A": 2.0, "sigma": 0}, "expand": "y"},
        {"source": "cue_y", "target": "plane", "kernel": {"A": 2.0, "sigma": 0}, "expand": "x"},
    ]}, backend=backend)
    net.set_stimulus_at("cue_x", "s", 8.0, 5.0, 1.0)
    net.run(0.5)
    assert net.peak_positions("cue_x") == [8.0]
    assert net.peak_xy("plane") is None, "one cue alone must not make a peak"
    net.set_stimulus_at("cue_y", "s", 14.0, 5.0, 1.0)
    net.run(0.5)
    x, y, _ = net.peak_xy("plane")
    assert abs(x - 8.0) < 0.5 and abs(y - 14.0) < 0.5
    u = net.u("plane")
    ys, xs = np.nonzero(u > 0)
    assert u.shape == (20, 30) and np.all(np.hypot(xs - 8.0, ys - 14.0) < 6), "one localised peak, not a ridge"


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_plane_holds_a_peak_through_a_gap_and_follows_a_moving_input(backend):
    net = Network.from_dict({"dt": 0.005, "fields": {"target": {
        "shape": [40, 80], "dx": 0.01, "tau": 0.05, "h": -3.0, "beta": 4.0,
        "kernel": {"A": 1500.0, "sigma": 0.03, "w_inhib": 50.0}, "input_sigma": 0.03}}}, backend=backend)
    net.set_stimulus_at("target", "s", (0.4, 0.25), 10.0)
    net.step(100)
    x, y, _ = net.peak_xy("target")
    assert abs(x - 0.4) < 0.01 and abs(y - 0.25) < 0.01
    net.clear_stimuli()
    net.step(100)  # a 0.5 s gap in the input: the peak is held
    x, y, _ = net.peak_xy("target")
    assert abs(x - 0.4) < 0.01 and abs(y - 0.25) < 0.01
    for k in range(60):  # the input moves by 0.1 m over 0.6 s
        net.set_stimulus_at("target", "s", (0.4 + 0.1 * (k + 1) / 60, 0.25), 10.0)
        net.step(2)
    net.step(80)
    assert abs(net.peak_xy("target")[0] - 0.5) < 0.01


def test_circular_boundary_wraps_and_linear_does_not():
    def net(boundary):
        n = Network.from_dict({"dt": 0.005, "fields": {"s": field(A=0.0, w_inhib=0.0), "t": field(A=0.0, w_inhib=0.0)},
                               "couplings": [{"source": "s", "target": "t", "boundary": boundary,
                                              "kernel": {"A": 1.0, "sigma": 2.0}}]}, backend="numba")
        n.state_u[n._slice("s")] = -50.0
        n.state_u[n._slice("s").start] = 50.0  # only position 0 of the source is on
        return n.input("t")

    lin, circ = net("linear"), net("circular")
    assert lin[-1] < 1e-9 < circ[-1]
    assert circ[-1] == pytest.approx(circ[1])
    assert lin[0] == pytest.approx(circ[0]) and lin[0] == pytest.approx(1.0, rel=1e-6)  # A dx g(0)


@pytest.mark.parametrize("coupling, key", [
    ({"source": "a", "target": "P", "kernel": {"A": 1}}, "target"),
    ({"source": "a", "target": "b", "kernel": {"A": 1}, "project": {"op": "sum", "over": "y"}}, "project"),
    ({"source": "P", "target": "a", "kernel": {"A": 1}, "project": {"op": "mean", "over": "y"}}, "project.op"),
    ({"source": "P", "target": "a", "kernel": {"A": 1}, "project": {"op": "sum", "over": "z"}}, "project.over"),
    ({"source": "P", "target": "a", "kernel": {"A": 1}, "project": {"op": "sum", "over": "y"}}, "target"),
    ({"source": "a", "target": "P", "kernel": {"A": 1}, "expand": "y"}, "source"),
    ({"source": "c", "target": "P", "kernel": {"A": 1}, "expand": "y", "project": {"op": "sum", "over": "y"}}, "project"),
    ({"source": "a", "target": "b", "kernel": {"A": 1, "w_inhib": 0.5}}, "kernel.w_inhib"),
    ({"source": "a", "target": "b", "kernel": {"A": 1, "sigma": -1}}, "kernel.sigma"),
    ({"source": "a", "target": "b", "kernel": {"A": 1, "cutoff": 0}}, "kernel.cutoff"),
    ({"source": "a", "target": "b", "kernel": {"A": 1, "normalize": "yes"}}, "kernel.normalize"),
    ({"source": "a", "target": "b", "kernel": {"A": 1, "width": 2}}, "kernel.width"),
    ({"source": "a", "target": "b", "kernel": {"A": 1}, "boundary": "reflect"}, "boundary"),
    ({"source": "a", "target": "nowhere", "kernel": {"A": 1}}, "target"),
    ({"source": "a", "target": "b", "kernel": {"A": 1}, "gain": 2}, "gain"),
])
def test_a_bad_continuous_coupling_names_its_key(coupling, key):
    spec = {"dt": 0.005, "fields": {"a": field(), "b": field(), "c": field(size=16), "P": plane()},
            "couplings": [coupling]}
    with pytest.raises(FieldError) as err:
        Network.from_dict(spec)
    assert err.value.key == key


@pytest.mark.parametrize("extra, key", [
    ({"shape": [0, 4]}, "shape"), ({"shape": [3]}, "shape"), ({"shape": [3, 4], "items": ["a"]}, "items"),
    ({"shape": [3, 4], "size": 13}, "size"), ({"shape": [True, 4]}, "shape"),
])
def test_a_bad_plane_names_its_key(extra, key):
    with pytest.raises(FieldError) as err:
        Network.from_dict({"dt": 0.005, "fields": {"P": {"tau": 0.05, **extra}}})
    assert err.value.key == key


def test_reading_a_plane_as_a_line_and_a_line_as_a_plane_is_refused():
    net = Network.from_dict({"dt": 0.005, "fields": {"a": field(), "P": plane()}})
    with pytest.raises(FieldError, match="peak_xy"):
        net.peak_positions("P")
    with pytest.raises(FieldError, match="peak_positions"):
        net.peak_xy("a")
    with pytest.raises(FieldError) as err:
        net.set_stimulus_at("P", "s", 3.0, 1.0)
    assert err.value.key == "position"


def test_continuous_coupling_parameters_are_addressable_by_path():
    net = Network.from_dict(mixed_spec(), backend="numba")
    assert "couplings.a->b.kernel.A" in net.parameter_paths()
    drive(net)
    net.run(0.2)
    before = net.u("b").copy()
    net.set("couplings.a->b.kernel.A", 0.0)
    assert net.get("couplings.a->b.kernel.A") == 0.0
    assert np.array_equal(net.u("b"), before), "changing a parameter keeps the activity"
    with pytest.raises(FieldError):
        net.set("couplings.b->a.kernel.w_inhib", 1.0)


def test_a_plane_is_drawn_as_a_snapshot_not_as_a_history(tmp_path):
    from assistbot.fields import plot_history
    from assistbot.fields.plot import plot_plane

    net = Network.from_dict({"dt": 0.005, "fields": {"P": plane()}})
    rec = net.record(["P"])
    net.step(3)
    assert rec.u["P"].shape == (4, 12, 16)
    with pytest.raises(FieldError, match="plot_plane"):
        plot_history(rec, "P", tmp_path / "p.png")
    png = plot_plane({"P": net.u("P")}, tmp_path / "p.png")
    assert png.read_bytes()[:4] == b"\x89PNG"
