"""Environment steps per second of assistbot/Drinking-v0 and assistbot/DrinkingJoints-v0, one env and two
in parallel processes.

Run: .venv/bin/python benchmarks/env_speed.py [--seconds S]

Decision level: steps of one perception tick (0.1 s simulated: 5 control ticks of physics, the person,
the executor, one percept) with no new decision, so that the figure is the world's cost, not an agent's.
Joint level: steps of one control tick (20 ms), the arm held still. Oracle and vision perception. Two envs
run in `gymnasium.vector.AsyncVectorEnv`, one process each; on a 2-core machine two can be at most twice
one. "x real time" is simulated seconds per wall second, per env. The worker processes are spawned, not
forked: a fork of a process that has already stepped an episode can hang in the child.
"""

from __future__ import annotations

import argparse
import sys
import time

import gymnasium as gym
import numpy as np

import assistbot.env  # noqa: F401  (registers the ids)

SCENARIO = "fig4-fill-and-hand-over"
LEVELS = {  # id, extra arguments, simulated seconds per step
    "decision": ("assistbot/Drinking-v0", {"step_until": "perception"}, 0.1),
    "joint": ("assistbot/DrinkingJoints-v0", {}, 0.02),
}


def make(level: str, perception: str):
    env_id, kw, _ = LEVELS[level]
    return lambda: gym.make(env_id, scenario=SCENARIO, perception=perception, **kw)


def still(space, n: int | None = None):
    """No decision (decision level) or no motion with the gripper open (joint level)."""
    if isinstance(space, gym.spaces.Discrete) or (n is not None and isinstance(space, gym.spaces.MultiDiscrete)):
        return np.zeros(n, dtype=np.int64) if n else 0
    a = np.zeros(space.shape, dtype=np.float32)
    a[..., -1] = -1.0
    return a


def rate(step, sim_per_step: float, seconds: float) -> float:
    step()   # warm: compiled kernels, vision's templates
    n, t0 = 0, time.perf_counter()
    while n * sim_per_step < seconds:
        step()
        n += 1
    return n / (time.perf_counter() - t0)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=20.0, help="simulated seconds timed per figure")
    args = ap.parse_args()
    print(f"{SCENARIO}: env steps per second (per env), one env and two (AsyncVectorEnv)")
    print(f"{'level':9} {'perception':10} {'1 env':>8} {'x real':>7} {'2 envs, each':>13} {'x real':>7} {'2 envs, total':>14}")
    for level, (_, _, dt) in LEVELS.items():
        for perception in ("oracle", "vision"):
            env = make(level, perception)()
            env.reset(seed=0)
            a = still(env.action_space)
            one = rate(lambda: env.step(a), dt, args.seconds)
            env.close()
            envs = gym.vector.AsyncVectorEnv([make(level, perception)] * 2, context="spawn")
            envs.reset(seed=[0, 1])
            a2 = still(envs.action_space, 2) if level == "decision" else still(envs.action_space)
            each = rate(lambda: envs.step(a2), dt, args.seconds)
            envs.close()
            print(f"{level:9} {perception:10} {one:8.1f} {one * dt:7.2f} {each:13.1f} {each * dt:7.2f} {2 * each:14.1f}")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
