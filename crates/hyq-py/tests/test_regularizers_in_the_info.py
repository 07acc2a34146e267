"""Gait regularisers from Python (``regularizers={...}``, docs/regularizers.md): off by default
and then absent from the info; on, the info holds ``regularizers.reward`` and each term that is
on (no other), the step's reward is the spec's plus that sum, a vector env holds the same keys
as arrays, and the velocity task refuses the table by name."""

import gymnasium as gym
import numpy as np
import pytest

import hyq

ON = {"action_rate": -0.01, "base_height": -1.0, "collision": -1.0}


def _regularizer_keys(info):
    return [k for k in info if k.startswith("regularizers.")]


def test_off_by_default_the_info_has_no_regularizer_key():
    env = gym.make("HyQ-v0")
    _, info = env.reset(seed=0)
    assert _regularizer_keys(info) == []
    _, _, _, _, info = env.step(np.zeros(12, dtype=np.float32))
    assert _regularizer_keys(info) == []
    env.close()


def test_the_reward_is_the_spec_reward_plus_the_terms_that_are_on():
    assert hyq.REGULARIZER_TERMS == (
        "action_rate", "torques", "joint_acc", "feet_air_time", "foot_slip", "base_height", "collision",
        "goal_heading", "goal_line", "goal_line_approach", "orientation")
    plain = gym.make("HyQ-v0").unwrapped
    reg = gym.make("HyQ-v0", regularizers=ON).unwrapped
    plain.reset(seed=0)
    _, info = reg.reset(seed=0)
    want = ["regularizers.reward"] + [f"regularizers.{t}" for t in hyq.REGULARIZER_TERMS if t in ON]
    assert _regularizer_keys(info) == want
    assert info["regularizers.reward"] == 0.0
    rng = np.random.default_rng(0)
    dt = 0.01
    for _ in range(15):
        action = rng.uniform(-0.2, 0.2, 12).astype(np.float32)
        _, p_reward, *_ = plain.step(action)
        _, reward, _, _, info = reg.step(action)
        assert _regularizer_keys(info) == want
        total = -0.0
        for term in hyq.REGULARIZER_TERMS:
            if term in ON:
                total += ON[term] * info[f"regularizers.{term}"] * dt
        assert info["regularizers.reward"] == total
        assert info["regularizers.action_rate"] > 0.0 and info["regularizers.base_height"] > 0.0
        assert reward == p_reward + total
        assert info["reward"] == reward


def test_a_vector_env_holds_the_same_keys_as_arrays():
    envs = gym.make_vec("HyQ-v0", num_envs=2, regularizers=ON)
    envs.reset(seed=0)
    _, reward, _, _, info = envs.step(np.zeros((2, 12), dtype=np.float32))
    keys = _regularizer_keys(info)
    assert keys == ["regularizers.reward"] + [f"regularizers.{t}" for t in hyq.REGULARIZER_TERMS if t in ON]
    for key in keys:
        assert info[key].shape == (2,) and info[f"_{key}"].all()
    np.testing.assert_array_equal(reward, info["reward"])
    envs.close()


def test_bad_values_and_the_velocity_task_are_refused_by_name():
    with pytest.raises(ValueError, match="regularizers.torques"):
        gym.make("HyQ-v0", regularizers={"torques": float("nan")})
    with pytest.raises(ValueError, match="regularizers"):
        gym.make("HyQ-v0", regularizers={"dof_acc": 1.0})
    with pytest.raises(ValueError, match=r"\[regularizers\]"):
        gym.make("HyQ-Velocity-v0", regularizers={"torques": -1e-5})
