"""Python inputs that used to be refused wrongly, wrap silently or read without bound: a
``pathlib.Path`` for ``terrain.file`` is taken like ``config_file`` and ``robot`` take one; a
vector env's seeds never wrap past 2**64 (env i is seeded ``seed + i``); ``max_episode_steps``
is checked under its own name; an integer past TOML's 64 bits is named as such; and
``read_policy`` reads only a regular file, up to the Rust reader's cap, naming the file in every
refusal."""

from __future__ import annotations

import json
import os
import pathlib
import struct
import time
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import hyq
from conftest import REPO
from hyq.policy_file import read_policy

WALK = REPO / "assets" / "policies" / "hyq_walk.safetensors"


def test_terrain_file_takes_a_path_object() -> None:
    hills = pathlib.Path(REPO / "assets" / "terrain" / "hills.npy")
    env = gym.make("HyQ-v0", env_config={"terrain": {"kind": "heightfield", "file": hills}})
    obs, _ = env.reset(seed=0)
    assert np.all(np.isfinite(obs))
    env.close()


def test_vector_seeds_never_wrap_past_2_to_the_64() -> None:
    v = gym.make_vec("HyQ-v0", num_envs=3)
    with pytest.raises(ValueError, match=r"seed = 18446744073709551614: env i is seeded seed \+ i"):
        v.reset(seed=2**64 - 2)
    obs, _ = v.reset(seed=2**64 - 3)
    assert np.all(np.isfinite(obs))
    v.close()


@pytest.mark.parametrize(("steps", "error"), [(-1, ValueError), (0, ValueError), (2.5, TypeError)])
def test_max_episode_steps_is_checked_under_its_own_name(steps, error) -> None:
    with pytest.raises(error, match="max_episode_steps") as err:
        gym.make_vec("HyQ-v0", num_envs=2, max_episode_steps=steps)
    assert "task.max_time_steps" not in str(err.value)


def test_an_integer_past_64_bits_is_named_as_such() -> None:
    with pytest.raises(ValueError, match="randomize.actuator_delay_substeps: an integer of 71 bits") as err:
        gym.make("HyQ-v0", env_config={"randomize": {"actuator_delay_substeps": [0, 2**70]}})
    assert "1180591620717411303424" not in str(err.value)


def with_header(tmp_path: Path, name: str, edit) -> Path:  # noqa: ANN001 - a header editor
    data = WALK.read_bytes()
    (n,) = struct.unpack("<Q", data[:8])
    header = json.loads(data[8 : 8 + n])
    edit(header)
    text = json.dumps(header).encode()
    path = tmp_path / name
    path.write_bytes(struct.pack("<Q", len(text)) + text + data[8 + n :])
    return path


def test_read_policy_reads_only_a_regular_file_up_to_the_cap(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="/dev/zero: is not a regular file"):
        read_policy("/dev/zero")
    fifo = tmp_path / "policy.safetensors"
    os.mkfifo(fifo)
    start = time.monotonic()
    with pytest.raises(ValueError, match="is not a regular file"):
        read_policy(fifo)
    assert time.monotonic() - start < 5, "a FIFO is refused at once"
    big = tmp_path / "big.safetensors"
    with open(big, "wb") as f:
        f.truncate(256 * 2**20 + 1)
    with pytest.raises(ValueError, match="big.safetensors: larger than 256 MiB"):
        read_policy(big)


def test_read_policy_names_the_file_for_bad_offsets_and_cut_files(tmp_path: Path) -> None:
    def far(header: dict) -> None:
        header["obs_mean"]["data_offsets"] = [0, 2**62]

    offsets = with_header(tmp_path, "offs.safetensors", far)
    with pytest.raises(ValueError, match=r"offs.safetensors: tensor `obs_mean`"):
        read_policy(offsets)
    cut = tmp_path / "trunc.safetensors"
    cut.write_bytes(WALK.read_bytes()[:-7])
    with pytest.raises(ValueError, match=r"trunc.safetensors: tensor `"):
        read_policy(cut)
