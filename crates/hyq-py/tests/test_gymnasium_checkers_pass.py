"""Gymnasium's env checker passes on HyQ-v0 with no warning when observations are clipped to the
declared bounds (``clip_observations=True``), with and without ``render_mode="rgb_array"``; with
the default raw observations its only possible warning is the observation-bounds one; the id is registered with the core's t_max, in both ``make`` forms,
and the vector entry point is the Rust-batched env."""

from __future__ import annotations

import subprocess
import sys
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import hyq


OUT_OF_SPACE = "The obs returned by the `step()` method is not within the observation space."


@pytest.mark.parametrize("render_mode", [None, "rgb_array"])
@pytest.mark.parametrize("repeat", [1, 2, 3])
def test_check_env_passes_without_warnings(render_mode: str | None, repeat: int) -> None:
    # check_env steps with unseeded samples of the action space, so each run tries other
    # actions: three runs per render mode.
    env = gym.make("HyQ-v0", render_mode=render_mode, clip_observations=True)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    assert [str(w.message) for w in caught] == []
    env.close()


@pytest.mark.parametrize("render_mode", [None, "rgb_array"])
@pytest.mark.parametrize("repeat", [1, 2, 3])
def test_raw_observations_pass_every_other_check(render_mode: str | None, repeat: int) -> None:
    # Unclipped (the default, spec §3), a violent random action can push a joint
    # speed past the table's 12 rad/s: the checker may then say so, and must say nothing else.
    env = gym.make("HyQ-v0", render_mode=render_mode)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    assert [m for w in caught if OUT_OF_SPACE not in (m := str(w.message))] == []
    env.close()


def test_spec_tells_the_core_episode_length() -> None:
    env = gym.make("HyQ-v0")
    assert env.spec is not None
    assert env.spec.max_episode_steps == hyq.MAX_EPISODE_STEPS == 1000
    assert env.unwrapped.max_time_steps == env.spec.max_episode_steps
    assert isinstance(env.unwrapped, gym.Env)
    assert isinstance(env.unwrapped, hyq.HyQEnv)


def test_spaces_are_the_spec_tables() -> None:
    env = hyq.HyQEnv()
    obs = env.observation_space
    assert obs.shape == (39,) and obs.dtype == np.float32
    names = env.observation_names
    assert names[0] == "lf_haa_angle" and names[38] == "trunk_position_z"
    # A few rows of the spec's section 3 table (the joint rows are the URDF's limits, which
    # the table prints to six digits).
    row = {n: i for i, n in enumerate(names)}
    assert obs.low[row["lf_kfe_angle"]] == pytest.approx(-2.44346, abs=1e-5)
    assert obs.high[row["lf_kfe_angle"]] == pytest.approx(-0.349066, abs=1e-5)
    assert obs.high[row["rh_kfe_speed"]] == 12.0
    assert (obs.low[row["trunk_accel_x"]], obs.high[row["trunk_accel_x"]]) == (-50.0, 50.0)
    assert (obs.low[row["trunk_position_z"]], obs.high[row["trunk_position_z"]]) == (0.0, 1.0)
    act = env.action_space
    assert act.shape == (12,) and act.dtype == np.float32
    assert np.all(act.low == -1.0) and np.all(act.high == 1.0)


def test_make_with_module_prefix_imports_the_package() -> None:
    code = (
        "import gymnasium as gym, sys\n"
        "assert 'hyq' not in sys.modules\n"
        "env = gym.make('hyq:HyQ-v0')\n"
        "obs, info = env.reset(seed=0)\n"
        "print(type(env.unwrapped).__name__, obs.shape, env.spec.max_episode_steps)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["HyQEnv", "(39,)", "1000"]


def test_make_vec_returns_the_rust_vector_env() -> None:
    envs = gym.make_vec("HyQ-v0", num_envs=3)
    assert isinstance(envs, hyq.HyQVectorEnv)
    assert envs.metadata["autoreset_mode"] == gym.vector.AutoresetMode.NEXT_STEP
    assert envs.max_time_steps == 1000
    obs, info = envs.reset(seed=0)
    assert obs.shape == (3, 39) and obs.dtype == np.float32
    assert obs in envs.observation_space
    envs.close()


def test_observations_stay_in_the_space_under_random_actions() -> None:
    # Joint speeds leave the table's +-12 rad/s under random targets; clipping keeps every
    # observation in the Box and says when it acted.
    env = hyq.HyQEnv(clip_observations=True)
    env.action_space.seed(0)
    obs, _ = env.reset(seed=0)
    clipped = 0
    for _ in range(300):
        obs, _, terminated, truncated, info = env.step(env.action_space.sample())
        assert obs in env.observation_space
        clipped += info["observation_clipped"]
        if terminated or truncated:
            obs, _ = env.reset()
    assert clipped > 0, "random actions were expected to push some joint speed past 12 rad/s"


def test_observations_are_raw_by_default_and_clipped_on_request() -> None:
    raw = hyq.HyQEnv()
    clipped = hyq.HyQEnv(clip_observations=True)
    raw.action_space.seed(3)
    raw.reset(seed=3)
    clipped.reset(seed=3)
    outside = 0
    for _ in range(50):
        a = raw.action_space.sample()
        o_raw, *_, i_raw = raw.step(a)
        o_clip, *_, i_clip = clipped.step(a)
        low, high = clipped.observation_space.low, clipped.observation_space.high
        np.testing.assert_array_equal(np.clip(o_raw, low, high), o_clip)
        assert i_raw["observation_clipped"] is False
        outside += bool(np.any((o_raw < low) | (o_raw > high)))
        if i_raw["reasons"]:
            break
    assert outside > 0
