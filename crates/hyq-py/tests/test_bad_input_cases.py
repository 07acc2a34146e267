"""The Python package's bad inputs (a new user's mistakes and an attacker's inputs): each is
refused with an exception that names
what was wrong, leaves the env as it was, and never surfaces a Rust panic; the odd-but-valid
inputs work. Cases with a file of their own: loose arguments
(``test_loose_arguments_are_refused_by_name``), panics and threads
(``test_no_panic_reaches_python``), the observation space (``test_observation_space_is_honest``)."""

from __future__ import annotations

import copy
import pickle
import re
import subprocess
import sys

import gymnasium as gym
import numpy as np
import pytest

import hyq
from conftest import REPO


def stepped(env: hyq.HyQEnv, n: int) -> list[np.ndarray]:
    out = []
    for k in range(n):
        obs, *_ = env.step(np.full(12, 0.1 * ((k % 5) - 2), dtype=np.float32))
        out.append(obs)
    return out


def test_step_before_reset() -> None:
    with pytest.raises(gym.error.ResetNeeded):
        gym.make("HyQ-v0").step(np.zeros(12, np.float32))
    with pytest.raises(RuntimeError, match="before reset"):
        hyq.HyQEnv().step(np.zeros(12))


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_actions_are_refused_naming_the_joint(bad: float) -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    action = np.zeros(12)
    action[11] = bad
    with pytest.raises(ValueError, match="rh_kfe"):
        env.step(action)


@pytest.mark.parametrize(
    "action", [np.zeros(11), np.zeros(13), np.zeros((1, 12)), np.zeros((12, 1)), 0.0, []]
)
def test_wrong_shapes_are_refused(action) -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action"):
        env.step(action)


@pytest.mark.parametrize(
    "action",
    [
        np.zeros(12, np.int64),
        np.zeros(12, np.float16),
        np.zeros(12, bool),
        [0.0] * 12,
        np.zeros(12, ">f8"),
        np.zeros(24)[::2],
    ],
)
def test_real_dtypes_and_layouts_are_accepted(action) -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    env.step(action)


def test_odd_action_types_are_refused() -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    for action in (["abc"] * 12, {"a": 1}, np.full(12, 1j), ["0.5"] * 12):
        with pytest.raises((ValueError, TypeError)):
            env.step(action)
    with pytest.raises(ValueError, match="masked"):
        env.step(np.ma.masked_array(np.zeros(12), mask=[True] + [False] * 11))


@pytest.mark.parametrize("value", [1e308, 1e39, 2.0**70])
def test_huge_finite_actions_are_clipped_and_flagged(value: float) -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    *_, info = env.step(np.full(12, value))
    assert info["action_clipped"] is True


def test_refused_actions_leave_no_trace() -> None:
    clean, dirty = hyq.HyQEnv(), hyq.HyQEnv()
    clean.reset(seed=4)
    dirty.reset(seed=4)
    for bad in (np.full(12, np.nan), np.zeros(11), np.zeros(13)):
        with pytest.raises(ValueError):
            dirty.step(bad)
    for a, b in zip(stepped(clean, 30), stepped(dirty, 30)):
        np.testing.assert_array_equal(a, b)


def test_step_after_the_end_without_reset() -> None:
    env = hyq.HyQEnv(max_time_steps=3)
    env.reset(seed=0)
    stepped(env, 3)
    with pytest.raises(RuntimeError, match="without reset"):
        env.step(np.zeros(12))


@pytest.mark.parametrize("seed", [-1, 2**64, 2**200, 1.0, True, "3", np.int64(-5)])
def test_bad_seeds_are_refused(seed) -> None:
    with pytest.raises(ValueError, match="seed"):
        hyq.HyQEnv().reset(seed=seed)


def test_the_largest_seeds_are_accepted() -> None:
    hyq.HyQEnv().reset(seed=2**64 - 1)
    hyq.HyQEnv().reset(seed=np.uint64(2**64 - 1))


