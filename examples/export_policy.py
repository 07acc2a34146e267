"""Export a trained policy for the Rust replay (`hyq run --policy mlp:FILE`) and as ONNX.

    target/train-venv/bin/python examples/export_policy.py --run runs/reach \\
        --out assets/policies/hyq_reach_mujoco.safetensors --onnx
    target/train-venv/bin/python examples/export_policy.py \\
        --policy assets/policies/hyq_walk.safetensors --onnx      # ONNX of an existing file

--run RUN reads a training run of examples/train_sb3_ppo.py (RUN/model.zip,
RUN/vecnormalize.pkl) or examples/train_rsl_rl.py (RUN/model_<last>.pt), with RUN/config.json,
and writes the actor and its observation normalisation as a `hyq-mlp-policy` safetensors file
(the format is documented in crates/hyq-env/src/mlp.rs). An rsl_rl actor normalises by
(o - mean) / (std + 0.01) and does not clip: the file stores var = (std + 0.01)^2 with epsilon 0
and a clip at the float32 maximum, which is the same formula. --onnx also writes its ONNX twin
beside it (same name, .onnx; hyq.policy_file, built from the safetensors file alone). With
--fixture it also records observations of the deterministic SB3 policy walking and SB3's own
actions for them, which a Rust test compares with the Rust forward pass.

A run directory without a model, or a model or normalisation trained for another robot than the
run's, is refused with one line naming it (exit status 2).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

import hyq
from hyq._config import config_pairs
from hyq.policy_file import check_finite, write_onnx

#: A clip that never binds: rsl_rl does not clip its normalised observations.
NO_CLIP = float(np.finfo(np.float32).max)


def fail(message: str) -> None:
    print(f"export_policy: error: {message}", file=sys.stderr)
    raise SystemExit(2)


def sb3_actor(run: Path, args: argparse.Namespace, robot: str, names: list[str]) -> dict[str, Any]:
    """The SB3 actor's layers, normalisation and activation."""
    import torch
    from stable_baselines3 import PPO

    model_path = args.model or run / "model.zip"
    stats_path = args.vecnormalize or run / "vecnormalize.pkl"
    if args.checkpoint == "best":
        evaluation = run / "eval.json"
        if not evaluation.is_file():
            fail(f"{evaluation}: no such file (--checkpoint best needs a finished run)")
        steps = json.loads(evaluation.read_text()).get("best_checkpoint_env_steps")
        if steps is None:
            fail(f"{evaluation}: names no best checkpoint (the run evaluated none)")
        model_path = run / "checkpoints" / f"model_{steps}.zip"
        stats_path = run / "checkpoints" / f"vecnormalize_{steps}.pkl"
    for path, what in ((model_path, "model"), (stats_path, "normalisation statistics")):
        if not Path(path).is_file():
            fail(f"{path}: no {what} file (is {run} a finished run of examples/train_sb3_ppo.py?)")
    import pickle

    with open(stats_path, "rb") as f:
        norm = pickle.load(f)
    stats_robot = norm.__dict__.get("hyq_robot")
    if stats_robot is not None and stats_robot != robot:
        fail(f"{stats_path}: normalisation statistics of robot {stats_robot!r}, the run trains {robot!r}")
    if norm.obs_rms.mean.shape != (len(names),):
        fail(f"{stats_path}: normalisation statistics of {norm.obs_rms.mean.shape[0]} observation "
             f"values, robot {robot!r} has {len(names)}")
    model = PPO.load(model_path, device="cpu")
    policy = model.policy
    layers = [m for m in policy.mlp_extractor.policy_net if isinstance(m, torch.nn.Linear)]
    layers.append(policy.action_net)
    if layers[0].in_features != len(names):
        fail(f"{model_path}: the actor takes {layers[0].in_features} inputs, robot {robot!r} has {len(names)}")
    kinds = {type(m).__name__.lower() for m in policy.mlp_extractor.policy_net
             if not isinstance(m, torch.nn.Linear)}
    if len(kinds) != 1 or next(iter(kinds)) not in ("tanh", "relu", "elu"):
        fail(f"{model_path}: unsupported activations {sorted(kinds)} (expected tanh, relu or elu)")
    return {
        "obs_mean": np.asarray(norm.obs_rms.mean, dtype=np.float64),
        "obs_var": np.asarray(norm.obs_rms.var, dtype=np.float64),
        "obs_clip": float(norm.clip_obs),
        "obs_epsilon": float(norm.epsilon),
        "layers": [(m.weight.detach().numpy(), m.bias.detach().numpy()) for m in layers],
        "activation": next(iter(kinds)),
        "env_steps": model.num_timesteps,
        "trainer": "stable-baselines3 PPO (examples/train_sb3_ppo.py)",
        "model": model,
        "norm": norm,
    }


