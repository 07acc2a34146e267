"""``[randomize]`` from Python: keyword arguments and ``env_config`` reach the core alike; the
episode's draws and the step's push are in the info under flat ``randomize.<key>`` keys
(``hyq.randomize_info_schema``) on every step and reset, and in no info when it is off; the
same seed draws the same values in the single env, the vector env (env i seeded s + i), on
every engine of the build and on the command line (``hyq run --json`` and ``--record``). Bad
``[randomize]`` values are ``test_bad_input_cases.py``'s."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

import hyq

RANDOMIZE = {
    "ground_friction": [0.4, 1.2],
    "trunk_added_mass_kg": [-5.0, 5.0],
    "trunk_com_offset_m": [[-0.03, 0.03], [-0.02, 0.02], [0.0, 0.01]],
    "link_mass_scale": [0.9, 1.1],
    "kp_scale": [0.8, 1.2],
    "actuator_delay_substeps": [0, 3],
    "push_interval_s": [0.05, 0.1],
    "push_velocity_xy_mps": [0.5, 0.5],
    "obs_noise": {"joint_angle": 0.01},
}
#: The same table as `hyq run --set` arguments.
SETS = [
    "randomize.ground_friction=[0.4, 1.2]",
    "randomize.trunk_added_mass_kg=[-5.0, 5.0]",
    "randomize.trunk_com_offset_m=[[-0.03, 0.03], [-0.02, 0.02], [0.0, 0.01]]",
    "randomize.link_mass_scale=[0.9, 1.1]",
    "randomize.kp_scale=[0.8, 1.2]",
    "randomize.actuator_delay_substeps=[0, 3]",
    "randomize.push_interval_s=[0.05, 0.1]",
    "randomize.push_velocity_xy_mps=[0.5, 0.5]",
    "randomize.obs_noise.joint_angle=0.01",
]
STEP_KEYS = ("randomize.push_velocity_mps", "randomize.pushes")


def draws(info: dict, i: int | None = None) -> dict:
    """The episode's drawn values of an info (env `i`'s of a vector info)."""
    out = {}
    for key, value in info.items():
        if key.startswith("randomize.") and key not in STEP_KEYS:
            out[key] = np.asarray(value if i is None else value[i]).tolist()
    return out


def test_the_info_holds_the_draws_and_pushes_only_when_randomize_is_on() -> None:
    env = hyq.HyQEnv(randomize=RANDOMIZE)
    schema = hyq.randomize_info_schema(13, 12)
    _, info = env.reset(seed=5)
    assert set(info) == set(hyq.INFO_SCHEMA) | set(schema)
    assert info["randomize.pushes"] == 0
    assert isinstance(info["randomize.actuator_delay_substeps"], int)
    assert info["randomize.link_mass_scale"].shape == (13,)
    assert 0.4 <= info["randomize.ground_friction"] < 1.2
    pushes = 0
    for _ in range(30):
        *_, terminated, truncated, info = env.step(np.zeros(12, dtype=np.float32))
        assert set(info) == set(hyq.INFO_SCHEMA) | set(schema)
        push = info["randomize.push_velocity_mps"]
        if info["randomize.pushes"] > pushes:
            assert abs(np.hypot(push[0], push[1]) - 0.5) < 1e-12, push
            pushes = info["randomize.pushes"]
        else:
            assert np.all(push == 0.0)
        if terminated or truncated:
            break
    assert pushes >= 2, "a push every 0.05-0.1 s"
    _, plain = hyq.HyQEnv().reset(seed=5)
    assert set(plain) == set(hyq.INFO_SCHEMA)


def test_the_same_seed_draws_the_same_on_every_front_and_engine() -> None:
    _, single = hyq.HyQEnv(randomize=RANDOMIZE).reset(seed=11)
    _, from_env_config = hyq.HyQEnv(env_config={"randomize": RANDOMIZE}).reset(seed=11)
    _, single_12 = hyq.HyQEnv(randomize=RANDOMIZE).reset(seed=12)
    vector = hyq.HyQVectorEnv(num_envs=2, randomize=RANDOMIZE)
    _, vinfo = vector.reset(seed=11)
    assert draws(single) == draws(from_env_config) == draws(vinfo, 0)
    assert draws(single_12) == draws(vinfo, 1) != draws(single)
    *_, vinfo = vector.step(np.zeros((2, 12), dtype=np.float32))
    assert vinfo["randomize.pushes"].dtype == np.int64
    assert vinfo["randomize.push_velocity_mps"].shape == (2, 3)
    for backend in hyq.BACKENDS[1:]:
        _, other = hyq.HyQEnv(backend=backend, randomize=RANDOMIZE).reset(seed=11)
        assert draws(other) == draws(single), backend


def test_the_command_line_draws_what_python_draws(hyq_cli: Path, tmp_path: Path) -> None:
    record = tmp_path / "run.jsonl"
    args = [str(hyq_cli), "run", "--policy", "random", "--seed", "11", "--episodes", "2",
            "--json", "--record", str(record), "--set", "task.max_time_steps=12"]
    for s in SETS:
        args += ["--set", s]
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    summaries = [json.loads(line) for line in out.splitlines()]
    env = hyq.HyQEnv(randomize=RANDOMIZE, max_time_steps=12)
    lines = [json.loads(line) for line in record.read_text().splitlines()]
    for episode, summary in enumerate(summaries, start=1):
        _, info = env.reset(seed=11 if episode == 1 else None)
        expected = {k.removeprefix("randomize."): v for k, v in draws(info).items()}
        drawn = dict(summary["randomize"])
        assert drawn.pop("pushes") >= 1
        assert drawn == expected
        steps = [r for r in lines if r["episode"] == episode]
        for rec in steps:
            *_, info = env.step(np.array(rec["action"]))
            assert rec["randomize"]["pushes"] == info["randomize.pushes"]
            assert rec["randomize"]["push_velocity_mps"] == info["randomize.push_velocity_mps"].tolist()
            assert {k: rec["randomize"][k] for k in expected} == expected
        assert steps[-1]["randomize"]["pushes"] == summary["randomize"]["pushes"]
