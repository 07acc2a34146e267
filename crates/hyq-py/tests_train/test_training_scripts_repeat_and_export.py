"""The training examples run end to end on a tiny budget: the same seed gives the same run to
the bit, the export writes a policy file and its ONNX twin whose actions are the trainer's own
deterministic actions (within 1e-5), and the exporter refuses a run without a model or a model
of another robot in one line."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import torch

from conftest import EXAMPLES
from hyq.policy_file import OnnxPolicy, read_policy

ENV = json.dumps({"max_time_steps": 40})
SB3 = ["--backend", "rapier", "--steps", "1024", "--envs", "4", "--checkpoint-every", "512",
       "--ppo", json.dumps({"n_steps": 128, "batch_size": 256}), "--env", ENV]
RSL = ["--backend", "rapier", "--iterations", "2", "--checkpoint-every", "1", "--envs", "4",
       "--cfg", json.dumps({"num_steps_per_env": 32}), "--env", ENV]


def script(name: str, *args: object) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)],
                          capture_output=True, text=True)


def train(name: str, args: list[str], out: Path) -> Path:
    done = script(name, *args, "--out", out)
    assert done.returncode == 0, done.stderr[-3000:]
    return out


def last_model(run: Path) -> Path:
    """The run's checkpoint model_N.pt with the highest N."""
    return max(run.glob("model_*.pt"), key=lambda p: int(p.stem[6:]))


def observations(n: int = 64) -> np.ndarray:
    import hyq

    env = hyq.HyQEnv(action={"mode": "offset"})
    obs, _ = env.reset(seed=5)
    rows = []
    rng = np.random.default_rng(0)
    for _ in range(n):
        rows.append(obs)
        obs, *_ = env.step(rng.uniform(-0.3, 0.3, 12).astype(np.float32))
    return np.array(rows, dtype=np.float32)


@pytest.fixture(scope="module")
def sb3_runs(tmp_path_factory) -> tuple[Path, Path]:
    root = tmp_path_factory.mktemp("sb3")
    return train("train_sb3_ppo.py", SB3, root / "a"), train("train_sb3_ppo.py", SB3, root / "b")


@pytest.fixture(scope="module")
def rsl_runs(tmp_path_factory) -> tuple[Path, Path]:
    root = tmp_path_factory.mktemp("rsl")
    return train("train_rsl_rl.py", RSL, root / "a"), train("train_rsl_rl.py", RSL, root / "b")


def test_sb3_runs_repeat_to_the_bit(sb3_runs) -> None:
    a, b = sb3_runs
    assert (a / "evals.csv").read_text() == (b / "evals.csv").read_text()
    from stable_baselines3 import PPO

    pa, pb = (PPO.load(r / "model.zip", device="cpu").policy.state_dict() for r in (a, b))
    assert all(torch.equal(pa[k], pb[k]) for k in pa)


def test_rsl_rl_runs_repeat_to_the_bit(rsl_runs) -> None:
    a, b = rsl_runs
    assert (a / "evals.csv").read_text() == (b / "evals.csv").read_text()
    ma, mb = (torch.load(sorted(r.glob("model_*.pt"))[-1], weights_only=False)["actor_state_dict"]
              for r in (a, b))
    assert all(torch.equal(ma[k], mb[k]) for k in ma)


def test_the_sb3_export_and_its_onnx_twin_act_as_sb3(sb3_runs, tmp_path) -> None:
    from stable_baselines3 import PPO
    from stable_baselines3.common.vec_env import VecNormalize
    import pickle

    run = sb3_runs[0]
    out = tmp_path / "sb3.safetensors"
    done = script("export_policy.py", "--run", run, "--out", out, "--onnx")
    assert done.returncode == 0, done.stderr
    assert read_policy(out).robot == "hyq"
    model = PPO.load(run / "model.zip", device="cpu")
    with open(run / "vecnormalize.pkl", "rb") as f:
        norm: VecNormalize = pickle.load(f)
    obs = observations()
    theirs, _ = model.predict(norm.normalize_obs(obs), deterministic=True)
    ours = OnnxPolicy(out.with_suffix(".onnx"), robot="hyq")(obs)
    assert np.max(np.abs(ours - np.clip(theirs, -1, 1))) <= 1e-5


