"""Microseconds per control tick of the human controller (goal: <= 200 us).

Measures (1) the arm alone (minimum-jerk segment + one IK step + servo targets) and (2) the
whole HumanController tick (perception of the robot, behaviour logic, arm) while the arm
reaches (mean and 99th percentile of single ticks), and (3) an idle passive partner's tick;
all excluding the physics step, in CPU time of the thread (see _clock).  Run: .venv/bin/python benchmarks/human_speed.py
"""

from __future__ import annotations

import time

import numpy as np

#: CPU time of this thread: on a shared machine the time the process waits for a core is not
#: the controller's cost (wall-clock figures swing 3x with the load of other jobs)
_clock = time.thread_time


def _time_us(fn, n: int) -> float:
    best = []
    for _ in range(3):
        t0 = _clock()
        for _ in range(n):
            fn()
        best.append((_clock() - t0) / n * 1e6)
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
    def episode(profile: str, seconds: float) -> tuple[np.ndarray, np.ndarray]:
        """Tick the controller with physics in between (untimed); per-tick times (us) and 'arm moving' flags."""
        world = build_world(PAPER_ARRANGEMENTS["fig3"], seed=0)
        hc = HumanController(world, profile=profile, seed=0)
        us, moving = [], []
        for _ in range(int(round(seconds / hc.dt))):
            t = world.time
            t0 = _clock()
            hc.tick(t)
            us.append((_clock() - t0) * 1e6)
            moving.append(hc.arm.segment is not None and not hc.arm.segment.done(t))
            world.step(hc.physics_steps)
        return np.array(us), np.array(moving)

    # the active partner of Fig. 3 grasps the closed bottle and holds it out (12 s); best of 3 runs
    # (the machine is shared: the best run is the least disturbed one)
    runs = [episode("active", 12.0) for _ in range(3)]
    us, moving = min(runs, key=lambda r: r[0].mean())
    print(f"human controller tick, active partner over 12 s (perception + behaviour + arm): {us.mean():.1f} us mean, "
          f"{np.median(us):.1f} us median, {us[moving].mean():.1f} us mean while the arm moves, "
          f"{np.percentile(us, 99):.1f} us p99  (goal <= 200 us)")
    us = min((episode("passive", 4.0)[0] for _ in range(3)), key=lambda u: u.mean())
    print(f"human controller tick, idle passive partner: {us.mean():.1f} us mean")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