@pytest.mark.parametrize(
    "goal", [[1.0, 2.0], [np.nan, 0, 0], [np.inf, 0, 0], "abc", [0, 0, 0.6003], [1e200, 0, 0]]
)
def test_bad_reset_goals_are_refused_naming_the_goal(goal) -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="goal"):
        env.reset(options={"goal": goal})
    with pytest.raises(ValueError, match="bogus"):
        env.reset(options={"bogus": 1})
    env.reset(options={})


def test_a_refused_reset_changes_nothing() -> None:
    clean, dirty = hyq.HyQEnv(), hyq.HyQEnv()
    clean.reset(seed=5)
    dirty.reset(seed=5)
    with pytest.raises(ValueError):
        dirty.reset(seed=9, options={"goal": [0, 0, 0.6003]})
    for a, b in zip(stepped(clean, 10), stepped(dirty, 10)):
        np.testing.assert_array_equal(a, b)


def test_close_twice() -> None:
    env = gym.make("HyQ-v0")
    env.close()
    env.close()


def test_pickling_is_refused_clearly() -> None:
    with pytest.raises(TypeError, match="pickle"):
        pickle.dumps(hyq.HyQEnv())
    with pytest.raises(TypeError):
        copy.deepcopy(hyq.HyQEnv())


def test_no_configuration_yields_non_finite_rewards() -> None:
    # k_exp = 1000 gave inf at t = 5 next to the goal; a goal at 1e308 m gave NaN every step.
    with pytest.raises(ValueError, match="exp_rew_scaling"):
        hyq.HyQEnv(exp_rew_scaling=1000.0, goal={"mode": "fixed", "position": [0, 0, 0.62]})
    with pytest.raises(ValueError, match="goal.position"):
        hyq.HyQEnv(
            exp_rew_scaling=None,
            base_rew_scaling=1.0,
            goal={"mode": "fixed", "position": [1e308, 1e308, 0]},
        )
    env = hyq.HyQEnv(exp_rew_scaling=500.0, goal={"mode": "fixed", "position": [0, 0, 0.62]})
    env.reset(seed=0)
    for _ in range(30):
        _, reward, terminated, truncated, info = env.step(np.zeros(12))
        assert np.isfinite(reward)
        if terminated or truncated:
            break


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(fall_penalty="abc"),
        dict(fall_penalty=[1]),
        dict(fall_penalty=np.float32(np.nan)),
        dict(fall_penalty=1j),
        dict(bogus_key=1),
        dict(goal="fixed"),
        dict(max_time_steps=True),
        dict(max_time_steps=5.0),
        dict(max_time_steps=2**63),
        dict(render_width=0),
        dict(config_file="/nonexistent/missing.toml"),
        dict(config_file="/dev/zero"),
        dict(env_config=[1]),
        dict(render_mode="bogus"),
        dict(goal={"position": [9, 9, 0.6]}),
    ],
)
def test_constructor_arguments_are_checked_by_name(kwargs) -> None:
    with pytest.raises((ValueError, TypeError)) as err:
        hyq.HyQEnv(**kwargs)
    name = next(iter(kwargs))
    words = {"bogus_key": "bogus_key", "env_config": "env_config", "config_file": "missing"}
    expected = words.get(name, name)
    if name == "config_file" and "zero" in str(kwargs[name]):
        # A device is not read at all, like a FIFO (it used to be read up to the 1 MiB cap).
        expected = "is not a regular file"
    if name == "goal" and isinstance(kwargs[name], dict):
        expected = "goal.position"
    assert expected in str(err.value), str(err.value)


def test_max_time_steps_with_gym_make_needs_max_episode_steps() -> None:
    env = gym.make("HyQ-v0", max_time_steps=2000, max_episode_steps=2000)
    assert env.spec.max_episode_steps == env.unwrapped.max_time_steps == 2000


