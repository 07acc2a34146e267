"""Export a trained Stable-Baselines3 PPO walker for the Rust replay (`hyq run --policy mlp:FILE`).

    target/train-venv/bin/python examples/export_policy.py --run runs/walk \\
        --out assets/policies/hyq_walk.safetensors \\
        --fixture crates/hyq-env/tests/fixtures/hyq_walk_actions.safetensors

Reads RUN/model.zip, RUN/vecnormalize.pkl and RUN/config.json (as examples/train_sb3_ppo.py
writes them) and writes the actor and the observation normalisation as a `hyq-mlp-policy`
safetensors file (the format is documented in crates/hyq-env/src/mlp.rs). With --fixture it
also records observations of the deterministic policy walking (seeded, with the training
reset noise) and SB3's own deterministic actions for them, which a Rust test compares with the
Rust forward pass.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

import numpy as np
import torch
from safetensors.numpy import save_file
from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import VecNormalize

import hyq
from hyq._config import config_pairs
from hyq.sb3 import HyQVecEnv

ACTIVATIONS = {torch.nn.Tanh: "tanh", torch.nn.ReLU: "relu", torch.nn.ELU: "elu"}


def actor_layers(model: PPO) -> list[torch.nn.Linear]:
    """The actor's linear layers, input first: the policy branch of the MLP extractor, then the
    action head (the Gaussian's mean)."""
    policy = model.policy
    if not isinstance(policy.features_extractor, torch.nn.Flatten) and type(
        policy.features_extractor
    ).__name__ != "FlattenExtractor":
        raise SystemExit("only MlpPolicy's flatten feature extractor is supported")
    layers = [m for m in policy.mlp_extractor.policy_net if isinstance(m, torch.nn.Linear)]
    return layers + [policy.action_net]


def activation_of(model: PPO) -> str:
    kinds = {type(m) for m in model.policy.mlp_extractor.policy_net if not isinstance(m, torch.nn.Linear)}
    if len(kinds) != 1 or next(iter(kinds)) not in ACTIVATIONS:
        raise SystemExit(f"unsupported activations {kinds}")
    return ACTIVATIONS[next(iter(kinds))]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--run", type=Path, required=True, help="the training output directory")
    parser.add_argument("--model", type=Path, help="model .zip (default: RUN/model.zip)")
    parser.add_argument("--vecnormalize", type=Path, help="statistics .pkl (default: RUN/vecnormalize.pkl)")
    parser.add_argument("--out", type=Path, required=True, help="the policy file to write")
    parser.add_argument("--fixture", type=Path, help="also write observations and SB3's actions here")
    args = parser.parse_args()

    config = json.loads((args.run / "config.json").read_text())
    env_kwargs: dict[str, Any] = config["env"]
    model = PPO.load(args.model or args.run / "model.zip", device="cpu")
    probe = hyq.HyQEnv(**env_kwargs)
    norm = VecNormalize.load(str(args.vecnormalize or args.run / "vecnormalize.pkl"), HyQVecEnv(num_envs=1, **env_kwargs))

    tensors: dict[str, np.ndarray] = {
        "obs_mean": np.asarray(norm.obs_rms.mean, dtype=np.float64),
        "obs_var": np.asarray(norm.obs_rms.var, dtype=np.float64),
    }
    for k, layer in enumerate(actor_layers(model)):
        tensors[f"layers.{k}.weight"] = layer.weight.detach().numpy().astype(np.float32)
        tensors[f"layers.{k}.bias"] = layer.bias.detach().numpy().astype(np.float32)

    action = env_kwargs.get("action", {})
    mode = action.get("mode", "normalized")
    # What the policy needs of its environment: every task and action key it trained with. The
    # reset distribution is the user's evaluation condition and is only recorded.
    applied = {k: v for k, v in config_pairs(env_kwargs) if not k.startswith("reset.")}
    metadata = {
        "format": "hyq-mlp-policy",
        "format_version": "1",
        "robot": "hyq",
        "observation": json.dumps([row.name for row in probe.observation_table]),
        "action": json.dumps(probe.joint_names),
        "action_mode": mode,
        "activation": activation_of(model),
        "obs_clip": repr(float(norm.clip_obs)),
        "obs_epsilon": repr(float(norm.epsilon)),
        "env_config": json.dumps(applied, sort_keys=True),
        "training_env_config": json.dumps(dict(config_pairs(env_kwargs)), sort_keys=True),
        "training_commit": config["commit"],
        "training_command": config["command"],
        "training_env_steps": str(model.num_timesteps),
        "trainer": "stable-baselines3 PPO (examples/train_sb3_ppo.py)",
        "seed": str(config["seed"]),
    }
    if mode == "offset":
        metadata["action_scale_rad"] = repr(float(action.get("max_offset_rad", 0.5)))
    elif mode == "delta":
        metadata["action_scale_rad"] = repr(float(action.get("max_delta_rad", 0.1)))
    probe.close()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    save_file(tensors, str(args.out), metadata=metadata)
    print(f"wrote {args.out} ({args.out.stat().st_size} bytes): layers "
          f"{[tensors[f'layers.{k}.weight'].shape for k in range(len(actor_layers(model)))]}")

    if args.fixture:
        # One seeded episode of the deterministic policy, every 10th observation: the inputs a
        # replay meets, with SB3's own deterministic (clipped) actions for them.
        env = hyq.HyQEnv(**env_kwargs)
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
        args.fixture.parent.mkdir(parents=True, exist_ok=True)
        save_file(
            {"observations": np.stack(observations).astype(np.float32),
             "actions": np.stack(actions).astype(np.float32)},
            str(args.fixture),
            metadata={"policy": args.out.name, "source": "examples/export_policy.py --fixture"},
        )
        print(f"wrote {args.fixture}: {len(observations)} observations")


if __name__ == "__main__":
    main()
