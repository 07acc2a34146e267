"""The Stable-Baselines3 adapter gives what SB3's ``DummyVecEnv`` over N ``HyQEnv`` gives:
same-step resets, ``terminal_observation`` (the final observation) and
``TimeLimit.truncated`` (timeout and not terminated) in the ended env's info, seeds
``seed + i``, float32 rewards and bool dones.

Stable-Baselines3 cannot be imported without PyTorch (a multi-gigabyte install), so these
tests put a stand-in for ``stable_baselines3.common.vec_env.VecEnv`` in ``sys.modules``: it
reproduces the parts of SB3 2.9.2's base class the adapter relies on (the constructor's
attributes and ``render_mode`` lookup, ``seed``, ``_reset_seeds``, ``_reset_options``,
``step``). The adapter's own logic is what is tested; running it under the real base class
is left to ``examples/train_sb3_ppo.py``.
"""

from __future__ import annotations

import importlib
import sys
import types
from typing import Any

import numpy as np
import pytest

import hyq


class FakeVecEnv:
    """The parts of ``stable_baselines3.common.vec_env.VecEnv`` (2.9.2) the adapter uses."""

    def __init__(self, num_envs: int, observation_space: Any, action_space: Any) -> None:
        self.num_envs = num_envs
        self.observation_space = observation_space
        self.action_space = action_space
        self.reset_infos: list[dict[str, Any]] = [{} for _ in range(num_envs)]
        self._seeds: list[int | None] = [None for _ in range(num_envs)]
        self._options: list[dict[str, Any]] = [{} for _ in range(num_envs)]
        self.render_mode = self.get_attr("render_mode")[0]

    def _reset_seeds(self) -> None:
        self._seeds = [None for _ in range(self.num_envs)]

    def _reset_options(self) -> None:
        self._options = [{} for _ in range(self.num_envs)]

    def seed(self, seed: int | None = None) -> list[int | None]:
        self._seeds = [seed + i for i in range(self.num_envs)]
        return self._seeds

    def step(self, actions: np.ndarray):
        self.step_async(actions)
        return self.step_wait()


@pytest.fixture()
def sb3(monkeypatch: pytest.MonkeyPatch) -> types.ModuleType:
    names = ["stable_baselines3", "stable_baselines3.common", "stable_baselines3.common.vec_env"]
    for name in names:
        monkeypatch.setitem(sys.modules, name, types.ModuleType(name))
    sys.modules["stable_baselines3.common.vec_env"].VecEnv = FakeVecEnv
    monkeypatch.delitem(sys.modules, "hyq.sb3", raising=False)
    return importlib.import_module("hyq.sb3")


N = 2
CONFIG = dict(max_time_steps=6, goal={"mode": "random"})


def test_adapter_matches_dummy_vec_env_semantics(sb3: types.ModuleType) -> None:
    venv = sb3.HyQVecEnv(num_envs=N, seed=3, **CONFIG)
    assert isinstance(venv, FakeVecEnv)
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


def test_seeds_are_used_once(sb3: types.ModuleType) -> None:
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
