"""`DrinkingDmEnv`: the decision-level environment as a `dm_env.Environment` (dm_control's interface), a
thin layer over the same `DrinkingEnv`.

The observation is the percept vector (``BoundedArray``), the action a ``DiscreteArray`` over
`assistbot.env.decision.ACTION_NAMES`; the discount is 1, and 0 on the step that ends the task (a
truncation at the time limit keeps it 1, as dm_env's convention for a cut-off episode has it).
"""

from __future__ import annotations

from typing import Any

import dm_env
import numpy as np
from dm_env import specs

from assistbot.env.decision import ACTION_NAMES, DrinkingEnv


class DrinkingDmEnv(dm_env.Environment):
    def __init__(self, seed: int | None = None, **kwargs: Any) -> None:
        """``kwargs`` as `DrinkingEnv` takes them (not ``images``: the observation is the vector);
        ``seed`` seeds every episode (None: the scenario's)."""
        if kwargs.get("images"):
            raise ValueError("DrinkingDmEnv: images are not offered here; use DrinkingEnv(images=True)")
        self.env = DrinkingEnv(**kwargs)
        self.seed = seed
        self._needs_reset = True

    def reset(self) -> dm_env.TimeStep:
        obs, _ = self.env.reset(seed=self.seed)
        self._needs_reset = False
        return dm_env.restart(obs)

    def step(self, action) -> dm_env.TimeStep:
        if self._needs_reset:
            return self.reset()
        obs, reward, terminated, truncated, _ = self.env.step(int(action))
        if terminated:
            self._needs_reset = True
            return dm_env.termination(np.float64(reward), obs)
        if truncated:
            self._needs_reset = True
            return dm_env.truncation(np.float64(reward), obs)
        return dm_env.transition(np.float64(reward), obs)

    def observation_spec(self) -> specs.BoundedArray:
        box = self.env.vector_space
        return specs.BoundedArray(box.shape, box.dtype, box.low, box.high, name="percept")

    def action_spec(self) -> specs.DiscreteArray:
        return specs.DiscreteArray(len(ACTION_NAMES), name="action")

    def reward_spec(self) -> specs.Array:
        return specs.Array((), np.float64, name="reward")

    def close(self) -> None:
        self.env.close()