def test_the_rsl_rl_export_and_its_onnx_twin_act_as_rsl_rl(rsl_runs, tmp_path) -> None:
    run = rsl_runs[0]
    out = tmp_path / "rsl.safetensors"
    done = script("export_policy.py", "--run", run, "--out", out, "--onnx")
    assert done.returncode == 0, done.stderr
    from rsl_rl.models import MLPModel
    from tensordict import TensorDict

    config = json.loads((run / "config.json").read_text())
    obs = observations()
    group = TensorDict({"policy": torch.as_tensor(obs)}, batch_size=[len(obs)])
    actor_cfg = {k: v for k, v in config["rsl_rl"]["actor"].items() if k != "class_name"}
    actor = MLPModel(group, config["rsl_rl"]["obs_groups"], "actor", 12, **actor_cfg)
    saved = torch.load(last_model(run), weights_only=False)
    actor.load_state_dict(saved["actor_state_dict"])
    actor.eval()
    with torch.inference_mode():
        theirs = actor(group).numpy()
    ours = OnnxPolicy(out.with_suffix(".onnx"), robot="hyq")(obs)
    assert np.max(np.abs(ours - np.clip(theirs, -1, 1))) <= 1e-5


def test_the_training_episode_length_is_recorded_and_not_applied(rsl_runs, tmp_path) -> None:
    """The runs train on 40-step episodes (ENV): the file's training_env_config says so, and
    its env_config, which replay applies, leaves the task's own episode length."""
    out = tmp_path / "rsl.safetensors"
    done = script("export_policy.py", "--run", rsl_runs[0], "--out", out)
    assert done.returncode == 0, done.stderr
    metadata = read_policy(out).metadata
    assert json.loads(metadata["training_env_config"])["task.max_time_steps"] == "40"
    applied = json.loads(metadata["env_config"])
    assert "task.max_time_steps" not in applied, applied
    assert applied["action.mode"] == '"offset"', applied


def one_line_error(done: subprocess.CompletedProcess) -> str:
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    return lines[0]


def test_a_run_without_a_model_is_refused_in_one_line(tmp_path, sb3_runs) -> None:
    run = tmp_path / "empty"
    run.mkdir()
    (run / "config.json").write_text((sb3_runs[0] / "config.json").read_text())
    line = one_line_error(script("export_policy.py", "--run", run, "--out", tmp_path / "x.safetensors"))
    assert "model.zip: no model file" in line


@pytest.mark.parametrize("which", ["sb3", "rsl"])
def test_another_robots_model_is_refused_in_one_line(which, tmp_path, sb3_runs, rsl_runs) -> None:
    source = (sb3_runs if which == "sb3" else rsl_runs)[0]
    run = tmp_path / "run"
    run.mkdir()
    for f in source.iterdir():
        if f.is_file():
            (run / f.name).write_bytes(f.read_bytes())
    config = json.loads((run / "config.json").read_text())
    config["robot"] = "anymal_c"
    (run / "config.json").write_text(json.dumps(config))
    line = one_line_error(script("export_policy.py", "--run", run, "--out", tmp_path / "x.safetensors"))
    assert "'hyq'" in line and "'anymal_c'" in line


def test_a_resumed_run_continues_the_checkpoint_and_names_both_commands(rsl_runs, tmp_path) -> None:
    source = rsl_runs[0]
    last = last_model(source)
    out = train("train_rsl_rl.py", [*RSL[:3], "1", *RSL[4:], "--resume", last], tmp_path / "resumed")
    first = torch.load(last, weights_only=False)
    resumed = torch.load(last_model(out), weights_only=False)
    # The observation statistics go on from the checkpoint's (a fresh start's one iteration
    # would have counted fewer samples than the checkpoint's two), and the networks moved on.
    count = "obs_normalizer.count"
    assert resumed["actor_state_dict"][count] > first["actor_state_dict"][count]
    weights = "actor_state_dict"
    assert any(not torch.equal(first[weights][k], resumed[weights][k]) for k in first[weights])
    # The env steps behind the new checkpoint count the resumed one's.
    per_iteration = 32 * 4
    assert first["infos"]["env_steps"] == 2 * per_iteration
    assert resumed["infos"]["env_steps"] == first["infos"]["env_steps"] + per_iteration
    config = json.loads((out / "config.json").read_text())
    assert config["resume"] == str(last)
    before = json.loads((source / "config.json").read_text())["command"]
    assert config["command"].startswith(before + " && ") and "--resume" in config["command"]


