"""The core's errors reach Python as exceptions with the core's messages: what the caller
gave wrong (action length, NaN, configuration key or value, goal, render mode) is a
``ValueError``; a call in the wrong state is a ``RuntimeError``; nothing changes on a refusal."""

from __future__ import annotations

import numpy as np
import pytest

import hyq


def test_nan_action_is_a_value_error_and_changes_nothing() -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    action = np.zeros(12, dtype=np.float32)
    action[3] = np.nan
    with pytest.raises(ValueError, match="lh_haa") as err:
        env.step(action)
    assert "3" in str(err.value)
    obs, _, _, _, info = env.step(np.zeros(12))
    assert info["t"] == 1


def test_wrong_length_is_a_value_error_with_the_core_message() -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="12") as err:
        env.step(np.zeros(11))
    assert "11" in str(err.value)
    with pytest.raises(ValueError, match=r"shape \(12, 1\)"):
        env.step(np.zeros((12, 1)))


def test_out_of_range_is_refused_when_configured() -> None:
    env = hyq.HyQEnv(action={"out_of_range": "error"})
    env.reset(seed=0)
    with pytest.raises(ValueError, match="1.5"):
        env.step(np.full(12, 1.5))
    clipping = hyq.HyQEnv()
    clipping.reset(seed=0)
    assert clipping.step(np.full(12, 1.5))[4]["action_clipped"] is True


def test_step_before_reset_is_a_runtime_error() -> None:
    with pytest.raises(RuntimeError, match="before reset"):
        hyq.HyQEnv().step(np.zeros(12))


def test_bad_configuration_names_the_key_and_value() -> None:
    with pytest.raises(ValueError, match="accepted_error"):
        hyq.HyQEnv(accepted_error=-1.0)
    with pytest.raises(ValueError, match="no_such_variable"):
        hyq.HyQEnv(no_such_variable=1)
    with pytest.raises(ValueError, match="goal"):
        hyq.HyQEnv(goal=3)
    with pytest.raises(ValueError, match="solver"):
        hyq.HyQEnv(physics={"rapier": {"solver": 4}})


def test_goal_at_the_start_is_a_value_error() -> None:
    env = hyq.HyQEnv()
    _, info = env.reset(seed=0)
    with pytest.raises(ValueError):
        env.reset(options={"goal": info["initial_position"].tolist()})
    with pytest.raises(ValueError, match="unknown"):
        env.reset(options={"gaol": [1, 2, 3]})


def test_unimplemented_render_modes_are_refused_at_construction() -> None:
    with pytest.raises(ValueError, match="human"):
        hyq.HyQEnv(render_mode="human")
    with pytest.raises(ValueError, match="ansi"):
        hyq.HyQVectorEnv(num_envs=2, render_mode="ansi")
    with pytest.raises(ValueError, match="width"):
        hyq.HyQEnv(render_mode="rgb_array", render_width=5)


def test_bad_seed_is_a_value_error() -> None:
    env = hyq.HyQEnv()
    with pytest.raises(ValueError, match="seed"):
        env.reset(seed=-1)
