"""The Stable-Baselines3 adapter gives what SB3's ``DummyVecEnv`` over N ``HyQEnv`` gives:
same-step resets, ``terminal_observation`` (the final observation) and
``TimeLimit.truncated`` (timeout and not terminated) in the ended env's info, seeds
``seed + i``, float32 rewards and bool dones.

The adapter runs on SB3's real ``VecEnv`` base class and is compared with SB3's real
``DummyVecEnv``, both loaded from the pinned SB3 wheel without PyTorch (see
``sb3_without_torch``).
"""

from __future__ import annotations

import importlib
import sys
import types

import numpy as np
import pytest

import hyq
from sb3_without_torch import load


@pytest.fixture()
def sb3(monkeypatch: pytest.MonkeyPatch) -> types.SimpleNamespace:
    real = load(monkeypatch)
    monkeypatch.delitem(sys.modules, "hyq.sb3", raising=False)
    module = importlib.import_module("hyq.sb3")
    # hyq.sb3 was imported against this test's SB3 modules: forget it afterwards.
    monkeypatch.setitem(sys.modules, "hyq.sb3", module)
    return types.SimpleNamespace(HyQVecEnv=module.HyQVecEnv, **vars(real))


N = 2
CONFIG = dict(max_time_steps=6, goal={"mode": "random"})


def test_adapter_matches_dummy_vec_env_semantics(sb3: types.SimpleNamespace) -> None:
    venv = sb3.HyQVecEnv(num_envs=N, seed=3, **CONFIG)
    assert isinstance(venv, sb3.VecEnv)
    singles = [hyq.HyQEnv(**CONFIG) for _ in range(N)]
    obs = venv.reset()
    for i, env in enumerate(singles):
        np.testing.assert_array_equal(obs[i], env.reset(seed=3 + i)[0])
    rng = np.random.default_rng(0)
    ended = 0
    for _ in range(20):
        actions = rng.uniform(-1, 1, size=(N, 12)).astype(np.float32)
        obs, rewards, dones, infos = venv.step(actions)
        assert rewards.dtype == np.float32 and dones.dtype == np.bool_
        for i, env in enumerate(singles):
            o, r, te, tr, info = env.step(actions[i])
            assert rewards[i] == np.float32(r)
            assert dones[i] == (te or tr)
            assert infos[i]["TimeLimit.truncated"] == (tr and not te)
            assert infos[i]["reasons"] == info["reasons"]
            if te or tr:
                ended += 1
                np.testing.assert_array_equal(infos[i]["terminal_observation"], o)
                o, reset_info = env.reset()
                np.testing.assert_array_equal(venv.reset_infos[i]["goal"], reset_info["goal"])
            else:
                assert "terminal_observation" not in infos[i]
            np.testing.assert_array_equal(obs[i], o)
    assert ended >= 2 * N
    assert venv.get_attr("max_time_steps") == [6, 6]
    assert venv.env_is_wrapped(object) == [False, False]


def test_seeds_are_used_once(sb3: types.SimpleNamespace) -> None:
    venv = sb3.HyQVecEnv(num_envs=N, **CONFIG)
    venv.seed(10)
    first = venv.reset()
    second = venv.reset()  # unseeded: the streams continue, so other random goals
    venv.seed(10)
    np.testing.assert_array_equal(venv.reset(), first)
    goals = [venv.reset_infos[i]["goal"] for i in range(N)]
    venv.reset()
    assert not all(np.array_equal(g, venv.reset_infos[i]["goal"]) for i, g in enumerate(goals))
    assert second.shape == first.shape


def test_adapter_gives_what_sb3s_dummy_vec_env_gives(sb3: types.SimpleNamespace) -> None:
    venv = sb3.HyQVecEnv(num_envs=N, **CONFIG)
    dummy = sb3.DummyVecEnv([lambda: hyq.HyQEnv(**CONFIG) for _ in range(N)])
    venv.seed(7)
    dummy.seed(7)
    np.testing.assert_array_equal(venv.reset(), dummy.reset())
    rng = np.random.default_rng(1)
    for _ in range(20):
        actions = rng.uniform(-1, 1, size=(N, 12)).astype(np.float32)
        obs, rewards, dones, infos = venv.step(actions)
        d_obs, d_rewards, d_dones, d_infos = dummy.step(actions)
        np.testing.assert_array_equal(obs, d_obs)
        np.testing.assert_array_equal(rewards, d_rewards)
        np.testing.assert_array_equal(dones, d_dones)
        for info, d_info in zip(infos, d_infos):
            assert info["TimeLimit.truncated"] == d_info.get("TimeLimit.truncated", False)
            assert ("terminal_observation" in info) == ("terminal_observation" in d_info)
            if "terminal_observation" in info:
                np.testing.assert_array_equal(
                    info["terminal_observation"], d_info["terminal_observation"]
                )


def test_the_same_seed_pickles_the_same_spaces(sb3: types.SimpleNamespace) -> None:
    """Two adapters of one seed pickle their spaces (as VecNormalize's statistics file holds
    them) to the same bytes; gymnasium alone seeds their samplers from the OS's entropy."""
    import pickle

    a, b = (sb3.HyQVecEnv(num_envs=N, seed=3, **CONFIG) for _ in range(2))
    for space in ("observation_space", "action_space"):
        assert pickle.dumps(getattr(a, space)) == pickle.dumps(getattr(b, space)), space
    assert np.array_equal(a.action_space.sample(), b.action_space.sample())