def test_a_refused_batch_changes_no_env() -> None:
    clean, dirty = hyq.HyQVectorEnv(num_envs=3), hyq.HyQVectorEnv(num_envs=3)
    clean.reset(seed=1)
    dirty.reset(seed=1)
    bad = np.zeros((3, 12))
    bad[1, 4] = np.nan
    for batch in (bad, np.zeros((3, 11)), np.zeros((4, 12)), np.zeros(12), np.zeros((3, 12, 1))):
        with pytest.raises(ValueError):
            dirty.step(batch)
    actions = np.full((3, 12), 0.2, dtype=np.float32)
    for _ in range(10):
        a, *_ = clean.step(actions)
        b, *_ = dirty.step(actions)
        np.testing.assert_array_equal(a, b)


def test_vector_env_arguments() -> None:
    with pytest.raises(ValueError, match="num_envs"):
        hyq.HyQVectorEnv(num_envs=0)
    with pytest.raises(ValueError):
        hyq.HyQVectorEnv(num_envs=2, autoreset_mode="bogus")
    envs = hyq.HyQVectorEnv(num_envs=3)
    with pytest.raises(ValueError, match="seeds"):
        envs.reset(seed=[1, 2])
    with pytest.raises(ValueError, match="reset_mask"):
        envs.reset(options={"reset_mask": [True]})
    with pytest.raises(IndexError):
        envs.env_info(5)
    # Env i is seeded seed + i: the largest seed leaves room for every env (it used to wrap).
    envs.reset(seed=2**64 - 3)
    with pytest.raises(ValueError, match="seed = 18446744073709551614"):
        envs.reset(seed=2**64 - 2)


@pytest.mark.parametrize("robot", ["hyq", "anymal_c"])
def test_absolute_action_space_bounds_are_inside_the_env(robot: str) -> None:
    # The float32 Box is rounded inward: its bounds step unclipped, even under
    # out_of_range="error" (rounded to nearest, 4 of HyQ's lower limits fell outside).
    env = hyq.HyQEnv(robot=robot, action={"mode": "absolute", "out_of_range": "error"})
    space = env.action_space
    for bound in (space.low, space.high):
        env.reset(seed=0)
        _, _, _, _, info = env.step(bound)
        assert not info["action_clipped"]
    vec = hyq.HyQVectorEnv(num_envs=2, robot=robot, action={"mode": "absolute"})
    vec.reset(seed=0)
    *_, infos = vec.step(np.stack([vec.single_action_space.low] * 2))
    assert not np.any(infos["action_clipped"])


def test_reset_options_and_paths_are_checked_by_name() -> None:
    env = hyq.HyQEnv()
    env.reset(seed=0)
    # A string's letters were listed as unknown options.
    with pytest.raises(TypeError, match="reset options = 'notadict': expected a dict"):
        env.reset(options="notadict")
    # Strings are not numbers here either (as in actions).
    with pytest.raises(ValueError, match="goal"):
        env.reset(options={"goal": ["1", "0", "0.6"]})
    with pytest.raises(TypeError, match="config_file = 123"):
        hyq.HyQEnv(config_file=123)
    vec = hyq.HyQVectorEnv(num_envs=2)
    with pytest.raises(TypeError, match="reset options"):
        vec.reset(options="abc")


def robot_copy(tmp_path, profile_edit=("", ""), urdf_edit=("", "")) -> str:
    """The bundled HyQ profile and URDF copied to `tmp_path`, each with one edit."""
    for name, (old, new) in (("profile.toml", profile_edit), ("hyq.urdf", urdf_edit)):
        text = (REPO / "assets" / "hyq" / name).read_text()
        assert old in text, old
        (tmp_path / name).write_text(text.replace(old, new, 1))
    return str(tmp_path / "profile.toml")


def test_robot_files_outside_the_bounds_are_value_errors(tmp_path) -> None:
    lf_haa = '{ name = "lf_haa", urdf = "lf_haa_joint", standing = -0.2 }'
    wide = lf_haa.replace(" }", ", lower = -1.7e308, upper = 1.7e308 }")
    # Limits whose span overflows gave a NaN joint target; a 1e6 m box killed render().
    with pytest.raises(ValueError, match=r"joints\[0\].lower"):
        hyq.HyQEnv(robot=robot_copy(tmp_path, profile_edit=(lf_haa, wide)))
    box = '<box size="1.2898 0.5954 0.3737"/>'
    with pytest.raises(ValueError, match="trunk"):
        hyq.HyQEnv(
            robot=robot_copy(tmp_path, urdf_edit=(box, '<box size="1e6 1e6 1e6"/>')),
            render_mode="rgb_array",
        )