def test_resuming_from_a_missing_checkpoint_is_refused_in_one_line(tmp_path) -> None:
    done = script("train_rsl_rl.py", *RSL, "--resume", tmp_path / "none.pt", "--out", tmp_path / "o")
    assert done.returncode != 0
    assert done.stderr.strip().splitlines()[-1] == f"error: --resume {tmp_path / 'none.pt'}: no such checkpoint file"


def test_action_noise_sets_a_resumed_policys_noise_and_leaves_its_mean(rsl_runs) -> None:
    """--action-noise after --resume: every action's deviation is the given one, in rsl_rl's
    "scalar" and "log" forms, and the policy's mean actions are the checkpoint's."""
    import copy

    import train_rsl_rl
    from hyq.rsl_rl import HyQRslRlVecEnv
    from rsl_rl.runners import OnPolicyRunner
    from tensordict import TensorDict

    last = last_model(rsl_runs[0])
    obs = TensorDict({"policy": torch.as_tensor(observations(16))}, batch_size=[16])
    for std_type in ("scalar", "log"):
        cfg = copy.deepcopy(train_rsl_rl.TRAIN_CFG)
        cfg["num_steps_per_env"] = 32
        cfg["actor"]["distribution_cfg"]["std_type"] = std_type
        env = HyQRslRlVecEnv(num_envs=2, seed=0, robot="hyq", backend="rapier", max_time_steps=40)
        runner = OnPolicyRunner(env, cfg, log_dir=None, device="cpu")
        if std_type == "scalar":
            train_rsl_rl.resume(runner, last, env.observation_names, per_iteration=64)
        policy = runner.alg.get_policy()
        policy.eval()
        with torch.inference_mode():
            before = policy(obs).clone()
        train_rsl_rl.set_action_noise(runner, 0.007)
        with torch.inference_mode():
            assert torch.equal(policy(obs), before)
            runner.alg.actor(obs, stochastic_output=True)
            std = runner.alg.actor.output_std
        assert torch.allclose(std, torch.full_like(std, 0.007)), std_type
        env.close()


def test_a_bad_action_noise_is_refused_in_one_line(tmp_path) -> None:
    for bad in ("0", "-0.1", "nan", "inf"):
        done = script("train_rsl_rl.py", *RSL, "--action-noise", bad, "--out", tmp_path / bad)
        assert done.returncode != 0
        assert done.stderr.strip().splitlines()[-1] == (
            f"error: --action-noise {float(bad)}: must be a finite number above 0")
        assert not (tmp_path / bad).exists()


def test_the_rough_recipe_trains_and_exports_its_height_scan_rows(tmp_path) -> None:
    run = train("train_rsl_rl.py", [*RSL, "--recipe", "walk_rough"], tmp_path / "rough")
    out = tmp_path / "rough.safetensors"
    done = script("export_policy.py", "--run", run, "--out", out, "--onnx")
    assert done.returncode == 0, done.stderr
    metadata = read_policy(out).metadata
    assert len(json.loads(metadata["observation"])) == 39 + 17 * 11
    # The height scan is part of what the policy needs; the ground and its curriculum are a
    # training condition, recorded only.
    applied = json.loads(metadata["env_config"])
    trained = json.loads(metadata["training_env_config"])
    assert "height_scan" in applied["observation.extra"], applied
    assert not any(k.startswith("terrain.") for k in applied), applied
    assert "rough" in trained["terrain.kind"] and trained["terrain.curriculum"] == "true", trained


