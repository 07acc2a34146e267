"""Same seed and same actions give bit-identical observations, rewards, flags and infos; an
unseeded reset after a seeded one continues the seed's streams reproducibly; the seed is the
one ``hyq run --seed`` takes."""

from __future__ import annotations

import numpy as np
from gymnasium.utils.env_checker import data_equivalence

import hyq


def rollout(env: hyq.HyQEnv, seed: int, steps: int, resets: int = 2) -> list:
    """Observations, rewards, flags and infos of `resets` episodes (the first seeded) under
    the action space's own seeded samples."""
    env.action_space.seed(seed)
    out = []
    for episode in range(resets):
        obs, info = env.reset(seed=seed if episode == 0 else None)
        out.append((obs, info))
        for _ in range(steps):
            step = env.step(env.action_space.sample())
            out.append(step)
            if step[2] or step[3]:
                break
    return out


def test_same_seed_same_actions_same_everything() -> None:
    config = dict(goal={"mode": "random", "heading_range_deg": [-30, 30]}, reset={"joint_noise_rad": 0.02})
    a = rollout(hyq.HyQEnv(**config), seed=11, steps=60)
    b = rollout(hyq.HyQEnv(**config), seed=11, steps=60)
    assert len(a) == len(b)
    for x, y in zip(a, b):
        assert data_equivalence(x, y, exact=True)


def test_different_seeds_draw_different_goals_and_noise() -> None:
    config = dict(goal={"mode": "random", "heading_range_deg": [-30, 30]}, reset={"joint_noise_rad": 0.02})
    env = hyq.HyQEnv(**config)
    obs_1, info_1 = env.reset(seed=1)
    obs_2, info_2 = env.reset(seed=2)
    assert not np.array_equal(info_1["goal"], info_2["goal"])
    assert not np.array_equal(obs_1[:12], obs_2[:12])


def test_unseeded_resets_continue_the_seeded_streams() -> None:
    config = dict(goal={"mode": "random"})
    env = hyq.HyQEnv(**config)
    env.reset(seed=5)
    goals = [env.reset()[1]["goal"] for _ in range(3)]
    env.reset(seed=5)
    again = [env.reset()[1]["goal"] for _ in range(3)]
    np.testing.assert_array_equal(goals, again)
    assert len({tuple(g) for g in goals}) == 3


def test_reset_goal_option_sets_this_episode_goal() -> None:
    env = hyq.HyQEnv()
    _, info = env.reset(seed=0, options={"goal": [3.0, 1.0, 0.6]})
    np.testing.assert_array_equal(info["goal"], [3.0, 1.0, 0.6])
    _, info = env.reset(seed=0)
    np.testing.assert_array_equal(info["goal"], [5.0, 0.0, 0.5895])