def test_a_deeply_nested_urdf_is_a_value_error_not_a_crash(tmp_path) -> None:
    # 20 000 nested elements overflowed the parser's stack: a segmentation fault that no
    # exception handler could catch. A child interpreter, so that a crash fails this test
    # instead of ending the test run.
    deep = "<a>" * 20_000 + "</a>" * 20_000 + "</robot>"
    profile = robot_copy(tmp_path, urdf_edit=("</robot>", deep))
    script = (
        "import hyq\n"
        "try:\n"
        f"    hyq.HyQEnv(robot={profile!r})\n"
        "except ValueError as e:\n"
        "    print('ValueError:', e)\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "nested more than 64 deep" in done.stdout, done.stdout


@pytest.mark.parametrize(
    ("randomize", "named"),
    [
        ({"ground_friction": [1.2, 0.4]}, "randomize.ground_friction = [1.2, 0.4]"),
        ({"trunk_added_mass_kg": [-1.0, float("inf")]}, "randomize.trunk_added_mass_kg"),
        ({"link_mass_scale": [float("nan"), 1.0]}, "randomize.link_mass_scale = [NaN, 1.0]"),
        ({"kp_scale": [0.0, 1.0]}, "randomize.kp_scale = [0.0, 1.0]"),
        ({"effort_scale": [-1.0, 1.0]}, "randomize.effort_scale = [-1.0, 1.0]"),
        ({"trunk_added_mass_kg": [-100.0, 0.0]}, "randomize.trunk_added_mass_kg = [-100.0, 0.0]"),
        ({"actuator_delay_substeps": [0, 11]}, "randomize.actuator_delay_substeps = [0, 11]"),
        ({"obs_noise": {"joint_speed": -1.0}}, "randomize.obs_noise.joint_speed = -1.0"),
        ({"push_interval_s": [2.0, 4.0]}, "randomize.push_interval_s"),
        ({"bogus": [0, 1]}, "bogus"),
        ({"preset": "gym"}, "gym"),
    ],
)
def test_bad_randomize_values_are_value_errors_naming_key_and_value(
    randomize: dict, named: str
) -> None:
    """Reversed or non-finite ranges, a scale that can make a mass or gain zero or negative, a
    delay longer than an env step, a negative deviation, an unknown key, a bad preset: a
    ValueError naming the key and the value, before an env exists, from keyword arguments and
    from ``env_config`` alike."""
    for kwargs in ({"randomize": randomize}, {"env_config": {"randomize": randomize}}):
        with pytest.raises(ValueError, match=re.escape(named)):
            hyq.HyQEnv(**kwargs)
    with pytest.raises(ValueError, match=re.escape(named)):
        hyq.HyQVectorEnv(num_envs=2, randomize=randomize)


@pytest.mark.parametrize(
    "terrain, named",
    [
        ({"kind": "slope", "step_height_m": 0.2}, "terrain.step_height_m"),
        ({"kind": "rough", "slope_deg": 5.0}, "terrain.slope_deg"),
        ({"kind": "stairs", "amplitude_m": 0.1}, "terrain.amplitude_m"),
        ({"kind": "flat", "curriculum": True}, "terrain.curriculum"),
    ],
)
def test_a_terrain_key_of_another_kind_is_a_value_error_naming_it(terrain: dict, named: str) -> None:
    """A terrain key that the chosen kind would ignore is refused, naming the key, from keyword
    arguments, ``env_config`` and the vector env alike (the CLI's `--set` refuses it too)."""
    for kwargs in ({"terrain": terrain}, {"env_config": {"terrain": terrain}}):
        with pytest.raises(ValueError, match=re.escape(named)):
            hyq.HyQEnv(**kwargs)
    with pytest.raises(ValueError, match=re.escape(named)):
        hyq.HyQVectorEnv(num_envs=2, terrain=terrain)
