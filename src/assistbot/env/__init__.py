"""Gymnasium and dm_env interfaces to the drinking task: any agent, learned or written, against the same
person, physics and cameras.

- ``assistbot/Drinking-v0`` (`DrinkingEnv`): the decision level, Discrete over the robot's actions;
- ``assistbot/DrinkingJoints-v0`` (`DrinkingJointsEnv`): the joint level, Box over the arm's joint
  velocity targets and the gripper, 50 Hz;
- `DrinkingDmEnv`: the same core as a `dm_env.Environment`, for dm_control-style users;
- `AgentPolicy`: the shipped agents (the field architecture, the state machine) as policies.

Importing this module registers the environment ids with Gymnasium.
"""

from __future__ import annotations

import gymnasium as gym

from assistbot.env.decision import ACTION_NAMES, DrinkingEnv
from assistbot.env.dm import DrinkingDmEnv
from assistbot.env.joints import JOINT_OBSERVATION_NAMES, DrinkingJointsEnv
from assistbot.env.observation import OBSERVATION_NAMES, encode
from assistbot.env.policies import AgentPolicy

DECISION_ENV_ID = "assistbot/Drinking-v0"
JOINTS_ENV_ID = "assistbot/DrinkingJoints-v0"

if DECISION_ENV_ID not in gym.registry:
    gym.register(DECISION_ENV_ID, entry_point="assistbot.env.decision:DrinkingEnv")
if JOINTS_ENV_ID not in gym.registry:
    gym.register(JOINTS_ENV_ID, entry_point="assistbot.env.joints:DrinkingJointsEnv")

__all__ = ["ACTION_NAMES", "AgentPolicy", "DECISION_ENV_ID", "DrinkingDmEnv", "DrinkingEnv", "DrinkingJointsEnv",
           "JOINTS_ENV_ID", "JOINT_OBSERVATION_NAMES", "OBSERVATION_NAMES", "encode"]
