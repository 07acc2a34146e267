"""The declared observation space contains every observation the env emits (a Gymnasium
observation must lie in its space; Stable-Baselines3's checker asserts it). Unclipped (the
default), the spec's section 3 bounds are declared only on the rows that are invariants (the
contact flags, 0 or 1, and the quaternion, within [-1, 1]); every other row is unbounded, as the
whole finite float32 range. With ``clip_observations=True`` the space is the table, and the values
are clipped to it. The table itself (names, bounds, units) is data: ``hyq.OBSERVATION_TABLE``."""

from __future__ import annotations

import numpy as np
import pytest

import hyq

F32_MAX = float(np.finfo(np.float32).max)
INVARIANT_ROWS = range(24, 33)


def random_steps(env, seed: int, steps: int):
    """Observations of `steps` random-action steps from seeded resets."""
    env.action_space.seed(seed)
    obs, _ = env.reset(seed=seed)
    yield obs
    for _ in range(steps):
        obs, _, terminated, truncated, _ = env.step(env.action_space.sample())
        yield obs
        if terminated or truncated:
            obs, _ = env.reset()
            yield obs


def test_the_table_is_data_with_names_bounds_and_units() -> None:
    table = hyq.OBSERVATION_TABLE
    assert len(table) == 39
    assert [r.index for r in table] == list(range(39))
    assert [r.name for r in table] == hyq.HyQEnv().observation_names
    row = {r.name: r for r in table}
    assert (row["lf_kfe_angle"].low, row["lf_kfe_angle"].high) == pytest.approx(
        (-2.44346, -0.349066), abs=1e-5
    )
    assert (row["rh_kfe_speed"].low, row["rh_kfe_speed"].high) == (-12.0, 12.0)
    assert (row["trunk_accel_x"].low, row["trunk_accel_x"].high) == (-50.0, 50.0)
    assert (row["trunk_position_z"].low, row["trunk_position_z"].high) == (0.0, 1.0)
    assert [r.index for r in table if r.estimated] == list(range(33, 39))
    assert [r.index for r in table if r.invariant] == list(INVARIANT_ROWS)
    assert row["lf_haa_speed"].unit == "rad/s" and row["trunk_position_x"].unit == "m"
    assert hyq.HyQEnv().observation_table == table


def test_the_default_space_bounds_only_the_invariant_rows() -> None:
    space = hyq.HyQEnv().observation_space
    table = hyq.OBSERVATION_TABLE
    for r in table:
        low, high = float(space.low[r.index]), float(space.high[r.index])
        if r.invariant:
            assert (low, high) == (pytest.approx(r.low), pytest.approx(r.high)), r.name
        else:
            assert (low, high) == (-F32_MAX, F32_MAX), r.name
    assert np.all(np.isfinite(space.low)) and np.all(np.isfinite(space.high))


def test_clipping_declares_the_table_and_keeps_values_in_it() -> None:
    env = hyq.HyQEnv(clip_observations=True)
    low = np.array([r.low for r in hyq.OBSERVATION_TABLE], dtype=np.float32)
    high = np.array([r.high for r in hyq.OBSERVATION_TABLE], dtype=np.float32)
    np.testing.assert_array_equal(env.observation_space.low, low)
    np.testing.assert_array_equal(env.observation_space.high, high)
    for obs in random_steps(env, 1, 200):
        assert obs in env.observation_space


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_every_raw_observation_lies_in_the_default_space(seed: int) -> None:
    # Random actions push joint speeds past the table's 12 rad/s within the first steps: the
    # old space (the table) did not contain them.
    env = hyq.HyQEnv()
    table_low = np.array([r.low for r in hyq.OBSERVATION_TABLE], dtype=np.float32)
    table_high = np.array([r.high for r in hyq.OBSERVATION_TABLE], dtype=np.float32)
    outside_table = 0
    for obs in random_steps(env, seed, 300):
        assert obs in env.observation_space
        outside_table += bool(np.any((obs < table_low) | (obs > table_high)))
    assert outside_table > 0, "the physics was expected to leave the table somewhere"


def test_the_vector_env_declares_the_same_spaces() -> None:
    for clip in (False, True):
        single = hyq.HyQEnv(clip_observations=clip)
        envs = hyq.HyQVectorEnv(num_envs=2, clip_observations=clip)
        assert envs.single_observation_space == single.observation_space
        envs.action_space.seed(0)
        obs, _ = envs.reset(seed=0)
        for _ in range(50):
            assert obs in envs.observation_space
            obs, *_ = envs.step(envs.action_space.sample())


def test_observation_extra_and_terrain_reach_the_spaces_and_the_table() -> None:
    """``observation.extra`` appends rows after the 39 (height scan, goal vector, trunk
    velocity), which the space (unbounded there), the env's table (named, with units) and the
    observations follow; the default env keeps the spec's 39 rows."""
    # The goal 2.5 m ahead, on the 6 m field (a field not under the goal is refused).
    env = hyq.HyQEnv(
        terrain={"kind": "rough", "amplitude_m": 0.05, "size_m": [6.0, 6.0]}, goal={"distance_m": 2.5},
        observation={"extra": ["goal_vector", "height_scan", "trunk_velocity"]},
    )
    assert env.observation_space.shape == (235,)
    table = env.observation_table
    assert [r.name for r in table] == env.observation_names
    assert [r.name for r in table[:39]] == [r.name for r in hyq.OBSERVATION_TABLE]
    units = {r.name: r.unit for r in table}
    assert units["height_scan_00_00"] == "m" and units["goal_vector_z"] == "m"
    assert units["trunk_angvel_z"] == "m/s, rad/s"
    assert not any(r.invariant for r in table[39:])
    assert env.observation_space.high[39:].min() == F32_MAX
    obs, info = env.reset(seed=3)
    assert obs.shape == (235,) and env.observation_space.contains(obs)
    # The goal vector's length is the distance to the goal.
    assert float(np.linalg.norm(obs[226:229])) == pytest.approx(info["distance_to_goal"], rel=1e-6)
    assert "[terrain]" in env.config_toml() and "[observation]" in env.config_toml()
    assert "[terrain]" not in hyq.HyQEnv().config_toml()
    # The vector env's table is the single env's, extras included.
    venv = hyq.HyQVectorEnv(num_envs=2, terrain={"kind": "rough", "amplitude_m": 0.05, "size_m": [6.0, 6.0]},
                            goal={"distance_m": 2.5},
                            observation={"extra": ["goal_vector", "height_scan", "trunk_velocity"]})
    assert venv.observation_table == table
    assert len(hyq.HyQVectorEnv(num_envs=1).observation_table) == 39
    venv.close()
    env.close()