def test_a_walk_checkpoint_widened_for_the_height_scan_acts_as_it_did(rsl_runs, tmp_path) -> None:
    """--resume of a checkpoint with the spec's 39 rows into the rough recipe (39 rows, then the
    height scan's 187): the widened policy's actions are the checkpoint's for every height scan,
    so the fine-tuning starts from the flat walker exactly."""
    import copy

    import recipes
    import train_rsl_rl
    from hyq.rsl_rl import HyQRslRlVecEnv
    from rsl_rl.runners import OnPolicyRunner
    from tensordict import TensorDict

    last = last_model(rsl_runs[0])
    cfg = copy.deepcopy(train_rsl_rl.TRAIN_CFG)
    cfg["num_steps_per_env"] = 32
    env = HyQRslRlVecEnv(num_envs=2, seed=0, robot="hyq", backend="rapier",
                         **recipes.merge(recipes.WALK_ROUGH_ENV, {"max_time_steps": 40}))
    runner = OnPolicyRunner(env, cfg, log_dir=None, device="cpu")
    train_rsl_rl.resume(runner, last, env.observation_names, per_iteration=64)
    widened = runner.alg.get_policy()
    widened.eval()
    saved = torch.load(last, weights_only=False)
    from rsl_rl.models import MLPModel

    flat_obs = torch.as_tensor(observations(16))
    group = TensorDict({"policy": flat_obs}, batch_size=[16])
    actor_cfg = {k: v for k, v in cfg["actor"].items() if k != "class_name"}
    flat = MLPModel(group, cfg["obs_groups"], "actor", 12, **actor_cfg)
    flat.load_state_dict(saved["actor_state_dict"])
    flat.eval()
    scans = torch.as_tensor(np.random.default_rng(1).uniform(-1, 1, (16, 187)), dtype=torch.float32)
    wide = TensorDict({"policy": torch.cat([flat_obs, scans], 1)}, batch_size=[16])
    with torch.inference_mode():
        assert torch.equal(widened(wide), flat(group))
    env.close()


def test_backends_trains_on_a_mix_and_evaluates_on_every_engine(tmp_path: Path) -> None:
    import hyq

    engines = list(hyq.BACKENDS)
    args = ["--backends", ",".join(engines), *RSL[2:]]
    out = train("train_rsl_rl.py", args, tmp_path / "mix")
    config = json.loads((out / "config.json").read_text())
    assert config["backends"] == engines and config["backend"] == ",".join(engines)
    result = json.loads((out / "eval.json").read_text())
    header = (out / "evals.csv").read_text().splitlines()[0].split(",")
    if len(engines) > 1:
        assert list(result["per_engine"]) == engines
        assert result["worst_reach_rate"] == min(r["reach_rate"] for r in result["per_engine"].values())
        assert len(result["episodes"]) == sum(len(r["episodes"]) for r in result["per_engine"].values())
        assert [f"{e}_reach_rate" for e in engines] == [h for h in header if h.endswith("_reach_rate")]
    for name in ("train_rsl_rl.py", "train_sb3_ppo.py"):
        done = script(name, "--backends", "rapier,bullet", "--out", tmp_path / "never")
        assert done.returncode != 0 and "--backends rapier,bullet" in done.stderr
        assert len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert not (tmp_path / "never").exists()


def test_an_eps_curriculum_changes_the_training_cube_and_repeats_to_the_bit(tmp_path) -> None:
    """--eps-curriculum 20:0.1:512:2 on 4 envs × 128 steps: the cube is 20 m for the first
    rollout (every training episode starts inside it and is reached at its first step) and
    0.1 m from the second on, the checkpoints judged on the recipe's 0.1 m all along; the same
    command gives the same run to the bit."""
    args = [*SB3, "--recipe", "reach", "--eps-curriculum", "20:0.1:512:2"]
    a, b = (train("train_sb3_ppo.py", args, tmp_path / n) for n in "ab")
    result = json.loads((a / "eval.json").read_text())
    assert result["eps_curriculum_changes"] == [[0, 20.0], [512, 0.1]]
    config = json.loads((a / "config.json").read_text())
    assert config["eps_curriculum"] == {"start": 20.0, "end": 0.1, "steps": 512, "stages": 2}
    assert config["env"]["accepted_error"] == 0.1 and config["eval_env"]["accepted_error"] == 0.1
    first = (a / "progress.csv").read_text().splitlines()[:2]
    row = dict(zip(first[0].split(","), first[1].split(",")))
    assert (row["env_steps"], row["episodes"], row["reach_rate"], row["mean_length"]) == ("512", "512", "1", "1")
    # Judged on the 0.1 m cube, the deterministic policy reaches in none of its 40 steps.
    assert result["reach_rate"] == 0.0
    assert (a / "evals.csv").read_text() == (b / "evals.csv").read_text()
    from stable_baselines3 import PPO

    pa, pb = (PPO.load(r / "model.zip", device="cpu").policy.state_dict() for r in (a, b))
    assert all(torch.equal(pa[k], pb[k]) for k in pa)


def test_a_run_without_a_curriculum_records_none(sb3_runs) -> None:
    config = json.loads((sb3_runs[0] / "config.json").read_text())
    assert "eps_curriculum" not in config
    assert "eps_curriculum_changes" not in json.loads((sb3_runs[0] / "eval.json").read_text())


