"""Microseconds per network step of assistbot.fields, next to a naive numpy implementation.

Run: .venv/bin/python benchmarks/fields_step.py [--steps N]

Networks:
- "seed-shaped": 12 fields of 100-200 positions wired like the seed's
  architecture (OL, OML, CSGL past/present/future -> ASL -> IL -> AML -> AEL),
  with items every 10 positions and sparse coupling tables;
- "100x100": 100 fields of 100 positions in a chain of couplings.

"naive numpy" is the textbook implementation measured in the same run: one
object per field with a dense N x N kernel matrix, a Python loop over fields
and couplings, coupling input rendered per coupling.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from assistbot.fields import Network
from assistbot.fields.spec import NetworkSpec


def seed_shaped_spec() -> dict:
    rng = np.random.default_rng(1)
    layers = {
        "OL": 160, "OML": 200, "CSGL_past": 100, "CSGL_present": 100, "CSGL_future": 100,
        "ASL": 200, "IL": 120, "AML": 100, "AEL": 200, "OL_hand": 100, "OML_zone": 120, "speech": 100,
    }
    fields = {}
    for name, size in layers.items():
        fields[name] = {
            "items": [f"{name}_{i}" for i in range(size // 10)], "spacing": 10, "tau": 0.05, "h": -3.0,
            "beta": 4.0, "kernel": {"A": 3.0, "sigma": 2.0, "w_inhib": 0.05}, "input_sigma": 2.0,
        }
    wiring = [("OL", "ASL"), ("OML", "ASL"), ("CSGL_present", "ASL"), ("ASL", "IL"), ("CSGL_past", "IL"),
              ("IL", "AML"), ("CSGL_present", "AML"), ("IL", "AEL"), ("OML", "AEL"), ("AML", "AEL"),
              ("CSGL_present", "AEL"), ("CSGL_future", "AEL"), ("OL_hand", "OL"), ("OML_zone", "OML"),
              ("CSGL_past", "CSGL_present"), ("CSGL_present", "CSGL_future"), ("AEL", "speech"), ("ASL", "speech")]
    couplings = []
    for src, tgt in wiring:
        s_items, t_items = fields[src]["items"], fields[tgt]["items"]
        table = {}
        for t in t_items:
            picks = rng.choice(len(s_items), size=3, replace=False)
            table[t] = {s_items[j]: float(rng.uniform(0.5, 2.0)) for j in picks}
        couplings.append({"source": src, "target": tgt, "k": 1.0, "table": table})
    return {"dt": 0.005, "fields": fields, "couplings": couplings}


def grid_spec(n_fields: int = 100, size: int = 100) -> dict:
    fields = {f"F{i}": {"items": [f"i{j}" for j in range(size // 10)], "tau": 0.05, "h": -3.0,
                        "kernel": {"A": 3.0, "sigma": 2.0, "w_inhib": 0.05}, "input_sigma": 2.0} for i in range(n_fields)}
    couplings = [{"source": f"F{i}", "target": f"F{i + 1}", "k": 1.0,
                  "table": {f"i{j}": {f"i{j}": 1.5} for j in range(size // 10)}} for i in range(n_fields - 1)]
    return {"dt": 0.005, "fields": fields, "couplings": couplings}


class NaiveNetwork:
    """Textbook numpy: per-field dense kernels and a Python loop over fields and couplings."""

    def __init__(self, spec: NetworkSpec) -> None:
        self.spec = spec
        self.u, self.W, self.G, self.idx = {}, {}, {}, {}
        for name, f in spec.fields.items():
            x = f.positions
            d = x[:, None] - x[None, :]
            self.W[name] = (f.kernel.A * np.exp(-d**2 / (2 * f.kernel.sigma**2)) - f.kernel.w_inhib) * f.dx
            self.G[name] = np.exp(-(x[:, None] - f.item_indices[None, :] * f.dx) ** 2 / (2 * f.input_sigma**2))
            self.idx[name] = f.item_indices
            self.u[name] = np.full(f.size, f.h)
        self.stim = {name: np.zeros(f.size) for name, f in spec.fields.items()}
        self.A = [(c.source, c.target, c.k * c.matrix(spec.fields)) for c in spec.couplings]

    def step(self) -> None:
        dt = self.spec.dt
        out = {n: 1.0 / (1.0 + np.exp(-f.beta * (self.u[n] - f.u0))) for n, f in self.spec.fields.items()}
        S = {n: self.stim[n].copy() for n in self.spec.fields}
        for src, tgt, a in self.A:
            S[tgt] += self.G[tgt] @ (a @ out[src][self.idx[src]])
        for n, f in self.spec.fields.items():
            self.u[n] += dt / f.tau * (-self.u[n] + S[n] + self.W[n] @ out[n] + f.h)


def per_step_us(step, steps: int, repeats: int = 5) -> float:
    step()
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(steps):
            step()
        best = min(best, (time.perf_counter() - t0) / steps)
    return best * 1e6


def drive(net: Network) -> None:
    # a few active items so that peaks (and the compiled path's sparse work) are realistic
    for name in list(net.spec.fields)[:5]:
        net.set_stimulus(name, net.spec.fields[name].items[1], 5.0)
    net.run(0.5)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=2000)
    args = ap.parse_args()

    print(f"{'network':<38}{'path':<14}{'us/step':>10}{'steps/s':>12}")
    for label, spec_d in (("seed-shaped: 12 fields, 100-200 pos", seed_shaped_spec()), ("100 fields x 100 positions", grid_spec())):
        spec = NetworkSpec.from_dict(spec_d)
        naive = NaiveNetwork(spec)
        steps = args.steps if "seed" in label else max(200, args.steps // 5)
        results = [("naive numpy", per_step_us(naive.step, max(100, steps // 4)))]
        for backend in ("numpy", "numba"):
            net = Network.from_dict(spec_d, backend=backend)
            drive(net)
            results.append((f"{backend} batch", per_step_us(lambda: net.step(1), steps)))
            results.append((f"{backend} x100", per_step_us(lambda: net.step(100), max(2, steps // 100)) / 100))
        for path, us in results:
            print(f"{label:<38}{path:<14}{us:>10.1f}{1e6 / us:>12.0f}")
    print("goal: <= 20 us/step for the seed-shaped network (numba batch)")


if __name__ == "__main__":
    main()
