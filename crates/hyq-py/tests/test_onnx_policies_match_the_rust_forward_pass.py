"""Every committed policy ships an ONNX twin, and onnxruntime running that twin gives the actions
the Rust forward pass gives (`hyq run --policy mlp:FILE`, recorded step by step) within 1e-5 on
the observations of a real episode; an ONNX file whose layout is not the robot's is refused by
name."""

from __future__ import annotations

import json
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import onnx
import pytest

from conftest import REPO
from hyq.policy_file import OnnxPolicy, check_onnx_layout, read_policy, to_onnx, action_bounds

POLICIES = sorted((REPO / "assets" / "policies").glob("*.safetensors"))
TOLERANCE = 1e-5


def test_there_are_committed_policies_and_each_has_its_onnx_twin() -> None:
    assert len(POLICIES) >= 1
    for policy in POLICIES:
        twin = policy.with_suffix(".onnx")
        assert twin.is_file(), f"{policy.name} has no ONNX twin {twin.name}"
        props = {p.key: p.value for p in onnx.load(str(twin)).metadata_props}
        # The twin was made from this very file, not from an older one of the same name.
        assert props["source_sha256"] == read_policy(policy).sha256, f"{twin.name} is stale"


def recorded_episode(hyq_cli: Path, policy: Path, robot: str, tmp_path: Path) -> list[dict]:
    record = tmp_path / f"{policy.stem}.jsonl"
    subprocess.run(
        [str(hyq_cli), "run", "--robot", robot, "--policy", f"mlp:{policy}", "--episodes", "1",
         "--seed", "3", "--set", "reset.joint_noise_rad=0.05", "--set", "reset.yaw_noise_deg=5",
         "--set", "task.max_time_steps=300", "--record", str(record)],
        check=True, capture_output=True,
    )
    return [json.loads(line) for line in record.read_text().splitlines() if line.strip()]


@pytest.mark.parametrize("policy", POLICIES, ids=[p.stem for p in POLICIES])
def test_onnxruntime_matches_the_rust_forward_pass(hyq_cli: Path, policy: Path, tmp_path: Path) -> None:
    robot = read_policy(policy).robot
    steps = recorded_episode(hyq_cli, policy, robot, tmp_path)
    assert len(steps) >= 100, f"the episode ended after {len(steps)} steps"
    # Step t's action was computed from the observation after step t - 1.
    obs = np.array([s["obs"] for s in steps[:-1]], dtype=np.float32)
    rust = np.array([s["action"] for s in steps[1:]], dtype=np.float64)
    # Checked against the environment `hyq run` replayed it in: the file's own (a velocity-task
    # policy's observation is the task's 75 rows, not the goal task's 39).
    trained = {key: tomllib.loads(f"v = {value}")["v"] for key, value in read_policy(policy).env_config.items()}
    ours = OnnxPolicy(policy.with_suffix(".onnx"), robot=robot, env_config=trained)(obs).astype(np.float64)
    assert ours.shape == rust.shape
    worst = float(np.max(np.abs(ours - rust)))
    assert worst <= TOLERANCE, f"{policy.name}: largest difference {worst:.3g}"
    # Most values lie inside the action space, so the network is compared, not only the clip.
    low, high = action_bounds(read_policy(policy))
    inside = (rust > low) & (rust < high)
    assert inside.mean() > 0.5, f"only {inside.mean():.0%} of the actions are unclipped"


def twin_of_walk() -> onnx.ModelProto:
    policy = read_policy(REPO / "assets" / "policies" / "hyq_walk.safetensors")
    return to_onnx(policy, *action_bounds(policy))


def with_prop(model: onnx.ModelProto, key: str, value: str | None) -> onnx.ModelProto:
    props = {p.key: p.value for p in model.metadata_props}
    if value is None:
        props.pop(key)
    else:
        props[key] = value
    del model.metadata_props[:]
    onnx.helper.set_model_props(model, props)
    return model


def test_another_robots_layout_is_refused_by_name() -> None:
    with pytest.raises(ValueError, match="trained for robot 'hyq', the environment runs 'anymal_c'"):
        check_onnx_layout(twin_of_walk(), "anymal_c", "hyq_walk.onnx")


