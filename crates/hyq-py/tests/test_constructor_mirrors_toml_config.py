"""Constructor keyword arguments mirror the TOML configuration (the spec's user variables by
name, the other tables as dicts), an ``env_config`` dict (RLlib's convention) and a TOML file
are accepted too, and all three reach the same core configuration."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import hyq


def test_keywords_env_config_and_file_give_the_same_configuration(tmp_path: Path) -> None:
    toml = tmp_path / "hyq.toml"
    toml.write_text(
        "[task]\nfall_penalty = 1.5\nnorm_rew_scaling = 10.0\nmax_time_steps = 300\n"
        '[goal]\nmode = "fixed"\nposition = [4.0, 1.0, 0.6]\n'
        '[action]\nmode = "delta"\n'
    )
    kwargs = dict(
        fall_penalty=1.5,
        norm_rew_scaling=10.0,
        max_time_steps=300,
        goal={"mode": "fixed", "position": [4.0, 1.0, 0.6]},
        action={"mode": "delta"},
    )
    by_keywords = hyq.HyQEnv(**kwargs)
    by_dict = hyq.HyQEnv(env_config=kwargs)
    by_file = hyq.HyQEnv(config_file=str(toml))
    by_table = hyq.HyQEnv(task={"fall_penalty": 1.5, "norm_rew_scaling": 10.0, "max_time_steps": 300},
                          goal=kwargs["goal"], action={"mode": "delta"})
    texts = {e.config_toml() for e in (by_keywords, by_dict, by_file, by_table)}
    assert len(texts) == 1
    assert "fall_penalty = 1.5" in texts.pop()
    assert by_keywords.max_time_steps == 300
    _, info = by_keywords.reset(seed=0)
    np.testing.assert_array_equal(info["goal"], [4.0, 1.0, 0.6])


def test_keywords_override_env_config_and_file(tmp_path: Path) -> None:
    toml = tmp_path / "hyq.toml"
    toml.write_text("[task]\nfall_penalty = 1.5\n")
    env = hyq.HyQEnv(config_file=str(toml), env_config={"fall_penalty": 2.0}, fall_penalty=3.0)
    assert "fall_penalty = 3.0" in env.config_toml()


def test_none_switches_an_optional_reward_off() -> None:
    env = hyq.HyQEnv(exp_rew_scaling=None)
    env.reset(seed=0)
    *_, info = env.step(np.ones(12))
    assert info["r_e"] == 0.0
    assert 'exp_rew_scaling = "off"' in env.config_toml()


def test_action_modes_set_the_action_space() -> None:
    absolute = hyq.HyQEnv(action={"mode": "absolute"})
    assert absolute._core.action_mode == "absolute"
    assert absolute.action_space.low[2] < -2.4 and absolute.action_space.high[2] < 0
    delta = hyq.HyQEnv(action={"mode": "delta", "max_delta_rad": 0.05})
    assert np.all(delta.action_space.low == -1.0) and np.all(delta.action_space.high == 1.0)


def test_physics_engine_table_is_passed_through() -> None:
    env = hyq.HyQEnv(physics={"rapier": {"solver_iterations": 4}})
    assert "solver_iterations = 4" in env.config_toml()


def test_numpy_scalars_and_arrays_are_accepted_as_values() -> None:
    env = hyq.HyQEnv(
        fall_penalty=np.float64(1.5),
        max_time_steps=np.int64(300),
        goal={"mode": "fixed", "position": np.array([4.0, 1.0, 0.6])},
    )
    text = env.config_toml()
    assert "fall_penalty = 1.5" in text
    assert "max_time_steps = 300" in text
    assert "position = [4.0, 1.0, 0.6]" in text