def test_the_go1_recipe_trains_on_the_three_engines_with_its_own_settings(tmp_path: Path) -> None:
    import hyq

    args = ["--recipe", "go1_walk", "--steps", "480", "--checkpoint-every", "100000",
            "--ppo", json.dumps({"n_steps": 32, "batch_size": 160}), "--env", ENV]
    if set(hyq.BACKENDS) != {"rapier", "dart", "mujoco"}:
        # The recipe's engines are its default: a build without one is refused in one line.
        done = script("train_sb3_ppo.py", *args, "--out", tmp_path / "never")
        assert done.returncode != 0 and len(done.stderr.strip().splitlines()) == 1, done.stderr
        assert not (tmp_path / "never").exists()
        return
    out = train("train_sb3_ppo.py", args, tmp_path / "go1")
    config = json.loads((out / "config.json").read_text())
    assert config["robot"] == "go1" and config["backends"] == ["rapier", "dart", "mujoco"]
    assert config["envs"] == 15
    assert {k: config["ppo"][k] for k in ("learning_rate", "lr_schedule", "target_kl")} == {
        "learning_rate": 1e-3, "lr_schedule": "linear", "target_kl": 0.02}
    assert config["ppo"]["n_steps"] == 32 and config["net"]["log_std_init"] == -1.0
    assert config["env"]["fall_penalty"] == 20.0
    assert config["env"]["regularizers"] == {"action_rate": -0.01}
    assert list(json.loads((out / "eval.json").read_text())["per_engine"]) == config["backends"]
    # --envs still wins over the recipe's 15, and rsl_rl has no Go1 recipe.
    again = train("train_sb3_ppo.py", [*args, "--envs", "3"], tmp_path / "three")
    assert json.loads((again / "config.json").read_text())["envs"] == 3
    done = script("train_rsl_rl.py", "--recipe", "go1_walk", "--out", tmp_path / "never")
    assert done.returncode != 0 and "go1_walk" in done.stderr


def test_a_recipe_of_the_other_trainer_is_refused_in_one_line(tmp_path: Path) -> None:
    # SB3 has no budget for the velocity recipes (they are rsl_rl's); it raised a KeyError.
    for name, recipe in (("train_sb3_ppo.py", "velocity_forward"), ("train_rsl_rl.py", "go1_walk")):
        done = script(name, "--recipe", recipe, "--out", tmp_path / "never")
        assert done.returncode == 2 and "invalid choice" in done.stderr and "Traceback" not in done.stderr
    assert not (tmp_path / "never").exists()


def test_an_sb3_run_resumes_a_checkpoint_with_its_statistics(sb3_runs, tmp_path) -> None:
    """--resume starts from the checkpoint's networks and VecNormalize statistics: at a learning
    rate of 0 the policy stays the checkpoint's to the bit while the statistics go on counting,
    and the run records the command of the run it resumed before its own."""
    import pickle

    from stable_baselines3 import PPO

    source = sb3_runs[0] / "checkpoints" / "model_512.zip"
    args = [a if a != json.dumps({"n_steps": 128, "batch_size": 256})
            else json.dumps({"n_steps": 128, "batch_size": 256, "learning_rate": 0.0}) for a in SB3]
    args[args.index("--steps") + 1] = "512"
    run = train("train_sb3_ppo.py", [*args, "--resume", source], tmp_path / "resumed")
    before = PPO.load(source, device="cpu").policy.state_dict()
    after = PPO.load(run / "model.zip", device="cpu").policy.state_dict()
    assert before.keys() == after.keys()
    for key in before:
        assert torch.equal(before[key], after[key]), key
    old = pickle.loads((sb3_runs[0] / "checkpoints" / "vecnormalize_512.pkl").read_bytes())
    new = pickle.loads((run / "vecnormalize.pkl").read_bytes())
    # Both counted 512 steps and a reset of the 4 envs on top of SB3's 1e-4.
    assert new.obs_rms.count == pytest.approx(2 * old.obs_rms.count - 1e-4), new.obs_rms.count
    config = json.loads((run / "config.json").read_text())
    first = json.loads((sb3_runs[0] / "config.json").read_text())["command"]
    assert config["resume"] == str(source)
    assert config["command"].startswith(first + " && ")
    missing = script("train_sb3_ppo.py", *args, "--resume", tmp_path / "none.zip", "--out", tmp_path / "x")
    assert missing.returncode != 0 and "--resume" in missing.stderr.splitlines()[-1]
    assert not (tmp_path / "x").exists()