def test_observation_rows_in_another_order_are_refused_naming_the_row() -> None:
    model = twin_of_walk()
    rows = json.loads({p.key: p.value for p in model.metadata_props}["observation"])
    rows[3], rows[4] = rows[4], rows[3]
    with pytest.raises(ValueError, match=f"observation value 3 was '{rows[3]}' in training"):
        check_onnx_layout(with_prop(model, "observation", json.dumps(rows)), "hyq", "x.onnx")


def test_another_joint_order_and_foreign_files_are_refused() -> None:
    model = twin_of_walk()
    joints = json.loads({p.key: p.value for p in model.metadata_props}["action"])
    with pytest.raises(ValueError, match="trained on 11 action values, the environment has 12"):
        check_onnx_layout(with_prop(model, "action", json.dumps(joints[:11])), "hyq", "x.onnx")
    with pytest.raises(ValueError, match="x.onnx: metadata `format` is None"):
        check_onnx_layout(with_prop(twin_of_walk(), "format", None), "hyq", "x.onnx")


def test_a_file_that_is_not_a_policy_is_refused_naming_it(tmp_path: Path) -> None:
    bogus = tmp_path / "bogus.safetensors"
    bogus.write_bytes(b"\x02\x00\x00\x00\x00\x00\x00\x00{}")
    with pytest.raises(ValueError, match="bogus.safetensors: metadata `format` is None"):
        read_policy(bogus)


ROUGH_TWIN = REPO / "assets" / "policies" / "hyq_walk_rough.onnx"


@pytest.mark.parametrize("scan", [
    {"height_scan_x_m": [-0.6, 1.0]},
    # The same 17 x 11 rows, names and count, over twice the extent.
    {"height_scan_x_m": [-1.6, 1.6], "height_scan_y_m": [-1.0, 1.0], "height_scan_spacing_m": 0.2},
    {"height_scan_y_m": [-0.4, 0.6]},
], ids=["x_m", "same_rows_twice_as_wide", "y_m"])
def test_a_height_scan_of_another_geometry_in_the_callers_env_is_refused(scan: dict) -> None:
    """Given the caller's ``env_config``, the check builds the caller's environment, so a height
    scan with the rows and names the file was trained on but read at other points is refused
    naming the key (the file's own ``env_config`` alone cannot see it: it was accepted)."""
    model = onnx.load(str(ROUGH_TWIN))
    caller = {"observation": {"extra": ["height_scan"], **scan}}
    key = next(iter(scan))
    with pytest.raises(ValueError, match=rf"hyq_walk_rough.onnx: trained with observation\.{key} = .*, "
                                         r"the environment has .*: the same scan rows would read"):
        check_onnx_layout(model, "hyq", "hyq_walk_rough.onnx", env_config=caller)
    with pytest.raises(ValueError, match=rf"observation\.{key}"):
        OnnxPolicy(ROUGH_TWIN, robot="hyq", env_config=caller)


def test_the_callers_env_with_the_trained_scan_or_other_rows_is_checked_as_before() -> None:
    """The trained geometry in the caller's env is accepted (also without any `env_config`, the
    file's own); the caller's env without the scan is refused by its row count."""
    model = onnx.load(str(ROUGH_TWIN))
    props = check_onnx_layout(model, "hyq", "hyq_walk_rough.onnx",
                              env_config={"observation": {"extra": ["height_scan"]},
                                          "terrain": {"kind": "rough"}})
    assert props["robot"] == "hyq"
    assert check_onnx_layout(model, "hyq", "hyq_walk_rough.onnx")["robot"] == "hyq"
    with pytest.raises(ValueError, match="trained on 226 observation values, the environment has 39"):
        check_onnx_layout(model, "hyq", "hyq_walk_rough.onnx", env_config={})
    # A policy that reads no scan is checked against the caller's rows as before.
    assert check_onnx_layout(twin_of_walk(), "hyq", "x.onnx", env_config={})["robot"] == "hyq"
