"""Microseconds per control tick of the human controller (goal: <= 200 us).

Measures (1) the arm alone (minimum-jerk segment + one IK step + servo targets) and (2) the
whole HumanController tick (perception of the robot, behaviour logic, arm) while the arm
reaches, excluding the physics step.  Run: .venv/bin/python benchmarks/human_speed.py
"""

from __future__ import annotations

import time

import numpy as np


def _time_us(fn, n: int) -> float:
    best = []
    for _ in range(3):
        t0 = time.perf_counter()
        for _ in range(n):
            fn()
        best.append((time.perf_counter() - t0) / n * 1e6)
    return min(best)


def main() -> int:
    from assistbot.human.arm import ORIENT, HumanArm
    from assistbot.world import PAPER_ARRANGEMENTS, build_world

    world = build_world(PAPER_ARRANGEMENTS["fig3"], seed=0)
    arm = HumanArm(world)
    arm.move_to((-0.22, -0.12, 0.92), ORIENT["ag"], t=0.0, duration=1e6)
    ts = iter(np.arange(0.0, 1e6, 0.02))
    us_arm = _time_us(lambda: arm.tick(next(ts)), 3000)
    print(f"human arm tick (min-jerk + IK + servo targets): {us_arm:.1f} us")
    try:
        from assistbot.human.controller import HumanController
    except ImportError:
        print("human controller tick: (controller not available)")
        return 0
    world = build_world(PAPER_ARRANGEMENTS["fig3"], seed=0)
    hc = HumanController(world, profile="active", seed=0)
    t = [0.0]

    def tick() -> None:
        hc.tick(t[0])
        t[0] += hc.dt

    for _ in range(100):  # let the policy start a behaviour
        tick()
        world.step(hc.physics_steps)
    us_ctl = _time_us(tick, 1000)
    print(f"human controller tick (perception + behaviour + arm): {us_ctl:.1f} us  (goal <= 200 us)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
