"""The ``info`` of every step and reset holds every key of ``hyq.INFO_SCHEMA`` (the README's
env card states it) and nothing else, each with one type and shape, whatever happened:
episodes ending by every reason (reached, joint_limit, fell, timeout, diverged), resets and
autoresets. So Gymnasium's vector info aggregation works on it: the single env, the project's
vector env, Gymnasium's ``SyncVectorEnv`` and ``AsyncVectorEnv``, and ``DictInfoToList`` over
each (RLlib's stack; a ``joint_at_limit`` that was None on ordinary steps and a dict on a
joint-limit step crashed it at the first episode end)."""

from __future__ import annotations

import numbers
import re
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AsyncVectorEnv, SyncVectorEnv
from gymnasium.wrappers.vector import DictInfoToList

import hyq
from conftest import REPO

#: One configuration per episode end, each reached within a few steps; the joint-limit env is
#: driven to its lower limits (action -1), the others hold still (action 0).
ENDINGS = {
    "reached": dict(goal={"mode": "fixed", "position": [0.5, 0.0, 0.6]}, accepted_error=2.0),
    "joint_limit": dict(),
    "fell": dict(physics={"contact_distance": 1.0}),
    "timeout": dict(max_time_steps=3),
    "diverged": dict(physics={"dt": 0.1}),
}
REASONS = list(ENDINGS)
STEPS = 25


def actions_for(reasons: list[str]) -> np.ndarray:
    return np.array(
        [np.full(12, -1.0 if r == "joint_limit" else 0.0, dtype=np.float32) for r in reasons]
    )


def check_value(key: str, value) -> None:
    """`value` has the type and shape `INFO_SCHEMA` gives `key` (NumPy scalars count as the
    Python type, as a vector info's element reads)."""
    kind = hyq.INFO_SCHEMA[key]
    if kind == "int":
        assert isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_)), (
            key,
            value,
        )
    elif kind == "float":
        assert isinstance(value, (float, np.floating)), (key, value)
        assert np.isfinite(value), (key, value)
    elif kind == "bool":
        assert isinstance(value, (bool, np.bool_)), (key, value)
    elif kind == "str":
        assert isinstance(value, str), (key, value)
    else:
        shape = tuple(int(n) for n in re.findall(r"\d+", kind.split("(")[1]))
        assert isinstance(value, np.ndarray) and value.dtype == np.float64, (key, value)
        assert value.shape == shape and np.all(np.isfinite(value)), (key, value)


def check_single(info: dict) -> None:
    assert set(info) == set(hyq.INFO_SCHEMA), set(info) ^ set(hyq.INFO_SCHEMA)
    for key, value in info.items():
        check_value(key, value)


def check_vector(info: dict, n: int, reference: dict | None) -> dict:
    """A vector info: every schema key as an array over the envs, with its all-true mask, of
    one dtype and shape from step to step. Returns (dtype, shape) per key."""
    keys = {k for k in info if not k.startswith("_")} - {"final_obs", "final_info"}
    assert keys == set(hyq.INFO_SCHEMA), keys ^ set(hyq.INFO_SCHEMA)
    layout = {}
    for key in keys:
        array = info[key]
        assert isinstance(array, np.ndarray) and array.shape[0] == n, key
        assert np.all(info[f"_{key}"]), key
        for value in array:
            check_value(key, value)
        layout[key] = (array.dtype, array.shape)
    if reference is not None:
        assert layout == reference
    return layout


def test_the_readme_states_the_schema_once() -> None:
    text = (REPO / "README.md").read_text()
    section = text.split("**Info**")[1].split("\n\n**")[0]
    rows = re.findall(r"^\| `([^`|]+)`((?:, `[^`|]+`)*) \| ([^|]+) \|", section, re.M)
    documented = {}
    for first, more, kind in rows:
        for key in [first, *re.findall(r"`([^`]+)`", more)]:
            documented[key] = kind.strip()
    # The keys of every info, then those `[randomize]` adds (HyQ's body and joint counts).
    assert documented == {**hyq.INFO_SCHEMA, **hyq.randomize_info_schema()}


