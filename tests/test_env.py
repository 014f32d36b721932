"""The Gymnasium and dm_env interfaces: they conform, they are deterministic for a seed, and a written or
the field architecture's policy drinks through them as in `assistbot run`."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from absl.testing import absltest
from dm_env import test_utils

import assistbot.env as E
from assistbot.scenario import shipped_scenarios

FAST = {"scenario": "fig4-fill-and-hand-over", "perception": "oracle"}
SCRIPT = ("Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over", "Suggest-drink")


def test_the_decision_level_env_passes_gymnasiums_checker():
    from gymnasium.utils.env_checker import check_env

    env = gym.make(E.DECISION_ENV_ID, max_step_seconds=2.0, render_mode="rgb_array", **FAST)
    check_env(env.unwrapped)
    env.close()


def test_a_written_policy_drinks_through_the_env_and_the_reward_says_so():
    env = gym.make(E.DECISION_ENV_ID, **FAST)
    obs, info = env.reset(seed=3)
    assert info["ground_truth"] is True, "an oracle's observation must be flagged"
    assert obs[E.OBSERVATION_NAMES.index("glass.state=empty")] == 1.0
    total, steps, done = 0.0, [], False
    for k, name in enumerate(SCRIPT):
        obs, r, term, trunc, info = env.step(E.ACTION_NAMES.index(name))
        total += r
        steps.append((name, info["t"]))
        done = term or trunc
        # handed the full glass, the active person may drink before the robot has finished suggesting it
        assert not done or (k == len(SCRIPT) - 1 and term and info["end_reason"] == "drink")
    while not done:
        obs, r, term, trunc, info = env.step(0)
        total += r
        done = term or trunc
    assert term and not trunc and info["end_reason"] == "drink"
    result = env.unwrapped.result()
    assert [a for _, a in result.decisions] == list(SCRIPT)
    assert [(a["action"], a["status"]) for a in result.actions][:-1] == [(a, "succeeded") for a in SCRIPT[:-1]]
    assert result.actions[-1]["action"] == SCRIPT[-1] and result.actions[-1]["status"] in ("succeeded", "running")
    # +1 for the drink, +0.2 for filling; the touch and spill penalties are what the task measured
    touched = result.touched_person["seconds_deeper_than_1cm"]
    assert total == pytest.approx(1.2 - 0.1 * touched - result.spilled_fraction, abs=1e-6)
    # each step lasted until its action ended: the next one began after the last one's end
    ends = [a["end"] for a in result.actions]
    assert all(end is None or t >= end for (_, t), end in zip(steps, ends))
    env.close()


@pytest.mark.parametrize("env_id, kw", [(E.DECISION_ENV_ID, {"step_until": "perception"}), (E.JOINTS_ENV_ID, {})],
                         ids=["decision", "joint"])
def test_the_same_seed_gives_the_same_trajectory(env_id, kw):
    def run(seed):
        env = gym.make(env_id, **kw, **FAST)
        obs, _ = env.reset(seed=seed)
        env.action_space.seed(0)
        trace = [obs]
        for _ in range(40):
            obs, r, term, trunc, info = env.step(env.action_space.sample())
            trace.append(np.append(obs, r))
        env.close()
        return np.concatenate(trace)

    a, b = run(7), run(7)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, run(8)), "another seed, another episode"


def test_vision_observations_are_not_flagged_as_truth():
    env = E.DrinkingEnv(scenario="fig4-fill-and-hand-over", step_until="perception")
    _, info = env.reset(seed=0)
    assert info["perception"] == "vision" and info["ground_truth"] is False
    env.close()


@pytest.mark.parametrize("agent", ["dnf", "fsm"])
def test_the_shipped_agents_drink_through_the_env_as_policies(agent):
    env = E.DrinkingEnv(step_until="perception", **FAST)
    env.reset(seed=0)
    policy = E.AgentPolicy.for_env(env, agent)
    done = False
    while not done:
        _, _, term, trunc, info = env.step(policy(env))
        done = term or trunc
    assert info["end_reason"] == "drink"
    decided = [a for _, a in env.result().decisions]
    # the robot fills and hands over; at the end it suggests the drink, or (the fields, whose decisions
    # come 20 ms later through the env) waits for the person who is about to drink on her own
    assert decided[:2] == list(SCRIPT[:2]) and decided[2:] in (["Suggest-drink"], ["Wait"]), decided
    env.close()


@pytest.mark.slow
@pytest.mark.parametrize("path", shipped_scenarios(), ids=lambda p: p.stem)
def test_the_field_architecture_drinks_through_the_env_with_vision(path):
    env = E.DrinkingEnv(scenario=str(path), step_until="perception")
    env.reset()
    policy = E.AgentPolicy.for_env(env, "dnf")
    done = False
    while not done:
        _, _, term, trunc, info = env.step(policy(env))
        done = term or trunc
    assert info["end_reason"] == "drink", path.stem
    env.close()


class DmEnvConformance(test_utils.EnvironmentTestMixin, absltest.TestCase):
    """dm_env's own conformance tests, on the adapter."""

    def make_object_under_test(self):
        return E.DrinkingDmEnv(seed=0, step_until="perception", **FAST)


