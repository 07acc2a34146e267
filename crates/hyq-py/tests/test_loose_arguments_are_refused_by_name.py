"""Arguments Python would silently coerce are refused with an error naming the argument:
``clip_observations`` must be a real bool (``"no"`` used to turn clipping on); counts and sizes
must be integers in their range (``num_envs=1.5`` used to make 1 env, a negative one raised an
``OverflowError`` naming nothing, ``num_envs=10**8`` built envs until memory ran out); actions
must be real numbers in a plain array (a complex action lost its imaginary part, a masked
array's mask was ignored); and a dict key of the configuration reaches the core as that one key,
however it is spelt (a key holding ``=`` and ``,`` used to set two keys)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import hyq


@pytest.mark.parametrize("value", ["no", "False", 1, 0, None, 1.0])
def test_clip_observations_must_be_a_bool(value) -> None:
    with pytest.raises(TypeError, match="clip_observations"):
        hyq.HyQEnv(clip_observations=value)
    with pytest.raises(TypeError, match="clip_observations"):
        hyq.HyQVectorEnv(num_envs=1, clip_observations=value)


def test_numpy_bools_are_bools() -> None:
    assert hyq.HyQEnv(clip_observations=np.bool_(True))._core.clip_observations


@pytest.mark.parametrize(
    ("name", "value", "error"),
    [
        ("num_envs", 1.5, TypeError),
        ("num_envs", True, TypeError),
        ("num_envs", "2", TypeError),
        ("num_envs", -1, ValueError),
        ("num_envs", 0, ValueError),
        ("num_envs", 10**8, ValueError),
        ("num_envs", 2**70, ValueError),
        ("threads", -1, ValueError),
        ("threads", 0, ValueError),
        ("threads", 1.5, TypeError),
        ("threads", 10**4, ValueError),
        ("render_width", 1.9, TypeError),
        ("render_width", -1, ValueError),
        ("render_height", 2**40, ValueError),
    ],
)
def test_counts_and_sizes_are_integers_in_their_range(name: str, value, error) -> None:
    kwargs = {"num_envs": 2, name: value}
    with pytest.raises(error, match=name):
        hyq.HyQVectorEnv(**kwargs)
    with pytest.raises(error, match=name):
        gym.make_vec("HyQ-v0", **kwargs)
    if name.startswith("render"):
        with pytest.raises(error, match=name):
            hyq.HyQEnv(**{name: value})


def test_env_indices_are_checked_by_name() -> None:
    envs = hyq.HyQVectorEnv(num_envs=2)
    envs.reset(seed=0)
    for bad in (-1, 2, 2**70):
        for method in (envs.env_info, envs.final_observation, envs.final_info):
            with pytest.raises(IndexError, match="env index"):
                method(bad)
    with pytest.raises(TypeError, match="env index"):
        envs.env_info(1.0)


@pytest.mark.parametrize(
    ("action", "words"),
    [
        (np.full(12, 0.1 + 0.5j), "complex"),
        (np.ma.masked_array(np.zeros(12), mask=[True] + [False] * 11), "masked"),
        (np.array([0.1] * 12, dtype=object), "object"),
        (["0.5"] * 12, "<U3"),
    ],
)
def test_actions_must_be_real_numbers_in_a_plain_array(action, words: str) -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match=words):
        env.step(action)
    assert env.step(np.zeros(12))[4]["t"] == 1, "the refused action changed nothing"
    envs = hyq.HyQVectorEnv(num_envs=2)
    envs.reset(seed=0)
    batch = np.ma.stack([action, action]) if np.ma.isMaskedArray(action) else np.stack(
        [np.asarray(action)] * 2
    )
    with pytest.raises(ValueError, match=words):
        envs.step(batch)


def test_integer_and_boolean_actions_are_numbers() -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    env.step(np.zeros(12, dtype=np.int64))
    env.step([0] * 12)


def test_a_configuration_key_reaches_the_core_as_one_key_however_spelt() -> None:
    # Written unquoted into the generated TOML, this key set solver_iterations = 3 and
    # prediction_distance = 0.5.
    with pytest.raises(ValueError, match="unknown field") as err:
        hyq.HyQEnv(physics={"rapier": {"solver_iterations = 3, prediction_distance": 0.5}})
    assert "solver_iterations = 3, prediction_distance" in str(err.value)
    for key in ['a"b', "a\\b", "a\nb", "café", "a.b", ""]:
        with pytest.raises(ValueError):
            hyq.HyQEnv(goal={key: 1.0})
    # Strings are written as TOML strings, whatever they hold.
    for text in ['ra"ndom', "rand\\om", "x\u007fy", "\U0001f600", "line\nbreak"]:
        with pytest.raises(ValueError, match="goal.mode"):
            hyq.HyQEnv(goal={"mode": text})
