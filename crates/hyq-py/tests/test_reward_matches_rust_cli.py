"""The Python env gives what the Rust command line gives for the same seed and actions:
``hyq run --seed S --record FILE.jsonl`` replayed action by action through ``HyQEnv`` yields
the same rewards, terms, flags and reasons to the bit, and the same observations (rounded to
float32)."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import numpy as np

import hyq

TERMS = ("r_b", "r_n", "r_e", "r_reach", "m_yaw", "m_pitch", "joint_penalty", "fall_penalty")


def test_random_policy_episodes_replay_identically(hyq_cli: Path, tmp_path: Path) -> None:
    record = tmp_path / "run.jsonl"
    sets = ["task.max_time_steps=120", "task.norm_rew_scaling=10", "task.fall_penalty=2"]
    args = [str(hyq_cli), "run", "--policy", "random", "--seed", "17", "--episodes", "3"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args + ["--record", str(record)], check=True, capture_output=True)
    steps = [json.loads(line) for line in record.read_text().splitlines()]
    assert len(steps) > 3

    env = hyq.HyQEnv(
        max_time_steps=120, norm_rew_scaling=10, fall_penalty=2, clip_observations=False
    )
    episode = 0
    for rec in steps:
        if rec["episode"] != episode:
            episode = rec["episode"]
            _, info = env.reset(seed=17 if episode == 1 else None)
            np.testing.assert_array_equal(info["goal"], rec["goal"])
            np.testing.assert_array_equal(info["initial_position"], rec["initial_position"])
        obs, reward, terminated, truncated, info = env.step(np.array(rec["action"]))
        assert info["t"] == rec["t"]
        assert reward == rec["reward"], f"episode {episode} t {rec['t']}"
        for term in TERMS:
            assert info[term] == rec["terms"][term], term
        assert (terminated, truncated) == (rec["terminated"], rec["truncated"])
        assert info["reasons"] == "+".join(rec["reasons"])
        assert info["distance_to_goal"] == rec["distance_to_goal"]
        np.testing.assert_array_equal(obs, np.asarray(rec["obs"], dtype=np.float32))
        np.testing.assert_array_equal(info["joint_targets"], rec["joint_targets"])
    assert episode == 3
