"""The DFT peers' own workloads through assistbot.fields, checked against a plain numpy reference.

Run: .venv/bin/python benchmarks/fields_peers.py [--repeat N]   (or: make bench-fields-peers)

The conventions the DFT toolkits share (COSIVINA, cedar, dnf-composer), all float64, one thread:

- forward Euler, dt = 1, tau = 10, of  tau du/dt = -u + h + s + sum_k w_k * f(u_src_k),
  h = -5, f(u) = 1 / (1 + exp(-4 u));
- every kernel is amp * g / sum(g), g a Gaussian with sigma = 5 at integer offsets |x| <= ceil(5 sigma)
  = 25 (51 taps, clipped to the field); the lateral kernel adds global * sum(f(u));
- a step uses the interaction from the previous step's outputs, zero on the first step;
- stimuli amp * exp(-(x - pos)^2 / (2 sigma^2)) at x = 1..size.

Workloads:
- A: 12 fields of 201 positions, lateral (amp 15, global -0.2), a static input (amp 7, sigma 5,
  position 20 + 14 i) each, 14 couplings (amp 6, sigma 5): the chain 0 -> 1 -> ... -> 11, 11 -> 0,
  2 -> 7 and 5 -> 10;
- B: 100 fields of 100 positions, the same lateral, a chain of 99 couplings, one input (amp 7, sigma 5,
  position 50) on field 0.

In the library a kernel like this is ``{A: amp, sigma: 5, normalize: true, cutoff: 5}``, global
inhibition is ``w_inhib = -global``, and the boundary is the fields' ``periodic``. The library's Euler
step reads the outputs of the state it starts from, which from the second step on is the peers' rule;
their first step sees no interaction, so the library starts from the state after that step,
u = h + dt/tau s, and runs the other 299.

Goals (issue: the field library as a DFT toolkit): A <= 20 us/step and B >= 10,000 steps/s in both
boundary modes; the peers measured on this machine kind: dnf-composer (C++, AVX2) 40 us / 5,353 steps/s
circular, 169 us / 1,487 linear; COSIVINA's Python port with numba 244 us / 917 circular, 391 us / 584
linear.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ[_var] = "1"  # one thread, as the peers were measured

import argparse  # noqa: E402
import math  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from assistbot.fields import Network  # noqa: E402

DT, TAU, H, BETA, SIGMA = 1.0, 10.0, -5.0, 4.0, 5.0
LATERAL_AMP, GLOBAL, COUPLING_AMP, INPUT_AMP = 15.0, -0.2, 6.0, 7.0
STEPS = 300


def workload_a() -> tuple[int, int, list[tuple[int, int]], dict[int, float]]:
    """(fields, size, couplings source -> target, input position per field)."""
    pairs = [(i, i + 1) for i in range(11)] + [(11, 0), (2, 7), (5, 10)]
    return 12, 201, pairs, {i: 20.0 + 14.0 * i for i in range(12)}


def workload_b() -> tuple[int, int, list[tuple[int, int]], dict[int, float]]:
    return 100, 100, [(i, i + 1) for i in range(99)], {0: 50.0}


def stimulus(size: int, pos: float) -> np.ndarray:
    x = np.arange(1, size + 1)
    return INPUT_AMP * np.exp(-(x - pos) ** 2 / (2 * SIGMA**2))


# ----------------------------------------------------------------------------- plain numpy reference
def reference_kernel(amp: float, size: int, circular: bool) -> np.ndarray:
    r = int(math.ceil(5 * SIGMA))
    r = min(r, (size - 1) // 2 if circular else size - 1)
    g = np.exp(-np.arange(-r, r + 1) ** 2 / (2 * SIGMA**2))
    return amp * g / g.sum()


def reference_convolve(f: np.ndarray, k: np.ndarray, circular: bool) -> np.ndarray:
    r = (k.size - 1) // 2
    padded = np.pad(f, r, mode="wrap" if circular else "constant")
    return np.convolve(padded, k, mode="valid")


class Reference:
    """The peers' model as they write it: one array per field, each step from the previous step's outputs."""

    def __init__(self, workload, circular: bool) -> None:
        n, size, self.pairs, inputs = workload
        self.circular = circular
        self.u = [np.full(size, H) for _ in range(n)]
        self.s = [stimulus(size, inputs[i]) if i in inputs else np.zeros(size) for i in range(n)]
        self.lateral = reference_kernel(LATERAL_AMP, size, circular)
        self.coupling = reference_kernel(COUPLING_AMP, size, circular)
        self.out = [np.zeros(size) for _ in range(n)]  # no output before the first step

    def step(self) -> None:
        interaction = [reference_convolve(o, self.lateral, self.circular) + GLOBAL * o.sum() for o in self.out]
        for src, tgt in self.pairs:
            interaction[tgt] = interaction[tgt] + reference_convolve(self.out[src], self.coupling, self.circular)
        for i, u in enumerate(self.u):
            u += DT / TAU * (-u + H + self.s[i] + interaction[i])
        self.out = [1.0 / (1.0 + np.exp(-BETA * u)) for u in self.u]


# ----------------------------------------------------------------------------- the same through assistbot.fields
def library_network(workload, circular: bool, backend: str = "numba") -> Network:
    n, size, pairs, inputs = workload
    kernel = {"sigma": SIGMA, "normalize": True, "cutoff": 5.0}
    fields = {f"F{i}": {"size": size, "tau": TAU, "h": H, "beta": BETA, "periodic": circular,
                        "kernel": {"A": LATERAL_AMP, "w_inhib": -GLOBAL, **kernel}} for i in range(n)}
    couplings = [{"source": f"F{a}", "target": f"F{b}", "kernel": {"A": COUPLING_AMP, **kernel}} for a, b in pairs]
    net = Network.from_dict({"dt": DT, "fields": fields, "couplings": couplings}, backend=backend)
    # the peers' first step: no interaction yet, so u = h + dt/tau s
    for i in range(n):
        net.u(f"F{i}")[:] = H + DT / TAU * (stimulus(size, inputs[i]) if i in inputs else 0.0)
    for i, pos in inputs.items():
        # a pattern, not set_stimulus_at: a periodic field's Gaussian input wraps, the peers' does not
        net.set_stimulus_pattern(f"F{i}", "input", stimulus(size, pos))
    return net


def agreement(workload, circular: bool) -> tuple[float, float]:
    """(largest |u_library - u_reference| over all fields after 300 steps, largest u)."""
    ref = Reference(workload, circular)
    for _ in range(STEPS):
        ref.step()
    net = library_network(workload, circular)
    net.step(STEPS - 1)
    got = np.concatenate([net.u(f"F{i}") for i in range(workload[0])])
    want = np.concatenate(ref.u)
    return float(np.max(np.abs(got - want))), float(want.max())


def seconds_per_step(step, n: int, repeat: int) -> float:
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        step(n)
        best = min(best, (time.perf_counter() - t0) / n)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5, help="timed runs per figure; the best is reported")
    args = ap.parse_args()
    rows = []
    for label, workload in (("A", workload_a()), ("B", workload_b())):
        for circular in (False, True):
            err, top = agreement(workload, circular)
            net = library_network(workload, circular)
            net.step(10)  # compiled and warm
            batched = seconds_per_step(net.step, 2000, args.repeat)
            per_call = seconds_per_step(lambda k: [net.step() for _ in range(k)], 500, args.repeat)
            ref = Reference(workload, circular)
            reference = seconds_per_step(lambda k: [ref.step() for _ in range(k)], 50, max(1, args.repeat // 2))
            rows.append((label, "circular" if circular else "linear", err, top, batched, per_call, reference))
    print("assistbot.fields on the DFT peers' workloads (float64, one thread, numba path)")
    print(f"{'load':4} {'boundary':8} {'max |diff|':>11} {'max u':>6} {'us/step':>8} {'steps/s':>9} "
          f"{'us/step, step() per call':>25} {'numpy ref us/step':>18}")
    for label, boundary, err, top, batched, per_call, reference in rows:
        print(f"{label:4} {boundary:8} {err:11.1e} {top:6.2f} {batched * 1e6:8.1f} {1 / batched:9,.0f} "
              f"{per_call * 1e6:25.1f} {reference * 1e6:18.1f}")
    worst = max(r[2] for r in rows)
    a_worst = max(r[4] for r in rows if r[0] == "A") * 1e6
    b_worst = min(1 / r[4] for r in rows if r[0] == "B")
    print(f"agreement with the reference after {STEPS} steps: {worst:.1e} (goal <= 1e-12): "
          f"{'met' if worst <= 1e-12 else 'NOT met'}")
    print(f"A: {a_worst:.1f} us/step at worst (goal <= 20): {'met' if a_worst <= 20 else 'NOT met'}; "
          f"B: {b_worst:,.0f} steps/s at worst (goal >= 10,000): {'met' if b_worst >= 10_000 else 'NOT met'}")
    print("peers on this machine kind: dnf-composer 40 us / 5,353 steps/s circular, 169 us / 1,487 linear; "
          "COSIVINA (numba) 244 us / 917 circular, 391 us / 584 linear")


if __name__ == "__main__":
    main()
