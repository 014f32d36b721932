"""IK speed: microseconds per mink solve with and without the collision limits, plus the target field.

Run: .venv/bin/python benchmarks/ik_speed.py
"""

from __future__ import annotations

import time

import mink
import numpy as np

from assistbot.robot.ik import READY_POSTURE, ArmIK
from assistbot.robot.target_field import TargetField


def bench_ik(collision: bool, n: int = 400) -> float:
    ik = ArmIK()
    rng = np.random.default_rng(0)
    q = READY_POSTURE.copy()
    t = 0.0
    for i in range(n):
        p = np.array([0.25, 0.0, 0.9]) + rng.uniform(-0.1, 0.1, 3)
        target = mink.SE3.from_rotation_and_translation(mink.SO3.identity(), p)
        t0 = time.perf_counter()
        res = ik.solve(q, target, 0.02, collision=collision)
        t += time.perf_counter() - t0
        q = res.q
    return t / n * 1e6


def bench_field(n: int = 200) -> float:
    f = TargetField()
    f.observe((0.2, 0.1))
    f.advance(0.3)
    t0 = time.perf_counter()
    for _ in range(n):
        f.observe((0.2, 0.1))
        f.advance(0.02)
        f.target()
    return (time.perf_counter() - t0) / n * 1e6


if __name__ == "__main__":
    no = bench_ik(False)
    yes = bench_ik(True)
    fld = bench_field()
    print(f"IK solve without collision limits: {no:7.1f} us")
    print(f"IK solve with collision limits:    {yes:7.1f} us")
    print(f"target field per 50 Hz tick:       {fld:7.1f} us")
    print(f"control tick (IK + collision + field): {yes + fld:7.1f} us (goal <= 300 us)")
