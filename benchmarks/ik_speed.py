"""IK speed and primitive durations.

Prints:
  * microseconds per mink solve with and without the collision limits, and per target-field tick;
  * for each primitive, run once in the world's physics (assistbot.world) from a representative
    arrangement: its outcome, simulated seconds, and the robot's own cost per 50 Hz control tick
    (`Primitive.tick`: target field + IK + gaze + grip sensing; physics and the human excluded),
    median and 95th percentile. Goal: <= 300 us per control tick.

Per-call times are medians: on a shared 2-core machine a mean mostly measures the neighbours.

Run: .venv/bin/python benchmarks/ik_speed.py [--quick]   (--quick: the IK figures only)
"""

from __future__ import annotations

import os
import sys
import time

import mink
import numpy as np

from assistbot.robot.ik import READY_POSTURE, ArmIK
from assistbot.robot.target_field import TargetField


def bench_ik(collision: bool, n: int = 400) -> float:
    ik = ArmIK()
    rng = np.random.default_rng(0)
    q = READY_POSTURE.copy()
    times = []
    for i in range(n):
        # targets near the middle line, so that the human collision limit is active too
        p = np.array([0.05, 0.0, 0.95]) + rng.uniform(-0.1, 0.1, 3)
        target = mink.SE3.from_rotation_and_translation(mink.SO3.identity(), p)
        t0 = time.perf_counter()
        res = ik.solve(q, target, 0.02, collision=collision)
        times.append(time.perf_counter() - t0)
        q = res.q
    return float(np.median(times)) * 1e6


def bench_field(n: int = 200) -> float:
    f = TargetField()
    f.observe((0.2, 0.1))
    f.advance(0.3)
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        f.observe((0.2, 0.1))
        f.advance(0.02)
        f.target()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)) * 1e6


# ----------------------------------------------------------------------------- primitives in the physics
def _cases():
    from assistbot.robot import primitives as P
    from assistbot.robot.sim import body_xy

    def stopper_pull(w, prim):
        sid = w.model.body("stopper").id

        def tick(t):
            on = prim.progress.phase == "hold steady for the stopper" and w.data.eq_active[w.eq_stopper]
            w.data.xfrc_applied[sid, 2] = 15.0 if on else 0.0
        return tick

    def taker(w, prim):
        from assistbot.human.controller import HumanController
        human = HumanController(w, "passive")

        def tick(t):
            if human.current is None and not human.done and prim.progress.phase.startswith("wait for the human"):
                human.start("take_from_robot", object=prim.object)
            human.tick(t)
        return tick

    removed = lambda w: (lambda: not w.data.eq_active[w.eq_stopper])  # noqa: E731
    return [
        # name, bottle, glass, factory(robot, world) -> primitive, target object, each-tick factory
        ("TurnGlass", "HWS:closed", "RWS:inverted", lambda r, w: P.TurnGlass(r), "glass", None),
        ("PlaceInRWS", "HWS:closed", "RWS:empty", lambda r, w: P.PlaceInRWS(r, "glass", spot=(0.25, 0.05)), "glass", None),
        ("Pour", "RWS:open", "RWS:empty", lambda r, w: P.Pour(r, "bottle", locate=lambda n: body_xy(w, n)()), "bottle", None),
        ("HoldBottleForStopper", "RWS:closed", "HWS:empty",
         lambda r, w: P.HoldBottleForStopper(r, stopper_removed=removed(w)), "bottle", stopper_pull),
        ("HandOver (full glass)", "HWS:closed", "RWS:full",
         lambda r, w: P.HandOver(r, "glass", human_holds=lambda: w.human_holding() == "glass"), "glass", taker),
        ("TurnAndHandOver", "HWS:closed", "RWS:inverted",
         lambda r, w: P.TurnAndHandOver(r, "glass", human_holds=lambda: w.human_holding() == "glass"), "glass", taker),
        ("Request", "HWS:closed", "HWS:empty", lambda r, w: P.Request(r, "glass"), "glass", None),
        ("Retract", "HWS:closed", "HWS:empty", lambda r, w: P.Retract(r), "glass", None),
    ]


def bench_primitives() -> list[tuple[str, str, float, float, float, float]]:
    from assistbot.robot.controller import RobotController
    from assistbot.robot.primitives import Status
    from assistbot.robot.sim import CONTROL_DT, body_xy
    from assistbot.world import Arrangement, build_world

    rows = []
    for name, bottle, glass, make, obj, extra in _cases():
        w = build_world(Arrangement.from_options(bottle, glass))
        robot = RobotController(w.model, w.data)
        prim = make(robot, w)
        target = body_xy(w, obj)
        each = extra(w, prim) if extra else None
        ticks = []
        t_wall = time.perf_counter()
        prim.start(target())
        pr = prim.progress
        for _ in range(int(60 / CONTROL_DT)):
            xy = target()
            t0 = time.perf_counter()
            pr = prim.tick(CONTROL_DT, xy)
            ticks.append(time.perf_counter() - t0)
            if each:
                each(w.time)
            w.step(10)
            if pr.status is not Status.RUNNING:
                break
        wall = time.perf_counter() - t_wall
        us = np.array(ticks) * 1e6
        rows.append((name, pr.status.value + (f" ({pr.reason})" if pr.reason else ""), pr.t, wall,
                     float(np.median(us)), float(np.percentile(us, 95))))
    return rows


if __name__ == "__main__":
    no = bench_ik(False)
    yes = bench_ik(True)
    fld = bench_field()
    print(f"IK solve without collision limits: {no:7.1f} us")
    print(f"IK solve with collision limits:    {yes:7.1f} us")
    print(f"target field per 50 Hz tick:       {fld:7.1f} us")
    print(f"control tick (IK + collision + field): {yes + fld:7.1f} us (goal <= 300 us)")
    print(f"(load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores while measuring)")
    if "--quick" not in sys.argv:
        print()
        print(f"{'primitive':24s} {'outcome':12s} {'sim s':>6s} {'wall s':>7s} {'med us':>8s} {'p95 us':>7s}")
        for name, outcome, sim_s, wall, mean, p95 in bench_primitives():
            print(f"{name:24s} {outcome:12s} {sim_s:6.1f} {wall:7.1f} {mean:8.0f} {p95:7.0f}")
        print("med/p95 us: Primitive.tick (target field + IK + gaze + grip sensing) per 20 ms control tick; physics excluded")