def trained_steps(saved: dict[str, Any], config: dict[str, Any]) -> int:
    """The env steps behind an rsl_rl checkpoint: its own count (which includes a resumed
    run's earlier steps), else, for a checkpoint written before checkpoints counted them, the
    run's budget."""
    steps = (saved.get("infos") or {}).get("env_steps")
    return int(config["steps"] if steps is None else steps)


def rsl_rl_actor(run: Path, args: argparse.Namespace, robot: str, names: list[str],
                 config: dict[str, Any]) -> dict[str, Any]:
    """The rsl_rl actor's layers, normalisation and activation."""
    import torch

    if args.model:
        model_path = args.model
    else:
        found = sorted(run.glob("model_*.pt"), key=lambda p: int(p.stem.split("_")[1]))
        if not found:
            fail(f"{run}: no model_<iteration>.pt (is it a finished run of examples/train_rsl_rl.py?)")
        model_path = found[-1]
    if not Path(model_path).is_file():
        fail(f"{model_path}: no model file")
    saved = torch.load(model_path, map_location="cpu", weights_only=False)
    infos = saved.get("infos") or {}
    if infos.get("robot", robot) != robot:
        fail(f"{model_path}: a model of robot {infos['robot']!r}, the run trains {robot!r}")
    if infos.get("observation", names) != names:
        fail(f"{model_path}: trained on other observation rows than robot {robot!r}'s")
    state = saved["actor_state_dict"]
    actor_cfg = config["rsl_rl"]["actor"]
    mean = state["obs_normalizer._mean"].reshape(-1).numpy()
    if mean.shape != (len(names),):
        fail(f"{model_path}: normalisation of {mean.shape[0]} observation values, robot {robot!r} has {len(names)}")
    # rsl_rl: (o - mean) / (std + eps) in float32; the file's formula is (o - mean) / sqrt(var + epsilon).
    std = state["obs_normalizer._std"].reshape(-1).numpy().astype(np.float32)
    denominator = (std + np.float32(0.01)).astype(np.float64)
    keys = sorted((k for k in state if k.startswith("mlp.") and k.endswith(".weight")),
                  key=lambda k: int(k.split(".")[1]))
    layers = [(state[k].numpy(), state[k.replace(".weight", ".bias")].numpy()) for k in keys]
    return {
        "obs_mean": mean.astype(np.float64),
        "obs_var": denominator**2,
        "obs_clip": NO_CLIP,
        "obs_epsilon": 0.0,
        "layers": layers,
        "activation": actor_cfg["activation"],
        "env_steps": trained_steps(saved, config),
        "trainer": "rsl_rl PPO (examples/train_rsl_rl.py)",
    }


#: The configuration keys (by prefix) that are training or evaluation conditions, recorded in a
#: policy file but not applied on replay (metadata_of).
TRAINING_CONDITIONS = ("reset.", "randomize.", "terrain.", "task.max_time_steps")


def metadata_of(actor: dict[str, Any], config: dict[str, Any], robot: str, names: list[str],
                joints: list[str]) -> dict[str, str]:
    env_kwargs: dict[str, Any] = config["env"]
    action = env_kwargs.get("action", {})
    mode = action.get("mode", "normalized")
    # What the policy needs of its environment: every task, action and observation key it
    # trained with. The reset distribution, the randomisation, the ground (with its
    # curriculum) and the episode length are training or evaluation conditions, only recorded
    # (training_env_config): replaying a rough-ground policy on its curriculum's first level
    # would measure it on ground a tenth as rough as the one it learned to walk on, and a
    # policy trained on short episodes (more starts from a reset) is judged on the task's own.
    applied = {k: v for k, v in config_pairs(env_kwargs) if not k.startswith(TRAINING_CONDITIONS)}
    metadata = {
        "format": "hyq-mlp-policy",
        "format_version": "1",
        "robot": robot,
        "observation": json.dumps(names),
        "action": json.dumps(joints),
        "action_mode": mode,
        "activation": actor["activation"],
        "obs_clip": repr(actor["obs_clip"]),
        "obs_epsilon": repr(actor["obs_epsilon"]),
        "env_config": json.dumps(applied, sort_keys=True),
        "training_env_config": json.dumps(dict(config_pairs(env_kwargs)), sort_keys=True),
        "training_backend": config.get("backend", "rapier"),
        "training_commit": config["commit"],
        "training_command": config["command"],
        "training_env_steps": str(actor["env_steps"]),
        "trainer": actor["trainer"],
        "seed": str(config["seed"]),
    }
    if mode == "offset":
        metadata["action_scale_rad"] = repr(float(action.get("max_offset_rad", 0.5)))
    elif mode == "delta":
        metadata["action_scale_rad"] = repr(float(action.get("max_delta_rad", 0.1)))
    return metadata


