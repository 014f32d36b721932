"""Microseconds per step of the whole cognitive architecture, and simulated seconds per wall second.

Run: .venv/bin/python benchmarks/cognition_step.py [--seconds S] [--backend auto|numpy|numba]

Three figures, on the default configuration (10 fields, 20 couplings):
- "fields only": `Network.step` of all layers (OL, OML, CSGL x3, INI, ASL, IL,
  AML, AEL), the number the goal (<= 50 us) is about;
- "architecture": `Cognition.update` on a 10 Hz percept stream (the Fig. 3
  timeline): field steps + percept-to-stimulus mapping + peak read-out,
  utterances and decisions, per field step;
- simulated seconds per wall second of the architecture.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from assistbot.cognition import Cognition, load_timeline

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=20.0, help="simulated seconds per measurement (default 20)")
    ap.add_argument("--backend", default="auto", choices=["auto", "numpy", "numba"])
    args = ap.parse_args()

    cog = Cognition(backend=args.backend)
    net = cog.net
    dt = net.dt
    n = int(args.seconds / dt)
    net.step(200)  # warm-up (compilation)
    best = float("inf")
    for _ in range(3):
        t0 = time.perf_counter()
        net.step(n)
        best = min(best, (time.perf_counter() - t0) / n)
    sizes = sum(net.field(f).size for f in net.field_names)

    tl = load_timeline(ROOT / "scenarios" / "timelines" / "fig3.yaml")
    percepts = list(tl.percepts())
    arch = float("inf")
    for _ in range(3):
        cog = Cognition(backend=args.backend)
        cog.net.step(10)
        t0 = time.perf_counter()
        for p in percepts:
            cog.update(p)
        wall = time.perf_counter() - t0
        arch = min(arch, wall / (cog.net.steps - 10))
    sim = percepts[-1].t

    print(f"cognition_step: {net!r}")
    print(f"  positions: {sizes}, backend: {net.backend}, dt = {dt * 1000:.1f} ms")
    print(f"  fields only:   {best * 1e6:7.1f} us per step   ({dt / best:8.0f} simulated s per wall s)")
    print(f"  architecture:  {arch * 1e6:7.1f} us per step   ({dt / arch:8.0f} simulated s per wall s; "
          f"fig3 timeline, {sim:.0f} s simulated, percepts at {tl.percept_rate:g} Hz)")
    print(f"  goal: <= 50 us per architecture step: {'met' if arch <= 50e-6 else 'NOT met'}")


if __name__ == "__main__":
    main()
