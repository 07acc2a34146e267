"""Gymnasium's env checker passes on HyQ-v0 with no warning on the default env and on every
combination of the options that shape the spaces and the output (observations raw or clipped,
render mode none or rgb_array, normalized or delta actions; absolute actions draw only the
checker's advice to use a normalized action space); the id is registered with the core's t_max,
in both ``make`` forms, and the vector entry point is the Rust-batched env."""

from __future__ import annotations

import subprocess
import sys
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import hyq

#: The one warning absolute actions (radians within each joint's range) draw, by design.
NORMALIZE_ADVICE = "For Box action spaces, we recommend using a symmetric and normalized space"


def checker_warnings(**kwargs) -> list[str]:
    env = gym.make("HyQ-v0", **kwargs)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    env.close()
    return [str(w.message) for w in caught]


@pytest.mark.parametrize("repeat", [1, 2, 3])
def test_check_env_is_silent_on_the_default_env(repeat: int) -> None:
    # check_env steps with unseeded samples of the action space, so each run tries other
    # actions: three runs.
    assert checker_warnings() == []


@pytest.mark.parametrize("clip", [False, True])
@pytest.mark.parametrize("render_mode", [None, "rgb_array"])
@pytest.mark.parametrize("mode", ["normalized", "delta", "absolute", "offset"])
def test_check_env_is_silent_on_every_option_combination(
    clip: bool, render_mode: str | None, mode: str
) -> None:
    caught = checker_warnings(
        clip_observations=clip, render_mode=render_mode, action={"mode": mode}
    )
    if mode == "absolute":
        caught = [m for m in caught if NORMALIZE_ADVICE not in m]
    assert caught == []


def test_spec_tells_the_core_episode_length() -> None:
    env = gym.make("HyQ-v0")
    assert env.spec is not None
    assert env.spec.max_episode_steps == hyq.MAX_EPISODE_STEPS == 1000
    assert env.unwrapped.max_time_steps == env.spec.max_episode_steps
    assert isinstance(env.unwrapped, gym.Env)
    assert isinstance(env.unwrapped, hyq.HyQEnv)


def test_spaces_follow_the_spec_tables() -> None:
    env = hyq.HyQEnv()
    obs = env.observation_space
    assert obs.shape == (39,) and obs.dtype == np.float32
    names = env.observation_names
    assert names[0] == "lf_haa_angle" and names[38] == "trunk_position_z"
    row = {n: i for i, n in enumerate(names)}
    # Raw observations: the table's bounds on the invariant rows only (see
    # test_observation_space_is_honest); clipped: the table.
    assert (obs.low[row["trunk_rotation_w"]], obs.high[row["trunk_rotation_w"]]) == (-1.0, 1.0)
    assert obs.high[row["rh_kfe_speed"]] == np.finfo(np.float32).max
    clipped = hyq.HyQEnv(clip_observations=True).observation_space
    assert clipped.low[row["lf_kfe_angle"]] == pytest.approx(-2.44346, abs=1e-5)
    assert clipped.high[row["lf_kfe_angle"]] == pytest.approx(-0.349066, abs=1e-5)
    assert clipped.high[row["rh_kfe_speed"]] == 12.0
    assert (clipped.low[row["trunk_accel_x"]], clipped.high[row["trunk_accel_x"]]) == (-50.0, 50.0)
    z = row["trunk_position_z"]
    assert (clipped.low[z], clipped.high[z]) == (0.0, 1.0)
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
