"""``render_mode="rgb_array"`` returns uint8 (H, W, 3) frames from hyq-render that show the
robot, fresh every call, headless; ``gymnasium.wrappers.RecordVideo`` writes a video of an
episode with no display."""

from __future__ import annotations

from pathlib import Path

import gymnasium as gym
import numpy as np

import hyq
from conftest import pose_action


def test_frames_have_the_shape_and_type_of_rgb_array() -> None:
    env = hyq.HyQEnv(render_mode="rgb_array", render_width=320, render_height=240)
    before_reset = env.render()
    assert before_reset.shape == (240, 320, 3) and before_reset.dtype == np.uint8
    env.reset(seed=0)
    frame = env.render()
    assert frame.shape == (240, 320, 3) and frame.dtype == np.uint8
    again = env.render()
    assert not np.shares_memory(frame, again)
    np.testing.assert_array_equal(frame, again)


def test_frames_show_the_robot_and_change_when_it_falls() -> None:
    env = hyq.HyQEnv(render_mode="rgb_array", action={"mode": "absolute"})
    env.reset(seed=0)
    standing = env.render()
    # The camera follows the trunk, so the trunk is drawn around the image centre: that region
    # is not the uniform background of ground and sky.
    h, w, _ = standing.shape
    centre = standing[h // 2 - 20 : h // 2 + 20, w // 2 - 20 : w // 2 + 20].reshape(-1, 3)
    assert len(np.unique(centre, axis=0)) > 10
    action = pose_action(env, (0.9, 0.5, 0.5))  # sits down until the trunk touches the ground
    for _ in range(400):
        *_, terminated, truncated, info = env.step(action)
        if terminated or truncated:
            break
    assert info["fell"]
    fallen = env.render()
    assert np.mean(np.abs(fallen.astype(int) - standing.astype(int))) > 1.0


def test_vector_env_renders_one_frame_per_env() -> None:
    venv = hyq.HyQVectorEnv(num_envs=2, render_mode="rgb_array", render_width=64, render_height=48)
    venv.reset(seed=0)
    frames = venv.render()
    assert len(frames) == 2
    assert all(f.shape == (48, 64, 3) and f.dtype == np.uint8 for f in frames)


def test_record_video_works_headless(tmp_path: Path) -> None:
    env = gym.make("HyQ-v0", render_mode="rgb_array", max_time_steps=30, max_episode_steps=30)
    folder = tmp_path / "videos"  # RecordVideo warns when the folder already exists
    env = gym.wrappers.RecordVideo(env, str(folder), episode_trigger=lambda e: True)
    env.reset(seed=0)
    done = False
    while not done:
        _, _, terminated, truncated, _ = env.step(np.zeros(12, dtype=np.float32))
        done = terminated or truncated
    env.close()
    videos = list(folder.glob("*.mp4"))
    assert len(videos) == 1 and videos[0].stat().st_size > 1000