def write_fixture(actor: dict[str, Any], config: dict[str, Any], robot: str, path: Path,
                  policy: Path) -> None:
    """One seeded episode of the deterministic SB3 policy, every 10th observation: the inputs a
    replay meets, with SB3's own deterministic (clipped) actions for them."""
    from safetensors.numpy import save_file

    model, norm = actor["model"], actor["norm"]
    env = hyq.HyQEnv(robot=robot, **config["env"])
    obs, _ = env.reset(seed=7)
    observations, actions = [], []
    for t in range(400):
        a, _ = model.predict(norm.normalize_obs(obs[None, :]), deterministic=True)
        if t % 10 == 0:
            observations.append(obs.copy())
            actions.append(a[0].astype(np.float32))
        obs, _, terminated, truncated, _ = env.step(a[0])
        if terminated or truncated:
            break
    env.close()
    path.parent.mkdir(parents=True, exist_ok=True)
    save_file(
        {"observations": np.stack(observations).astype(np.float32),
         "actions": np.stack(actions).astype(np.float32)},
        str(path),
        metadata={"policy": policy.name, "source": "examples/export_policy.py --fixture"},
    )
    print(f"wrote {path}: {len(observations)} observations")


def export_run(args: argparse.Namespace) -> Path:
    from safetensors.numpy import save_file

    run: Path = args.run
    if not (run / "config.json").is_file():
        fail(f"{run}: no config.json (not a run directory of examples/train_sb3_ppo.py or train_rsl_rl.py)")
    config = json.loads((run / "config.json").read_text())
    robot = config.get("robot", "hyq")
    # The rows the policy was trained on: the robot's, then the run's observation extras, then
    # the velocity task's group when the run trained that task ([task] kind).
    probe = hyq.HyQEnv(robot=robot, **{k: v for k, v in config["env"].items() if k in ("observation", "task")})
    names = [row.name for row in probe.observation_table]
    joints = list(probe.joint_names)
    probe.close()
    trainer = config.get("trainer", "sb3")
    if trainer == "rsl_rl":
        actor = rsl_rl_actor(run, args, robot, names, config)
    else:
        actor = sb3_actor(run, args, robot, names)
    tensors: dict[str, np.ndarray] = {"obs_mean": actor["obs_mean"], "obs_var": actor["obs_var"]}
    for k, (weight, bias) in enumerate(actor["layers"]):
        tensors[f"layers.{k}.weight"] = np.ascontiguousarray(weight, dtype=np.float32)
        tensors[f"layers.{k}.bias"] = np.ascontiguousarray(bias, dtype=np.float32)
    out: Path = args.out or fail("--out is needed with --run")  # type: ignore[assignment]
    # A trained actor with a NaN or an infinity (a diverged run) is refused before anything is
    # written, in the reader's words: `hyq run` would refuse the file anyway.
    try:
        check_finite(tensors, run)
    except ValueError as e:
        fail(str(e))
    out.parent.mkdir(parents=True, exist_ok=True)
    save_file(tensors, str(out), metadata=metadata_of(actor, config, robot, names, joints))
    print(f"wrote {out} ({out.stat().st_size} bytes): layers "
          f"{[w.shape for w, _ in actor['layers']]}")
    if args.fixture:
        if trainer == "rsl_rl":
            fail("--fixture records SB3's own actions: it is for runs of examples/train_sb3_ppo.py")
        write_fixture(actor, config, robot, args.fixture, out)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--run", type=Path, help="the training output directory")
    parser.add_argument("--policy", type=Path, help="an existing policy file (with --onnx: write its ONNX twin)")
    parser.add_argument("--model", type=Path, help="the model (default: RUN/model.zip, or RUN's last model_<i>.pt)")
    parser.add_argument("--vecnormalize", type=Path, help="SB3's statistics .pkl (default: RUN/vecnormalize.pkl)")
    parser.add_argument("--checkpoint", choices=["final", "best"], default="final",
                        help="SB3 runs: the final model, or the best evaluated checkpoint (eval.json)")
    parser.add_argument("--out", type=Path, help="the policy file to write (with --run)")
    parser.add_argument("--onnx", action="store_true", help="also write the policy's ONNX twin (FILE.onnx)")
    parser.add_argument("--fixture", type=Path, help="also write observations and SB3's actions here")
    args = parser.parse_args()
    if (args.run is None) == (args.policy is None):
        fail("give --run RUN (a training run to export) or --policy FILE (an exported policy), not both")
    if args.run is not None:
        policy = export_run(args)
    else:
        policy = args.policy
        if not args.onnx:
            fail("--policy FILE does nothing without --onnx")
    if args.onnx:
        try:
            onnx_path = write_onnx(policy, Path(policy).with_suffix(".onnx"))
        except (OSError, ValueError) as e:
            fail(str(e))
        print(f"wrote {onnx_path} ({onnx_path.stat().st_size} bytes)")


if __name__ == "__main__":
    main()
