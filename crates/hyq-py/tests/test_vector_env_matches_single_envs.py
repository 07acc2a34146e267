"""The Rust-batched vector env gives exactly what N single ``HyQEnv`` give for the same seeds
and actions, across autoresets: next-step (Gymnasium's default: the step after an episode
ends resets that env, ignores its action and reports reward 0) and same-step (the reset
happens at once; the final observation and info are kept)."""

from __future__ import annotations

import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import hyq

N = 3
# Short episodes, so that every env autoresets several times within the test.
CONFIG = dict(max_time_steps=9, goal={"mode": "random"}, reset={"joint_noise_rad": 0.05})


def actions(seed: int, steps: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.uniform(-1, 1, size=(steps, N, 12)).astype(np.float32)


@pytest.mark.parametrize("threads", [None, 1, 2])
def test_next_step_autoreset_matches_single_envs(threads: int | None) -> None:
    venv = hyq.HyQVectorEnv(num_envs=N, threads=threads, **CONFIG)
    singles = [hyq.HyQEnv(**CONFIG) for _ in range(N)]
    obs, infos = venv.reset(seed=40)
    for i, env in enumerate(singles):
        o, info = env.reset(seed=40 + i)
        np.testing.assert_array_equal(obs[i], o)
        np.testing.assert_array_equal(infos["goal"][i], info["goal"])
    ended = [False] * N
    autoresets = 0
    for a in actions(1, 40):
        obs, rewards, terminated, truncated, infos = venv.step(a)
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
            assert infos["r_e"][i] == info["r_e"]
            np.testing.assert_array_equal(infos["goal"][i], info["goal"])
            ended[i] = te or tr
    assert autoresets >= 3 * N


def test_same_step_autoreset_matches_single_envs() -> None:
    venv = hyq.HyQVectorEnv(num_envs=N, autoreset_mode=AutoresetMode.SAME_STEP, **CONFIG)
    assert venv.metadata["autoreset_mode"] == AutoresetMode.SAME_STEP
    singles = [hyq.HyQEnv(**CONFIG) for _ in range(N)]
    venv.reset(seed=7)
    for i, env in enumerate(singles):
        env.reset(seed=7 + i)
    finals = 0
    for a in actions(2, 30):
        obs, rewards, terminated, truncated, _ = venv.step(a)
        for i, env in enumerate(singles):
            o, r, te, tr, info = env.step(a[i])
            assert rewards[i] == r and terminated[i] == te and truncated[i] == tr
            if te or tr:
                finals += 1
                np.testing.assert_array_equal(venv.final_observation(i), o)
                assert venv.final_info(i)["reasons"] == info["reasons"]
                o, _ = env.reset()
            else:
                assert venv.final_observation(i) is None
            np.testing.assert_array_equal(obs[i], o)
    assert finals >= N


def test_list_seeds_and_reset_mask() -> None:
    venv = hyq.HyQVectorEnv(num_envs=N, **CONFIG)
    obs, _ = venv.reset(seed=[5, None, 9])
    single = hyq.HyQEnv(**CONFIG)
    np.testing.assert_array_equal(obs[0], single.reset(seed=5)[0])
    np.testing.assert_array_equal(obs[2], single.reset(seed=9)[0])
    before = obs.copy()
    venv.step(np.zeros((N, 12), dtype=np.float32))
    stepped = venv.step(np.zeros((N, 12), dtype=np.float32))[0]
    obs, infos = venv.reset(seed=5, options={"reset_mask": [True, False, False]})
    np.testing.assert_array_equal(obs[0], before[0])
    np.testing.assert_array_equal(obs[1:], stepped[1:])
    assert list(infos["t"]) == [0, 2, 2]


def test_vector_make_vec_max_episode_steps_sets_the_core_t_max() -> None:
    import gymnasium as gym

    assert gym.make_vec("HyQ-v0", num_envs=2).max_time_steps == 1000
    assert gym.make_vec("HyQ-v0", num_envs=2, max_time_steps=50).max_time_steps == 50


def test_vector_errors_name_the_env() -> None:
    venv = hyq.HyQVectorEnv(num_envs=N)
    venv.reset(seed=0)
    a = np.zeros((N, 12))
    a[1, 4] = np.nan
    with pytest.raises(ValueError, match="env 1: .*not finite|env 1: .*NaN"):
        venv.step(a)
    with pytest.raises(ValueError, match=r"shape \(3, 11\)"):
        venv.step(np.zeros((N, 11)))
