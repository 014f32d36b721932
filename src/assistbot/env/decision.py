"""`assistbot/Drinking-v0`: the drinking task at the level of decisions, as a Gymnasium environment.

The world, the person, perception, the executor and speech are those of `assistbot run`; the environment
takes the agent's place (`assistbot.interfaces.Agent`) and hands the choice to the caller:

- action: ``Discrete(1 + len(AEL_ITEMS))``: 0 lets time pass without a new decision, ``1 + i`` decides
  robot action ``AEL_ITEMS[i]`` (`ACTION_NAMES`), which the executor carries out while the robot says the
  action's own utterance (every AEL pool has one), as the field architecture's decision would;
- a step lasts until the action has ended (``step_until="action"``, capped at ``max_step_seconds``; 0
  lets ``CONTINUE_SECONDS`` pass) or one perception tick, 0.1 s (``step_until="perception"``, for agents
  that watch the world all the time, as the field architecture and the state machine do);
- observation: the percept as a vector (`assistbot.env.observation`), from vision by default; with
  ``perception="oracle"`` it is labelled ground truth, and ``info["ground_truth"]`` says so; with
  ``images=True`` a dict of that vector ("percept") and the two head cameras' images ("left", "right",
  ``image_size`` rows x columns, RGB), drawn at the end of each step;
- reward: +1 when the person drinks; with ``shaping`` (the default), +0.1 the first time the stopper
  comes off, +0.1 the first time the glass is turned upright, +0.2 the first time it is filled; -1 times
  the fraction of the liquid spilled during the step; -0.1 per second of overlap with the person deeper
  than 1 cm;
- terminated when the task ends (the drink, an object that fell, a stall, a repeated failure, a
  diverged physics), truncated at the scenario's time limit; ``info["end_reason"]`` is the task's.

Utterances of the other layers (ASL, IL, AML: what the robot understood, inferred or found wrong) are
not actions; an agent that speaks them says them through `DrinkingEnv.say` (the field architecture's
policy does, `assistbot.env.policies`). A decision taken on an observation begins at the next control
tick, 20 ms later than inside `assistbot run`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from assistbot.cognition.percept import Decision, Percept, Said
from assistbot.env.observation import HIGH, LOW, OBSERVATION_NAMES, encode
from assistbot.interfaces import CONTROL_DT
from assistbot.task import AEL_ITEMS, ROBOT_ACTION_BY_NAME, UTTERANCES

#: action index -> what it decides (None: no new decision)
ACTION_NAMES: tuple[str | None, ...] = (None, *AEL_ITEMS)
#: simulated seconds that action 0 lets pass when a step lasts until an action ends
CONTINUE_SECONDS = 1.0
#: shaped reward for the first time each world event happens (``shaping=True``)
SUBGOAL_REWARDS = {"stopper_removed": 0.1, "glass_turned": 0.1, "glass_filled": 0.2}
DRINK_REWARD = 1.0
SPILL_PENALTY = 1.0   # per fraction of the liquid spilled
TOUCH_PENALTY = 0.1   # per second of overlap with the person deeper than 1 cm
#: end reasons that end the task itself; "time limit" truncates
TRUNCATING = ("time limit",)


class ChosenDecisions:
    """The agent of an episode driven from outside (`assistbot.interfaces.Agent`): it decides what the
    environment was told to decide, at the next control tick, and says what it was told to say."""

    def __init__(self) -> None:
        self.pending: str | None = None
        self.speak: list[Said] = []
        self.history: list[tuple[float, str, str]] = []
        self.last_percept: Percept | None = None

    def _decision(self, t: float) -> Decision:
        said, self.speak = self.speak, []
        if self.pending is None:
            return Decision(t=t, utterances=said)
        action, self.pending = self.pending, None
        u = UTTERANCES["AEL"][action]
        self.history.append((t, "decide", action))
        return Decision(t=t, action=action, target=ROBOT_ACTION_BY_NAME[action].target, new=True,
                        utterances=[Said(t, "AEL", action, u.text, u.tag), *said])

    def update(self, percept: Percept) -> Decision:
        self.last_percept = percept
        return self._decision(percept.t)

    def between(self, t: float) -> Decision:
        return self._decision(t)

    def decisions(self) -> list[tuple[float, str, str]]:
        return list(self.history)

    def trace(self) -> dict[str, Any]:
        return {}


class DrinkingEnv(gym.Env):
    """See the module docstring. ``scenario``: a shipped scenario's name or a scenario file; ``overrides``:
    dotted paths as ``assistbot run --set`` takes them (the partner's profile and habits: ``human.*``)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(self, scenario: str | Path = "fig4-fill-and-hand-over", perception: str = "vision",
                 overrides: dict[str, Any] | None = None, step_until: str = "action", max_step_seconds: float = 60.0,
                 shaping: bool = True, render_mode: str | None = None, images: bool = False,
                 image_size: tuple[int, int] = (120, 160)) -> None:
        from assistbot.episode.builder import PERCEPTIONS
        from assistbot.scenario import load_scenario

        if perception not in PERCEPTIONS:
            raise ValueError(f"perception: one of {', '.join(PERCEPTIONS)}, got {perception!r}")
        if step_until not in ("action", "perception"):
            raise ValueError(f"step_until: 'action' or 'perception', got {step_until!r}")
        if render_mode not in (None, *self.metadata["render_modes"]):
            raise ValueError(f"render_mode: one of {self.metadata['render_modes']} or None, got {render_mode!r}")
        self.scenario = load_scenario(scenario)
        self.perception_mode = perception
        self.overrides = dict(overrides or {})
        self.step_until = step_until
        self.max_step_seconds = float(max_step_seconds)
        self.shaping = shaping
        self.render_mode = render_mode
        self.action_space: gym.spaces.Space = gym.spaces.Discrete(len(ACTION_NAMES))
        #: the vector part of the observation (all of it without images)
        self.vector_space = gym.spaces.Box(LOW, HIGH, shape=(len(OBSERVATION_NAMES),), dtype=np.float32)
        self.observation_space: gym.spaces.Space = self.vector_space
        self.images = images
        self.image_size = (int(image_size[0]), int(image_size[1]))
        self.episode: Any = None
        self.agent = ChosenDecisions()
        self._renderer: Any = None
        self._eyes: Any = None
        self._spaces_with_images()

    # -- gymnasium ------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        from assistbot.episode.builder import build_episode

        self.close_episode()
        # the episode's own seed (the person's habits, vision's noise) comes from the caller's seed when
        # given, else from the scenario, so one seed gives one trajectory
        ep_seed = self.scenario.seed if seed is None else int(seed)
        self.episode = build_episode(self.scenario, perception=self.perception_mode, seed=ep_seed,
                                     overrides=self.overrides)
        self.agent = ChosenDecisions()
        self.episode.agent = self.agent
        self._install()
        self._over = False
        self._rewarded: set[str] = set()
        self._events_seen = 0
        self._spilled = 0.0
        self._touch_seconds = 0.0
        self._advance_to_perception()
        return self._observation(), self._info()

    def step(self, action):
        if self.episode is None:
            raise RuntimeError("call reset() before step()")
        if self._over:
            raise RuntimeError("the episode has ended; call reset()")
        name = ACTION_NAMES[int(action)]
        ep = self.episode
        t0 = ep.world.time
        if name is not None:
            self.agent.pending = name
        n_records = len(ep.actor.records)
        while not self._over:
            self._advance_to_perception()
            if self.step_until == "perception":
                break
            if ep.world.time - t0 >= (CONTINUE_SECONDS if name is None else self.max_step_seconds) - 1e-9:
                break
            if name is not None and len(ep.actor.records) > n_records and ep.actor.records[-1].status.ended:
                break
        reward = self._reward()
        reason = ep.task.end_reason if self._over else None
        terminated = self._over and reason not in TRUNCATING
        truncated = self._over and reason in TRUNCATING
        return self._observation(), reward, terminated, truncated, self._info()

    def render(self):
        if self.render_mode != "rgb_array" or self.episode is None:
            return None
        if self._renderer is None:
            from assistbot.world.render import Renderer

            self._renderer = Renderer(self.episode.world.model, 480, 360)
        return self._renderer.rgb(self.episode.world.data, "scene_cam")

    def close(self) -> None:
        self.close_episode()

    # -- beyond gymnasium -----------------------------------------------------------------------
    def say(self, layer: str, item: str) -> None:
        """Say pool ``item`` of ``layer`` (ASL, IL, AML) at the next control tick, as the fields would."""
        u = UTTERANCES[layer][item]
        self.agent.speak.append(Said(self.episode.world.time, layer, item, u.text, u.tag))

    @property
    def percept(self) -> Percept:
        """The last percept, as the observation encodes it (vision's, or the oracle's in oracle mode)."""
        if self.agent.last_percept is None:
            raise RuntimeError("call reset() first: there is no percept yet")
        return self.agent.last_percept

    def result(self):
        """The episode's summary so far (`assistbot.episode.runner.EpisodeResult`)."""
        return self.episode.result()

    def close_episode(self) -> None:
        """End the current episode's resources: its perception, and the renderers made for its model."""
        for r in (self._renderer, self._eyes):
            if r is not None:
                r.close()
        self._renderer = self._eyes = None
        if self.episode is not None:
            self.episode.perception.close()
            self.episode = None

    # -- the loop -------------------------------------------------------------------------------
    def _install(self) -> None:
        """What a subclass changes in a new episode before its first tick (the joint level: the actor)."""

    def _advance_to_perception(self) -> None:
        """Control ticks up to and including the next one that perceives (or the end)."""
        ep = self.episode
        seen = self.agent.last_percept
        while not self._over:
            self._over = ep.tick()
            if self.agent.last_percept is not seen:
                return

    def _vector(self) -> np.ndarray:
        return encode(self.percept, self.scenario.time_limit)

    def _observation(self):
        v = self._vector()
        if not self.images:
            return v
        if self._eyes is None:
            from assistbot.world.render import Renderer  # headless: EGL or OSMesa, chosen once per process

            rows, cols = self.image_size
            self._eyes = Renderer(self.episode.world.model, cols, rows)
        out = {"percept": v}
        for side in ("left", "right"):
            out[side] = self._eyes.rgb(self.episode.world.data, f"head_cam_{side}")
        return out

    def _spaces_with_images(self) -> None:
        """The observation space as a dict once the vector's space is final (a subclass widens it)."""
        if self.images:
            eye = gym.spaces.Box(0, 255, shape=(*self.image_size, 3), dtype=np.uint8)
            self.observation_space = gym.spaces.Dict({"percept": self.vector_space, "left": eye, "right": eye})

    def _reward(self) -> float:
        task = self.episode.task
        r = 0.0
        for ev in task.events[self._events_seen:]:
            name = ev["event"]
            if name == "drink":
                r += DRINK_REWARD
            elif self.shaping and name in SUBGOAL_REWARDS and name not in self._rewarded:
                self._rewarded.add(name)
                r += SUBGOAL_REWARDS[name]
        self._events_seen = len(task.events)
        if self.shaping:
            outcome = task.outcome()
            spilled = outcome["spilled_fraction"]
            touch = outcome["touched_person"]["seconds_deeper_than_1cm"]
            r -= SPILL_PENALTY * max(0.0, spilled - self._spilled) + TOUCH_PENALTY * max(0.0, touch - self._touch_seconds)
            self._spilled, self._touch_seconds = spilled, touch
        return float(r)

    def _info(self) -> dict[str, Any]:
        ep = self.episode
        body = ep.actor.proprioception()
        return {
            "t": round(ep.world.time, 3),
            "perception": self.perception_mode,
            "ground_truth": self.perception_mode == "oracle",
            "end_reason": ep.task.end_reason if self._over else None,
            "robot_action": body.action,
            "robot_status": body.status.value,
            "control_dt": CONTROL_DT,
        }