@pytest.mark.parametrize("reason", REASONS)
def test_single_env_info_keeps_its_shape_through_every_ending(reason: str) -> None:
    env = hyq.HyQEnv(**ENDINGS[reason])
    _, info = env.reset(seed=0)
    check_single(info)
    action = actions_for([reason])[0]
    seen = set()
    for _ in range(STEPS):
        _, _, terminated, truncated, info = env.step(action)
        check_single(info)
        if terminated or truncated:
            seen.update(r for r in REASONS if info[r])
            assert info["reasons"] == "+".join(r for r in REASONS if info[r])
            _, info = env.reset()
            check_single(info)
    assert reason in seen


def test_joint_at_limit_and_divergence_are_described_when_they_happen() -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    while True:
        *_, terminated, _, info = env.step(-np.ones(12))
        if terminated:
            break
    assert info["joint_at_limit"] in env.joint_names
    assert info["joint_at_limit_side"] == "lower" and info["joint_at_limit_angle"] < 0
    _, info = env.reset()
    assert (info["joint_at_limit"], info["joint_at_limit_side"]) == ("", "")
    assert info["joint_at_limit_angle"] == 0.0 and info["divergence"] == ""
    env = hyq.HyQEnv(physics={"dt": 0.1})
    env.reset(seed=0)
    *_, info = env.step(np.zeros(12))
    assert info["diverged"] and "diverged" in info["divergence"]


@pytest.mark.parametrize("reason", REASONS)
def test_the_vector_env_info_keeps_its_shape_and_matches_sync_vector_env(reason: str) -> None:
    n = 2
    ours = hyq.HyQVectorEnv(num_envs=n, **ENDINGS[reason])
    sync = SyncVectorEnv([lambda: hyq.HyQEnv(**ENDINGS[reason]) for _ in range(n)])
    _, info = ours.reset(seed=0)
    _, sync_info = sync.reset(seed=0)
    layout = check_vector(info, n, None)
    assert check_vector(sync_info, n, None) == layout
    actions = actions_for([reason] * n)
    for _ in range(STEPS):
        *_, info = ours.step(actions)
        *_, sync_info = sync.step(actions)
        check_vector(info, n, layout)
        check_vector(sync_info, n, layout)
        for key in hyq.INFO_SCHEMA:
            np.testing.assert_array_equal(info[key], sync_info[key], err_msg=key)
    assert ours.env_info(0).keys() == hyq.INFO_SCHEMA.keys()


def mixed_envs(vector: type) -> gym.vector.VectorEnv:
    """One env per ending, side by side: the envs end at different steps by different reasons."""
    return vector([lambda cfg=cfg: hyq.HyQEnv(**cfg) for cfg in ENDINGS.values()])


@pytest.mark.parametrize("vector", [SyncVectorEnv, AsyncVectorEnv])
def test_gymnasium_vector_envs_and_dict_info_to_list_take_every_ending(vector: type) -> None:
    envs = DictInfoToList(mixed_envs(vector))
    try:
        _, infos = envs.reset(seed=0)
        actions = actions_for(REASONS)
        seen = set()
        for _ in range(STEPS):
            *_, terminated, truncated, infos = envs.step(actions)
            assert len(infos) == len(REASONS)
            for info in infos:
                check_single(info)
                seen.update(r for r in REASONS if info[r])
        assert seen == set(REASONS)
    finally:
        envs.close()


def test_dict_info_to_list_over_the_projects_vector_env() -> None:
    for reason in REASONS:
        envs = DictInfoToList(hyq.HyQVectorEnv(num_envs=2, **ENDINGS[reason]))
        envs.reset(seed=0)
        ended = False
        for _ in range(STEPS):
            *_, terminated, truncated, infos = envs.step(actions_for([reason] * 2))
            for info in infos:
                check_single(info)
                ended |= bool(info[reason])
        assert ended, reason


def test_every_reward_term_of_the_core_is_an_info_key_with_the_steps_value() -> None:
    """The info's term keys are hyq-spec's table of reward terms (``_core.REWARD_TERMS``), so a
    term added there reaches Python without another edit."""
    terms = hyq._core.REWARD_TERMS
    assert len(terms) == len(set(terms)) and "r_e" in terms and "fall_penalty" in terms
    env = hyq.HyQEnv()
    env.reset(seed=0)
    *_, info = env.step(np.zeros(12, dtype=np.float32))
    for term in terms:
        assert hyq.INFO_SCHEMA[term] == "float", term
        assert isinstance(info[term], float), (term, info[term])
