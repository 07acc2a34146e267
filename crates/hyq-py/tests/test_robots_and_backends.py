"""Every robot and every built backend through the Gymnasium front: ``robot=`` takes a bundled
robot's name or a profile path, ``ANYmalC-v0`` is registered, the spaces, row names and table
follow the robot (HyQ's 39 and 12 come from its model), Gymnasium's and Stable-Baselines3's
checkers pass on ANYmal C, a third robot (an 8-joint, 2-foot fixture with its own joint names)
runs single and vectorised, and ``backend=`` picks an engine this build has, runs it
bit-identically to the same engine's vector env, and otherwise is a ``ValueError`` naming the
build option."""

from __future__ import annotations

import types
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import hyq
from conftest import REPO
from sb3_without_torch import sb3  # noqa: F401  (the fixture)


def eight_joint_profile(tmp_path: Path) -> Path:
    """hyq-env's fixture robot: ANYmal C with its HAA joints fixed, next to its profile."""
    urdf = (REPO / "assets/anymal_c/anymal_c.urdf").read_text()
    for leg in ("LF", "LH", "RF", "RH"):
        revolute = f'<joint name="{leg}_HAA" type="revolute">'
        assert revolute in urdf
        urdf = urdf.replace(revolute, f'<joint name="{leg}_HAA" type="fixed">')
    (tmp_path / "anymal_c_8dof.urdf").write_text(urdf)
    profile = tmp_path / "profile.toml"
    fixture = REPO / "crates/hyq-env/tests/fixtures/anymal_c_8dof/profile.toml"
    profile.write_text(fixture.read_text())
    return profile


def test_every_bundled_robot_but_the_default_has_its_id() -> None:
    assert hyq.ROBOTS[0] == "hyq"
    assert set(hyq.ROBOT_IDS) == set(hyq.ROBOTS[1:])
    env = gym.make("ANYmalC-v0")
    assert env.unwrapped.robot == "anymal_c"
    assert env.spec.max_episode_steps == hyq.MAX_EPISODE_STEPS
    assert gym.make("HyQ-v0").unwrapped.robot == "hyq"
    envs = gym.make_vec("ANYmalC-v0", num_envs=2)
    assert envs.robot == "anymal_c"
    # Go1 comes from an MJCF file, through the same resolver.
    assert gym.make("Go1-v0").unwrapped.robot == "go1"
    assert len(hyq.HyQEnv(robot="go1").joint_names) == 12


def test_spaces_and_rows_come_from_the_model() -> None:
    hyq_env = hyq.HyQEnv()
    anymal = hyq.HyQEnv(robot="anymal_c")
    # HyQ's sizes are its model's: 2 rows per joint, one flag per foot, 12 trunk rows.
    assert hyq_env.observation_space.shape == (2 * 12 + 4 + 12 - 1,)
    assert len(hyq_env.joint_names) == 12
    assert anymal.observation_space.shape == (39,)
    assert anymal.joint_names[0] == "lf_haa"
    assert [r.name for r in anymal.observation_table] == anymal.observation_names
    # The trunk's declared bounds are each robot's: ANYmal C's profile has none, so the spec's.
    assert hyq.observation_table("anymal_c")[38].high == hyq.OBSERVATION_TABLE[38].high
    # Joint-angle rows carry each robot's limits.
    assert anymal.observation_table[1].high == pytest.approx(np.pi / 2)
    assert hyq.OBSERVATION_TABLE[1].high != anymal.observation_table[1].high
    assert "ANYmalC-v0" in hyq.HyQEnv.__doc__


@pytest.mark.parametrize("clip", [False, True])
def test_gymnasium_check_env_is_silent_on_anymal_c(clip: bool) -> None:
    env = gym.make("ANYmalC-v0", clip_observations=clip)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    assert [str(w.message) for w in caught] == []


def test_sb3_check_env_is_silent_on_anymal_c(sb3: types.SimpleNamespace) -> None:
    env = hyq.HyQEnv(robot="anymal_c")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sb3.check_env(env, warn=True)
    assert [str(w.message) for w in caught] == []