def test_an_sb3_resume_takes_a_new_action_noise_and_refuses_new_networks(sb3_runs, tmp_path) -> None:
    """--action-noise after --resume: at a learning rate of 0 every action's log deviation is
    log(STD) and the rest of the policy is the checkpoint's to the bit; --net with --resume, and a
    noise that is not a finite number above 0, are refused with one line before OUT is made."""
    import math

    from stable_baselines3 import PPO

    source = sb3_runs[0] / "checkpoints" / "model_512.zip"
    args = [a if a != json.dumps({"n_steps": 128, "batch_size": 256})
            else json.dumps({"n_steps": 128, "batch_size": 256, "learning_rate": 0.0}) for a in SB3]
    args[args.index("--steps") + 1] = "512"
    run = train("train_sb3_ppo.py", [*args, "--resume", source, "--action-noise", "0.05"], tmp_path / "quiet")
    before = PPO.load(source, device="cpu").policy.state_dict()
    after = PPO.load(run / "model.zip", device="cpu").policy.state_dict()
    assert not torch.equal(before["log_std"], after["log_std"])
    assert torch.equal(after["log_std"], torch.full_like(after["log_std"], math.log(0.05)))
    for key in before.keys() - {"log_std"}:
        assert torch.equal(before[key], after[key]), key
    for extra, named in ((["--net", json.dumps({"pi": [64]})], "--net pi"),
                         (["--action-noise", "0"], "--action-noise 0.0"),
                         (["--action-noise", "nan"], "--action-noise nan")):
        done = script("train_sb3_ppo.py", *args, "--resume", source, *extra, "--out", tmp_path / "x")
        last = done.stderr.strip().splitlines()[-1]
        assert done.returncode != 0 and last.startswith(f"error: {named}"), done.stderr[-500:]
    assert not (tmp_path / "x").exists()


def test_stop_at_ends_at_the_checkpoints_model_and_eval_chooses_what_is_evaluated(sb3_runs, tmp_path) -> None:
    """--stop-at N ends the run at the step its checkpoint N is written, so model.zip and its
    statistics are that checkpoint's to the bit; --eval none evaluates nothing (eval.json keeps the
    timing alone), --eval final the final model alone; a stop outside the budget is refused in
    one line before OUT is made."""
    import pickle
    import zipfile

    stopped = train("train_sb3_ppo.py", [*SB3, "--stop-at", "512", "--eval", "none"], tmp_path / "stopped")
    checkpoint = sb3_runs[0] / "checkpoints" / "model_512.zip"
    for part in ("policy.pth", "policy.optimizer.pth", "pytorch_variables.pth"):
        assert (zipfile.ZipFile(stopped / "model.zip").read(part)
                == zipfile.ZipFile(checkpoint).read(part)), part
    old = pickle.loads((sb3_runs[0] / "checkpoints" / "vecnormalize_512.pkl").read_bytes())
    new = pickle.loads((stopped / "vecnormalize.pkl").read_bytes())
    for rms in ("obs_rms", "ret_rms"):
        a, b = getattr(old, rms), getattr(new, rms)
        assert a.count == b.count and np.array_equal(a.mean, b.mean) and np.array_equal(a.var, b.var), rms
    assert not (stopped / "checkpoints" / "model_1024.zip").exists()
    assert list(json.loads((stopped / "eval.json").read_text())) == ["timing"]
    assert json.loads((stopped / "config.json").read_text())["stop_at"] == 512
    assert len((stopped / "evals.csv").read_text().splitlines()) == 1  # the header

    final = train("train_sb3_ppo.py", [*SB3, "--eval", "final"], tmp_path / "final")
    result = json.loads((final / "eval.json").read_text())
    assert "estimates" in result and "best_checkpoint_env_steps" not in result
    assert (final / "checkpoints" / "model_1024.zip").exists()
    assert len((final / "evals.csv").read_text().splitlines()) == 1

    for stop in ("0", "1025"):
        done = script("train_sb3_ppo.py", *SB3, "--stop-at", stop, "--out", tmp_path / "x")
        last = done.stderr.strip().splitlines()[-1]
        assert done.returncode != 0 and last.startswith(f"error: --stop-at {stop}"), done.stderr[-500:]
    assert not (tmp_path / "x").exists()
