"""The seed's field architecture as a policy of the Gymnasium environment: it drinks as in `assistbot run`.

Run: .venv/bin/python examples/dnf_agent_via_gym.py [--scenario NAME] [--perception vision|oracle]

The environment steps one perception tick (0.1 s) at a time; at each, the policy hands the percept to the
architecture, turns a new AEL decision into the action and says its other layers' utterances through the
environment. Exit status 0 when the person drank.
"""

from __future__ import annotations

import argparse

from assistbot.env import AgentPolicy, DrinkingEnv


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", default="fig4-fill-and-hand-over")
    ap.add_argument("--perception", choices=["vision", "oracle"], default="vision")
    ap.add_argument("--agent", choices=["dnf", "fsm"], default="dnf")
    args = ap.parse_args()
    env = DrinkingEnv(scenario=args.scenario, perception=args.perception, step_until="perception")
    env.reset()
    policy = AgentPolicy.for_env(env, args.agent)
    done, info = False, {}
    while not done:
        _, _, terminated, truncated, info = env.step(policy(env))
        done = terminated or truncated
    result = env.result()
    print(f"{args.scenario} ({args.perception}, {args.agent} through the env): {info['end_reason']} at "
          f"t = {info['t']:.1f} s; decisions: {', '.join(a for _, a in result.decisions)}")
    env.close()
    return 0 if info["end_reason"] == "drink" else 1


if __name__ == "__main__":
    raise SystemExit(main())
