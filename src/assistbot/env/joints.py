"""`assistbot/DrinkingJoints-v0`: the drinking task at the level of the arm's joints, 50 Hz.

The same world, person, perception and task as `assistbot/Drinking-v0`, without the executor: the agent
moves the arm itself.

- action: ``Box(-1, 1, (8,))``: the seven arm joints' velocity targets as fractions of
  `MAX_JOINT_SPEED` (integrated into the position servos' targets, held within their ranges) and the
  gripper (-1 open, +1 closed, in between part way);
- a step is one control tick (20 ms); the percept is new at every fifth;
- observation: proprioception (joint angles and velocities, the finger angles, whether the fingers feel
  a grasp, the wrist force sensor's force) and the last percept's vector (`assistbot.env.observation`),
  laid out as ``JOINT_OBSERVATION_NAMES``; with ``images=True`` also the head cameras' images, as the
  decision level gives them;
- the head looks at the hand (the robot's own body: its gaze needs nothing else), so what the cameras see
  follows the arm;
- reward and ends as the decision level's; no utterances: the person answers only what she sees.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from assistbot.cognition.percept import Percept, RobotPercept
from assistbot.env.decision import DrinkingEnv
from assistbot.env.observation import OBSERVATION_NAMES, encode
from assistbot.interfaces import ActionRecord, Status
from assistbot.robot.controller import RobotController
from assistbot.robot.gripper import FINGER_JOINTS
from assistbot.robot.ik_model import ARM_JOINTS

#: rad/s of a joint at action 1
MAX_JOINT_SPEED = 1.0
PROPRIOCEPTION_NAMES: tuple[str, ...] = (
    *(f"q.{j}" for j in ARM_JOINTS), *(f"qdot.{j}" for j in ARM_JOINTS),
    *(f"finger.{j}" for j in FINGER_JOINTS), "grasps", "wrist.fx", "wrist.fy", "wrist.fz")
#: bounds of the proprioception slots (rad, rad/s, rad, 0/1, N): beyond any the arm reaches
PROPRIOCEPTION_BOUND = 200.0


class JointActor:
    """The robot's body driven joint by joint (`assistbot.interfaces.Actor`): it carries out no actions."""

    def __init__(self, world) -> None:
        self.world = world
        self.robot = RobotController(world.model, world.data)
        m = world.model
        self._range = m.actuator_ctrlrange[[m.actuator(j).id for j in ARM_JOINTS]].copy()
        self._vadr = np.array([m.jnt_dofadr[m.joint(j).id] for j in ARM_JOINTS])
        self.velocity = np.zeros(len(ARM_JOINTS))
        self.grip = 0.0
        self.action: str | None = None
        self.records: list[ActionRecord] = []

    def command(self, action: np.ndarray) -> None:
        a = np.clip(np.asarray(action, dtype=float), -1.0, 1.0)
        self.velocity = MAX_JOINT_SPEED * a[:len(ARM_JOINTS)]
        self.grip = (a[len(ARM_JOINTS)] + 1.0) / 2.0

    def see(self, percept: Percept) -> None:
        pass

    def begin(self, action: str, t: float, utterance: str = "") -> None:
        raise RuntimeError("the joint-level environment decides no actions")

    def tick(self, t: float, dt: float) -> None:
        r = self.robot
        r.q_cmd = np.clip(r.q_cmd + self.velocity * dt, self._range[:, 0], self._range[:, 1])
        r.hold()   # the servos' targets: the commanded configuration
        self.robot.gripper.open(1.0 - self.grip)
        self.robot.look_at(self.robot.tcp_pose().translation())

    def proprioception(self) -> RobotPercept:
        # the fingers feel that they hold something, not what: naming it is an agent's inference
        return RobotPercept(holding=None, action=None, status=Status.IDLE)

    def ended(self) -> ActionRecord | None:
        return None

    def vector(self) -> np.ndarray:
        d = self.world.data
        g = self.robot.gripper
        v = np.concatenate([self.robot.q(), d.qvel[self._vadr], g.finger_angles(),
                            [float(g.grasps())], g.wrist_force()])
        return np.clip(v, -PROPRIOCEPTION_BOUND, PROPRIOCEPTION_BOUND).astype(np.float32)


class DrinkingJointsEnv(DrinkingEnv):
    """See the module docstring; arguments as `DrinkingEnv`'s (``step_until`` does not apply)."""

    def __init__(self, **kwargs) -> None:
        kwargs.pop("step_until", None)
        images = kwargs.pop("images", False)
        super().__init__(**kwargs)
        self.images = images
        self.action_space = gym.spaces.Box(-1.0, 1.0, shape=(len(ARM_JOINTS) + 1,), dtype=np.float32)
        n = len(PROPRIOCEPTION_NAMES)
        low = np.concatenate([np.full(n, -PROPRIOCEPTION_BOUND), self.vector_space.low])
        high = np.concatenate([np.full(n, PROPRIOCEPTION_BOUND), self.vector_space.high])
        self.vector_space = gym.spaces.Box(low.astype(np.float32), high.astype(np.float32), dtype=np.float32)
        self.observation_space = self.vector_space
        self._spaces_with_images()
        self._actor: JointActor | None = None

    @property
    def actor(self) -> JointActor:
        if self._actor is None:
            raise RuntimeError("call reset() first: there is no arm to move yet")
        return self._actor

    def _install(self) -> None:
        self._actor = JointActor(self.episode.world)
        self.episode.actor = self._actor

    def step(self, action):
        if self.episode is None:
            raise RuntimeError("call reset() before step()")
        if self._over:
            raise RuntimeError("the episode has ended; call reset()")
        self.actor.command(action)
        self._over = self.episode.tick()
        reward = self._reward()
        reason = self.episode.task.end_reason if self._over else None
        terminated = self._over and reason != "time limit"
        truncated = self._over and reason == "time limit"
        return self._observation(), reward, terminated, truncated, self._info()

    def _vector(self) -> np.ndarray:
        return np.concatenate([self.actor.vector(), encode(self.percept, self.scenario.time_limit)])


#: the joint-level observation's slots, in order
JOINT_OBSERVATION_NAMES: tuple[str, ...] = PROPRIOCEPTION_NAMES + OBSERVATION_NAMES
