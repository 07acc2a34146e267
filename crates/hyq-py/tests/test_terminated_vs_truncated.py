"""Scripted episodes end as the spec rules: reaching the goal, a joint limit and a fall set
``terminated`` (and not ``truncated``); the timeout at t_max sets ``truncated`` (and not
``terminated``), with no penalty; a step after the end is refused."""

from __future__ import annotations

import numpy as np
import pytest

import hyq
from conftest import pose_action


def run(env: hyq.HyQEnv, action: np.ndarray, limit: int = 400):
    """Steps `action` until the episode ends; returns (steps, reward, terminated, truncated,
    info) of the last step."""
    for t in range(1, limit + 1):
        _, reward, terminated, truncated, info = env.step(action)
        assert isinstance(reward, float)
        assert type(terminated) is bool and type(truncated) is bool
        if terminated or truncated:
            return t, reward, terminated, truncated, info
    raise AssertionError(f"no episode end in {limit} steps")


def standing(env: hyq.HyQEnv, seed: int = 0, **options) -> np.ndarray:
    """Resets and returns the absolute-mode action that holds the reset pose."""
    _, info = env.reset(seed=seed, **options)
    return info["joint_targets"].copy()


def test_timeout_truncates_without_terminating() -> None:
    env = hyq.HyQEnv(action={"mode": "absolute"}, max_time_steps=5, fall_penalty=3.0)
    t, _, terminated, truncated, info = run(env, standing(env))
    assert (t, terminated, truncated) == (5, False, True)
    assert info["reasons"] == "timeout" and info["timeout"]
    assert info["fall_penalty"] == 0.0 and info["joint_penalty"] == 0.0


def test_reaching_the_goal_terminates() -> None:
    env = hyq.HyQEnv(
        action={"mode": "absolute"}, accepted_error=0.5, reach_target_bonus_reward=7.0
    )
    _, info = env.reset(seed=0)
    goal = info["initial_position"] + np.array([0.1, 0.0, 0.0])
    action = standing(env, options={"goal": goal.tolist()})
    t, reward, terminated, truncated, info = run(env, action)
    assert (t, terminated, truncated) == (1, True, False)
    assert info["reasons"] == "reached"
    assert info["r_reach"] == 7.0
    assert reward == info["reward"]


def test_a_joint_at_its_limit_terminates_with_the_penalty() -> None:
    env = hyq.HyQEnv(action={"mode": "absolute"}, reach_bounds_penalty=2.0)
    action = standing(env)
    action[2] = env.action_space.low[2]  # lf_kfe to its lower limit
    _, reward, terminated, truncated, info = run(env, action)
    assert (terminated, truncated) == (True, False)
    assert "joint_limit" in info["reasons"]
    assert info["joint_at_limit"] == "lf_kfe"
    assert info["joint_at_limit_side"] == "lower"
    assert info["joint_penalty"] == 2.0
    assert reward < 0.0


def test_a_fall_terminates_with_the_penalty() -> None:
    # Hips splayed, knees half bent: the robot sits down and its trunk touches the ground
    # before any joint reaches a limit (found by trying poses; rapier is deterministic).
    env = hyq.HyQEnv(action={"mode": "absolute"}, fall_penalty=4.0)
    env.reset(seed=0)
    _, reward, terminated, truncated, info = run(env, pose_action(env, (0.9, 0.5, 0.5)))
    assert (terminated, truncated) == (True, False)
    assert info["reasons"] == "fell"
    assert info["fall_penalty"] == 4.0
    assert reward <= -4.0 + 1.0


def test_termination_on_the_last_step_is_terminated_not_truncated() -> None:
    env = hyq.HyQEnv(action={"mode": "absolute"}, accepted_error=0.5, max_time_steps=1)
    _, info = env.reset(seed=0)
    goal = info["initial_position"] + np.array([0.1, 0.0, 0.0])
    action = standing(env, options={"goal": goal.tolist()})
    t, _, terminated, truncated, info = run(env, action)
    assert (t, terminated, truncated) == (1, True, False)
    assert info["reasons"] == "reached+timeout"


def test_a_step_after_the_end_is_refused() -> None:
    env = hyq.HyQEnv(action={"mode": "absolute"}, max_time_steps=2)
    action = standing(env)
    run(env, action)
    with pytest.raises(RuntimeError, match="without reset"):
        env.step(action)
