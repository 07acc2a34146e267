"""The velocity-command task from Python: ``HyQ-Velocity-v0`` and ``ANYmalC-Velocity-v0`` are
the env with ``task.kind = "velocity"``; its info holds the command and every term; a fixed
command set through ``env_config``'s dotted keys holds; ``task.kind`` in ``env_config`` is the
same env; and the spec's ids have none of the task's keys."""

import gymnasium as gym
import numpy as np
import pytest

import hyq

TERMS = (
    "tracking_lin_vel",
    "tracking_ang_vel",
    "lin_vel_z",
    "ang_vel_xy",
    "orientation",
    "torques",
    "torques_abs",
    "joint_acc",
    "action_rate",
    "feet_air_time",
    "foot_slip",
    "stand_still",
    "joint_limits",
    "termination",
)


@pytest.mark.parametrize("env_id,robot", [("HyQ-Velocity-v0", "hyq"), ("ANYmalC-Velocity-v0", "anymal_c")])
def test_velocity_ids_pose_the_velocity_task(env_id, robot):
    env = gym.make(env_id, env_config={"command.lin_vel_x": [0.5, 0.5], "command.lin_vel_y": [0, 0],
                                       "command.ang_vel_yaw": [0, 0]})
    obs, info = env.reset(seed=0)
    assert env.unwrapped.robot == robot
    n = env.action_space.shape[0]
    spec_rows = 2 * n + 4 + 1 + 10
    assert obs.shape == (spec_rows + 12 + 2 * n,)
    np.testing.assert_array_equal(info["velocity.command"], [0.5, 0.0, 0.0])
    np.testing.assert_array_equal(obs[spec_rows + 9 : spec_rows + 12], [0.5, 0.0, 0.0])
    for _ in range(20):
        obs, reward, terminated, truncated, info = env.step(np.zeros(n, dtype=np.float32))
        np.testing.assert_array_equal(info["velocity.command"], [0.5, 0.0, 0.0])
        assert reward == info["velocity.reward"]
        for term in TERMS:
            assert np.isfinite(info[f"velocity.{term}"]), term
    env.close()


def test_task_kind_in_env_config_is_the_registered_env():
    a = gym.make("HyQ-v0", env_config={"task.kind": "velocity"})
    b = gym.make("HyQ-Velocity-v0")
    oa, _ = a.reset(seed=3)
    ob, _ = b.reset(seed=3)
    np.testing.assert_array_equal(oa, ob)
    act = np.zeros(a.action_space.shape, dtype=np.float32)
    for _ in range(10):
        ra = a.step(act)[1]
        rb = b.step(act)[1]
        assert ra == rb


def test_the_spec_ids_have_no_velocity_keys():
    env = gym.make("HyQ-v0")
    _, info = env.reset(seed=0)
    assert not any(k.startswith("velocity.") for k in info)
    assert hyq.VELOCITY_IDS == {"hyq": "HyQ-Velocity-v0", "anymal_c": "ANYmalC-Velocity-v0"}


def test_a_bad_task_kind_is_a_value_error_naming_the_key():
    with pytest.raises(ValueError, match="task.kind"):
        gym.make("HyQ-v0", env_config={"task.kind": "walk"})