def test_the_joint_level_env_passes_gymnasiums_checker():
    from gymnasium.utils.env_checker import check_env

    env = gym.make(E.JOINTS_ENV_ID, render_mode="rgb_array", **FAST)
    check_env(env.unwrapped)
    env.close()


def test_joint_velocity_targets_move_the_arm_and_the_gripper_closes():
    env = E.DrinkingJointsEnv(**FAST)
    obs, _ = env.reset(seed=0)
    names = E.JOINT_OBSERVATION_NAMES
    q0 = obs[names.index("q.robot_j1")]
    action = np.zeros(env.action_space.shape, dtype=np.float32)
    action[0], action[-1] = 0.5, 1.0   # the first joint at half speed; the gripper closed
    for _ in range(50):                # 1 s at 50 Hz
        obs, _, term, trunc, info = env.step(action)
    assert info["t"] == pytest.approx(1.02, abs=1e-6)
    from assistbot.env.joints import MAX_JOINT_SPEED

    assert obs[names.index("q.robot_j1")] - q0 == pytest.approx(0.5 * MAX_JOINT_SPEED * 1.0, abs=0.05)
    assert obs[names.index("finger.robot_f1_prox")] > 1.0, "the fingers closed"
    assert obs[names.index("grasps")] == 0.0, "closed on nothing: no grasp felt"
    assert obs[names.index("bottle.seen")] == 1.0, "the percept rides along"
    env.close()


def test_two_envs_run_in_parallel_processes():
    envs = gym.vector.AsyncVectorEnv([lambda: gym.make(E.DECISION_ENV_ID, step_until="perception", **FAST)] * 2,
                                     context="spawn")
    obs, _ = envs.reset(seed=[0, 1])
    assert obs.shape == (2, len(E.OBSERVATION_NAMES))
    obs, reward, term, trunc, info = envs.step(np.zeros(2, dtype=np.int64))
    assert obs.shape == (2, len(E.OBSERVATION_NAMES)) and not term.any()
    envs.close()


@pytest.mark.parametrize("make", [E.DrinkingEnv, E.DrinkingJointsEnv], ids=["decision", "joint"])
def test_the_head_cameras_images_come_with_the_percept_when_asked(make):
    env = make(images=True, image_size=(60, 80), **FAST)
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    assert obs["left"].shape == (60, 80, 3) and obs["left"].dtype == np.uint8
    assert not np.array_equal(obs["left"], obs["right"]), "two eyes, two views"
    assert obs["left"].std() > 10, "an image of the scene, not a blank"
    env.close()


def test_render_gives_the_scene_cameras_image():
    env = gym.make(E.DECISION_ENV_ID, render_mode="rgb_array", **FAST)
    env.reset(seed=0)
    frame = env.render()
    assert frame.shape == (360, 480, 3) and frame.dtype == np.uint8 and frame.std() > 10
    env.close()