def test_a_third_robot_runs_from_its_profile_path(tmp_path: Path) -> None:
    profile = eight_joint_profile(tmp_path)
    env = gym.make("HyQ-v0", robot=str(profile))
    assert env.unwrapped.robot == "anymal_c_8dof"
    assert env.observation_space.shape == (29,)
    assert env.action_space.shape == (8,)
    names = env.unwrapped.observation_names
    assert names[0] == "fl_hip_angle" and "hind_right_contact_flag" in names
    table = env.unwrapped.observation_table
    assert (table[-1].low, table[-1].high) == (0.0, 0.8)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    assert [str(w.message) for w in caught] == []

    # The vector env gives what single envs give, on this robot too.
    envs = gym.make_vec("HyQ-v0", num_envs=2, robot=profile)
    single = hyq.HyQEnv(robot=profile)
    obs, _ = envs.reset(seed=5)
    first, _ = single.reset(seed=5)
    np.testing.assert_array_equal(obs[0], first)
    rng = np.random.default_rng(0)
    for _ in range(20):
        actions = rng.uniform(-1, 1, size=(2, 8)).astype(np.float32)
        obs, rewards, terminated, truncated, _ = envs.step(actions)
        o, r, term, trunc, _ = single.step(actions[0])
        np.testing.assert_array_equal(obs[0], o)
        assert rewards[0] == r
        if term or trunc:
            break


def test_an_mjcf_file_alone_runs_with_its_profile_drafted(tmp_path: Path) -> None:
    """Go1's MJCF file (a ``home`` keyframe, a ``<position>`` actuator on every joint) runs
    without a profile, drafted in memory as ``hyq robot init`` drafts it; it stands where the
    bundled profile says. Without a keyframe it is a ValueError pointing at ``hyq robot init``."""
    mjcf = REPO / "assets/go1/go1.xml"
    env = hyq.HyQEnv(robot=mjcf)
    assert env.robot == "go1"
    assert env.joint_names == hyq.HyQEnv(robot="go1").joint_names
    _, info = env.reset(seed=0)
    _, bundled = hyq.HyQEnv(robot="go1").reset(seed=0)
    # The goal sits at the standing height: the settle run's, within 1 mm of the profile's.
    assert abs(info["goal"][2] - bundled["goal"][2]) < 1e-3
    text = mjcf.read_text()
    start, end = text.index("<keyframe>"), text.index("</keyframe>") + len("</keyframe>")
    no_key = tmp_path / "go1-no-keyframe.xml"
    no_key.write_text(text[:start] + text[end:])
    with pytest.raises(ValueError, match="no keyframe.*hyq robot init"):
        hyq.HyQEnv(robot=no_key)


def test_bad_robots_are_value_errors_naming_them(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match='robot: unknown robot "anymal".*hyq, anymal_c'):
        hyq.HyQEnv(robot="anymal")
    with pytest.raises(ValueError, match="no/such/profile.toml"):
        gym.make_vec("HyQ-v0", num_envs=2, robot="no/such/profile.toml")
    bad = tmp_path / "profile.toml"
    bad.write_text('name = "x"\nurdf = "x.urdf"\ncolour = "red"\n')
    with pytest.raises(ValueError, match="colour"):
        hyq.HyQEnv(robot=bad)
    with pytest.raises(TypeError, match="robot = 3"):
        hyq.HyQEnv(robot=3)


def test_the_default_backend_is_rapier_and_others_are_named_build_options() -> None:
    assert hyq.BACKENDS[0] == "rapier"
    assert set(hyq.BACKENDS) <= {"rapier", "mujoco", "dart"}
    with pytest.raises(ValueError, match="unknown backend"):
        hyq.HyQEnv(backend="bullet")
    for name in ("mujoco", "dart"):
        if name not in hyq.BACKENDS:
            with pytest.raises(ValueError, match=f"--features {name}"):
                gym.make("HyQ-v0", backend=name)
            with pytest.raises(ValueError, match=f"--features {name}"):
                gym.make_vec("HyQ-v0", num_envs=2, backend=name)


@pytest.mark.parametrize("robot", ["hyq", "anymal_c"])
def test_every_built_backend_runs_and_matches_its_vector_env(robot: str) -> None:
    # rapier is always built; the CI build has MuJoCo too (`cargo xtask test` builds the
    # package with every engine it finds).
    for backend in hyq.BACKENDS:
        env = hyq.HyQEnv(robot=robot, backend=backend)
        envs = gym.make_vec("HyQ-v0", num_envs=2, robot=robot, backend=backend)
        obs, _ = env.reset(seed=3)
        vobs, _ = envs.reset(seed=3)
        np.testing.assert_array_equal(vobs[0], obs)
        rng = np.random.default_rng(1)
        for _ in range(30):
            a = rng.uniform(-1, 1, size=(2, env.action_space.shape[0])).astype(np.float32)
            o, r, term, trunc, info = env.step(a[0])
            vo, vr, _, _, _ = envs.step(a)
            np.testing.assert_array_equal(vo[0], o)
            assert vr[0] == r
            assert np.all(np.isfinite(o))
            if term or trunc:
                break
