"""A vector env whose envs run on different engines: ``backend=[...]`` assigns the listed
engines round-robin to the envs (env i on the ``i % len``-th); env i gives exactly what a single
``HyQEnv`` on its engine gives for seed s + i and the same actions, across autoresets;
``info["backend"]`` names each env's engine (in the single env and the single-engine vector env
too); a name this build lacks is the usual ``ValueError`` naming the build option. The package
is built in the test stage with rapier and MuJoCo (not DART), so the mix tested is what is
built, and DART's absence is tested as the not-built error."""

from __future__ import annotations

import importlib
import sys
import types

import gymnasium as gym
import numpy as np
import pytest

import hyq
from sb3_without_torch import load

# Short episodes, so that every env autoresets within the test.
CONFIG = dict(max_time_steps=9, goal={"mode": "random"}, reset={"joint_noise_rad": 0.05})
ENGINES = list(hyq.BACKENDS)


@pytest.fixture()
def sb3(monkeypatch: pytest.MonkeyPatch) -> types.SimpleNamespace:
    """SB3's VecEnv without PyTorch, and ``hyq.sb3`` imported against it (as
    test_sb3_adapter_bootstrapping_info.py does)."""
    real = load(monkeypatch)
    monkeypatch.delitem(sys.modules, "hyq.sb3", raising=False)
    module = importlib.import_module("hyq.sb3")
    monkeypatch.setitem(sys.modules, "hyq.sb3", module)
    return types.SimpleNamespace(HyQVecEnv=module.HyQVecEnv, **vars(real))


def test_each_env_of_the_mix_is_a_single_env_on_its_engine() -> None:
    n = 2 * len(ENGINES) + 1
    venv = gym.make_vec("HyQ-v0", num_envs=n, backend=ENGINES, **CONFIG)
    expected = [ENGINES[i % len(ENGINES)] for i in range(n)]
    assert venv.backends == tuple(expected)
    singles = [hyq.HyQEnv(backend=name, **CONFIG) for name in expected]
    obs, infos = venv.reset(seed=40)
    assert list(infos["backend"]) == expected
    assert infos["_backend"].all()
    for i, env in enumerate(singles):
        o, info = env.reset(seed=40 + i)
        np.testing.assert_array_equal(obs[i], o)
        assert info["backend"] == expected[i]
    ended = [False] * n
    autoresets = 0
    rng = np.random.default_rng(1)
    for _ in range(25):
        a = rng.uniform(-1, 1, size=(n, 12)).astype(np.float32)
        obs, rewards, terminated, truncated, infos = venv.step(a)
        assert list(infos["backend"]) == expected
        for i, env in enumerate(singles):
            if ended[i]:
                o, info = env.reset()
                r, te, tr = 0.0, False, False
                autoresets += 1
            else:
                o, r, te, tr, info = env.step(a[i])
            np.testing.assert_array_equal(obs[i], o)
            assert rewards[i] == r and terminated[i] == te and truncated[i] == tr
            assert infos["t"][i] == info["t"]
            ended[i] = te or tr
    assert autoresets >= n


def test_the_mix_repeats_bit_for_bit_whatever_the_threads() -> None:
    def run(threads: int) -> list[np.ndarray]:
        venv = hyq.HyQVectorEnv(num_envs=4, backend=ENGINES, threads=threads, **CONFIG)
        out = [venv.reset(seed=5)[0]]
        rng = np.random.default_rng(2)
        for _ in range(12):
            obs, rewards, *_ = venv.step(rng.uniform(-1, 1, size=(4, 12)).astype(np.float32))
            out += [obs, rewards]
        return out

    for a, b in zip(run(1), run(2)):
        np.testing.assert_array_equal(a, b)


def test_the_single_engine_envs_name_their_engine() -> None:
    for name in ENGINES:
        _, info = hyq.HyQEnv(backend=name).reset(seed=0)
        assert info["backend"] == name
        venv = gym.make_vec("HyQ-v0", num_envs=2, backend=name)
        _, infos = venv.reset(seed=0)
        assert list(infos["backend"]) == [name, name]
        assert venv.backends == (name, name)
        assert venv.env_info(1)["backend"] == name
    assert hyq.INFO_SCHEMA["backend"] == "str"


def test_an_engine_not_built_in_the_list_is_the_usual_error() -> None:
    for name in ("mujoco", "dart"):
        if name not in hyq.BACKENDS:
            with pytest.raises(ValueError, match=f'backend="{name}".*--features {name}'):
                gym.make_vec("HyQ-v0", num_envs=4, backend=["rapier", name])
    with pytest.raises(ValueError, match="unknown backend"):
        hyq.HyQVectorEnv(num_envs=2, backend=["rapier", "bullet"])


def test_bad_lists_are_refused_by_name() -> None:
    with pytest.raises(ValueError, match=r"backend = \[\]"):
        hyq.HyQVectorEnv(num_envs=2, backend=[])
    with pytest.raises(TypeError, match="backend"):
        hyq.HyQVectorEnv(num_envs=2, backend=["rapier", 3])
    if len(ENGINES) >= 2:
        with pytest.raises(ValueError, match="num_envs = 1"):
            hyq.HyQVectorEnv(num_envs=1, backend=ENGINES)
    # One engine listed (even twice) is that engine's own vector env.
    venv = hyq.HyQVectorEnv(num_envs=3, backend=["rapier", "rapier"])
    assert venv.backends == ("rapier",) * 3


def test_the_sb3_adapter_takes_the_list(sb3: types.SimpleNamespace) -> None:
    n = 2 * len(ENGINES)
    venv = sb3.HyQVecEnv(num_envs=n, seed=3, backend=ENGINES, **CONFIG)
    venv.reset()
    names = [info["backend"] for info in venv.reset_infos]
    assert names == [ENGINES[i % len(ENGINES)] for i in range(n)]
    venv.step_async(np.zeros((n, 12), dtype=np.float32))
    _, _, _, infos = venv.step_wait()
    assert [info["backend"] for info in infos] == names
