"""A random agent on the decision-level drinking environment, the way any Gymnasium agent meets it.

Run: .venv/bin/python examples/random_agent.py [--scenario NAME] [--perception vision|oracle] [--seed N]

Each step decides one of the robot's actions (or none) and lasts until that action has ended. A random
choice rarely ends in a drink: the print-out shows what it tried, what the task rewarded and why the
episode ended.
"""

from __future__ import annotations

import argparse

import gymnasium as gym

import assistbot.env  # noqa: F401  (registers assistbot/Drinking-v0)
from assistbot.env import ACTION_NAMES


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", default="fig4-fill-and-hand-over")
    ap.add_argument("--perception", choices=["vision", "oracle"], default="oracle")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--steps", type=int, default=20, help="at most this many decisions")
    args = ap.parse_args()
    env = gym.make("assistbot/Drinking-v0", scenario=args.scenario, perception=args.perception)
    env.action_space.seed(args.seed)
    obs, info = env.reset(seed=args.seed)
    total = 0.0
    for _ in range(args.steps):
        action = int(env.action_space.sample())
        obs, reward, terminated, truncated, info = env.step(action)
        total += reward
        print(f"t={info['t']:7.2f} s  {ACTION_NAMES[action] or '(no decision)':36s} reward {reward:+.3f}")
        if terminated or truncated:
            break
    print(f"return {total:+.3f}; episode {'ended: ' + info['end_reason'] if info['end_reason'] else 'goes on'}")
    env.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
