"""Train a PPO walker on HyQ-v0 with Stable-Baselines3 (not run in CI: it needs PyTorch).

    python3 -m venv target/train-venv
    target/train-venv/bin/pip install -r examples/requirements-train.txt   # PyTorch: 5.5 GB
    (cd crates/hyq-py && VIRTUAL_ENV=$PWD/../../target/train-venv \\
        ../../target/train-venv/bin/maturin develop --release --locked)
    target/train-venv/bin/python examples/train_sb3_ppo.py --out runs/walk

The recipe (docs/training.md says why each setting is there): the environment of RECIPE_ENV
(the spec's rewards and penalties with user variables only, and the project's `offset` action
mode), 16 envs stepped in Rust (hyq.sb3.HyQVecEnv, same-step resets with SB3's
terminal_observation and TimeLimit.truncated, so PPO bootstraps timeouts), VecNormalize on
observations and rewards, PPO with the settings of RECIPE_PPO, seed 0, a fixed budget of env
steps. It writes into OUT:

    progress.csv, progress.png   the learning curve: mean return, distance walked toward the
                                 goal (K - D^T), fall, joint-limit and reach rates, episode
                                 length, over env steps (each row: the episodes that ended since
                                 the previous row, at least --curve-episodes of them)
    checkpoints/                 model_<steps>.zip and vecnormalize_<steps>.pkl
    model.zip, vecnormalize.pkl  the final agent
    eval.json                    the final agent on 20 seeded episodes with reset noise
    config.json                  every setting of the run

Export the result for the Rust replay (`hyq run --policy mlp:FILE`) with
examples/export_policy.py.
"""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback, CallbackList
from stable_baselines3.common.utils import set_random_seed
from stable_baselines3.common.vec_env import VecMonitor, VecNormalize

from hyq.sb3 import HyQVecEnv

#: The environment the policy trains in, as the package's keyword arguments. Only the spec's
#: user variables and the project's own tables: docs/training.md has the experiments behind
#: each value.
RECIPE_ENV: dict[str, Any] = {
    # Spec §4.2's normalised reward on top of the default exponential one (k_exp = 5): r_e
    # pays almost nothing in the first metres (0.2 per metre at the start), r_n pays
    # k_norm / K per metre from the first step.
    "norm_rew_scaling": 10.0,
    # Spec §5.4 and §5.3: a fall or a joint at its limit ends the episode; without a penalty
    # that end costs only the progress not made, which a still-learning walker barely has.
    "fall_penalty": 5.0,
    "reach_bounds_penalty": 5.0,
    # The project's offset mode (spec §7.1): a zero action holds the standing pose and a
    # target stays within 0.5 rad of it.
    "action": {"mode": "offset", "max_offset_rad": 0.5},
    # The evaluation's reset noise, so the policy is trained on the starts it is judged on.
    "reset": {"joint_noise_rad": 0.05, "yaw_noise_deg": 5.0},
}

#: PPO's settings (Stable-Baselines3 names).
RECIPE_PPO: dict[str, Any] = {
    "n_steps": 256,
    "batch_size": 1024,
    "n_epochs": 5,
    "learning_rate": 3e-4,
    "gamma": 0.99,
    "gae_lambda": 0.95,
    "clip_range": 0.2,
    "ent_coef": 0.0,
    "vf_coef": 0.5,
    "max_grad_norm": 0.5,
}
#: log_std_init -2 (action noise σ ≈ 0.14, i.e. about 0.07 rad of target noise): with -1
#: (σ ≈ 0.37) the training episodes walked 3 m on the noise's shuffling while the deterministic
#: policy, the one exported, walked 0.45 m at 160k steps and hit a joint limit in 65 % of its
#: episodes at 320k; with -2 the deterministic policy walked 2.6 m at 150k (docs/training.md).
RECIPE_NET: dict[str, Any] = {"pi": [128, 128], "vf": [128, 128], "log_std_init": -2.0}

#: The evaluation of issue-style claims: 20 seeded episodes with this reset noise.
EVAL_EPISODES = 20
EVAL_SEED = 1000


def distance_walked(info: dict[str, Any]) -> float:
    """K - D^T: how much closer to the goal the trunk ended than it started (m)."""
    goal = np.asarray(info["goal"], dtype=np.float64)
    start = np.asarray(info["initial_position"], dtype=np.float64)
    return float(np.linalg.norm(goal - start) - info["distance_to_goal"])


class Curve(BaseCallback):
    """Writes the learning curve (CSV rows over env steps) from the final info of every
    episode, and draws it as a PNG at each checkpoint and at the end."""

    FIELDS = [
        "env_steps", "episodes", "mean_return", "mean_distance_m", "fall_rate",
        "joint_limit_rate", "reach_rate", "mean_length", "env_steps_per_s",
    ]

    def __init__(self, out: Path, min_episodes: int) -> None:
        super().__init__()
        self.out = out
        self.min_episodes = min_episodes
        self.pending: list[dict[str, float]] = []
        self.rows: list[dict[str, float]] = []
        self.evals: list[dict[str, float]] = []
        self.start = time.monotonic()
        self.file = open(out / "progress.csv", "w", newline="")
        self.writer = csv.DictWriter(self.file, fieldnames=self.FIELDS)
        self.writer.writeheader()

    def _on_step(self) -> bool:
        for done, info in zip(self.locals["dones"], self.locals["infos"]):
            if done:
                self.pending.append({
                    "return": float(info["episode"]["r"]),
                    "length": float(info["episode"]["l"]),
                    "distance": distance_walked(info),
                    "fell": float(info["fell"]),
                    "joint_limit": float(info["joint_limit"]),
                    "reached": float(info["reached"]),
                })
        return True

    def _on_rollout_end(self) -> None:
        if len(self.pending) < self.min_episodes:
            return
        mean = lambda key: float(np.mean([e[key] for e in self.pending]))  # noqa: E731
        row = {
            "env_steps": self.num_timesteps,
            "episodes": len(self.pending),
            "mean_return": mean("return"),
            "mean_distance_m": mean("distance"),
            "fall_rate": mean("fell"),
            "joint_limit_rate": mean("joint_limit"),
            "reach_rate": mean("reached"),
            "mean_length": mean("length"),
            "env_steps_per_s": self.num_timesteps / (time.monotonic() - self.start),
        }
        self.writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
        self.file.flush()
        self.rows.append(row)
        self.pending.clear()
        self.logger.record("hyq/distance_m", row["mean_distance_m"])
        self.logger.record("hyq/fall_rate", row["fall_rate"])
        self.logger.record("hyq/joint_limit_rate", row["joint_limit_rate"])

    def _on_training_end(self) -> None:
        self.file.close()
        plot_curve(self.rows, self.out / "progress.png", self.evals)


class Checkpoints(BaseCallback):
    """Every `every` env steps: saves the model and the normalisation statistics, and
    evaluates the deterministic policy (`evaluate`, a row of evals.csv). Training episodes
    run the stochastic policy, whose action noise alone can shuffle the robot forward; the
    deterministic one is what gets exported, so the curve shows both."""

    FIELDS = ["env_steps", "mean_return", "mean_distance_m", "fall_rate", "joint_limit_rate", "reach_rate"]

    def __init__(self, out: Path, every: int, curve: Curve, env_kwargs: dict[str, Any]) -> None:
        super().__init__()
        self.dir = out / "checkpoints"
        self.dir.mkdir(parents=True, exist_ok=True)
        self.every = every
        self.next = every
        self.curve = curve
        self.env_kwargs = env_kwargs
        self.file = open(out / "evals.csv", "w", newline="")
        self.writer = csv.DictWriter(self.file, fieldnames=self.FIELDS)
        self.writer.writeheader()

    def _on_step(self) -> bool:
        if self.num_timesteps >= self.next:
            self.next += self.every
            norm = self.model.get_vec_normalize_env()
            self.model.save(self.dir / f"model_{self.num_timesteps}.zip")
            norm.save(str(self.dir / f"vecnormalize_{self.num_timesteps}.pkl"))
            result = evaluate(self.model, norm, self.env_kwargs)
            row = {"env_steps": self.num_timesteps, **{k: result[k] for k in self.FIELDS[1:]}}
            self.curve.evals.append(row)
            self.writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
            self.file.flush()
            plot_curve(self.curve.rows, self.curve.out / "progress.png", self.curve.evals)
        return True

    def _on_training_end(self) -> None:
        self.file.close()


def plot_curve(rows: list[dict[str, float]], path: Path, evals: list[dict[str, float]]) -> None:
    """The learning curve as a 2x2 PNG (matplotlib, no display): the training episodes
    (stochastic policy) as lines, the deterministic evaluations as points."""
    if not rows:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x = np.array([r["env_steps"] for r in rows]) / 1e6
    col = lambda key: np.array([r[key] for r in rows])  # noqa: E731
    fig, axes = plt.subplots(2, 2, figsize=(10, 6.5), sharex=True)
    ex = np.array([r["env_steps"] for r in evals]) / 1e6
    ecol = lambda key: np.array([r[key] for r in evals])  # noqa: E731
    axes[0, 0].plot(x, col("mean_return"), label="training episodes")
    axes[0, 0].plot(ex, ecol("mean_return"), "o", label="deterministic, 20 eval episodes")
    axes[0, 0].set_ylabel("mean episode return")
    axes[0, 0].legend()
    axes[0, 1].plot(x, col("mean_distance_m"))
    axes[0, 1].plot(ex, ecol("mean_distance_m"), "o")
    axes[0, 1].set_ylabel("distance walked toward the goal (m)")
    axes[1, 0].plot(x, col("fall_rate"), label="fell")
    axes[1, 0].plot(x, col("joint_limit_rate"), label="joint limit")
    axes[1, 0].plot(x, col("reach_rate"), label="reached")
    axes[1, 0].plot(ex, ecol("fall_rate"), "o", color="C0")
    axes[1, 0].plot(ex, ecol("joint_limit_rate"), "o", color="C1")
    axes[1, 0].set_ylabel("fraction of episodes")
    axes[1, 0].set_ylim(-0.02, 1.02)
    axes[1, 0].legend()
    axes[1, 1].plot(x, col("mean_length") / 100.0)
    axes[1, 1].set_ylabel("mean episode length (s)")
    for ax in axes[1]:
        ax.set_xlabel("env steps (millions)")
    for ax in axes.flat:
        ax.grid(alpha=0.3)
    fig.suptitle("PPO on HyQ-v0 (rapier), examples/train_sb3_ppo.py")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def evaluate(model: PPO, obs_norm: VecNormalize, env_kwargs: dict[str, Any]) -> dict[str, Any]:
    """The deterministic policy on EVAL_EPISODES episodes (env i seeded EVAL_SEED + i), with
    the recipe's reset noise: the first episode of each env counts."""
    venv = HyQVecEnv(num_envs=EVAL_EPISODES, seed=EVAL_SEED, **env_kwargs)
    obs = venv.reset()
    episodes: list[dict[str, Any] | None] = [None] * EVAL_EPISODES
    returns = np.zeros(EVAL_EPISODES)
    while any(e is None for e in episodes):
        action, _ = model.predict(obs_norm.normalize_obs(obs), deterministic=True)
        obs, rewards, dones, infos = venv.step(action)
        for i in range(EVAL_EPISODES):
            if episodes[i] is None:
                returns[i] += rewards[i]
                if dones[i]:
                    episodes[i] = {
                        "return": float(returns[i]),
                        "distance_m": distance_walked(infos[i]),
                        "steps": int(infos[i]["t"]),
                        "reasons": infos[i]["reasons"],
                    }
    venv.close()
    done = [e for e in episodes if e is not None]
    return {
        "episodes": done,
        "mean_return": float(np.mean([e["return"] for e in done])),
        "mean_distance_m": float(np.mean([e["distance_m"] for e in done])),
        "fall_rate": float(np.mean(["fell" in e["reasons"] for e in done])),
        "joint_limit_rate": float(np.mean(["joint_limit" in e["reasons"] for e in done])),
        "reach_rate": float(np.mean(["reached" in e["reasons"] for e in done])),
    }


def git_commit() -> str:
    """The commit of the checkout the script runs from ("unknown" outside git)."""
    try:
        return subprocess.run(
            ["git", "rev-parse", "HEAD"], capture_output=True, text=True, check=True,
            cwd=Path(__file__).resolve().parent,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True, help="output directory")
    parser.add_argument("--steps", type=int, default=600_000, help="total env steps (default: 600k)")
    parser.add_argument("--envs", type=int, default=16, help="parallel envs (default: 16)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--checkpoint-every", type=int, default=150_000,
                        help="env steps between checkpoints (default: 150k)")
    parser.add_argument("--curve-episodes", type=int, default=32, help="least episodes per curve row")
    parser.add_argument("--env", type=json.loads, default={},
                        help='JSON object of environment keys to change, e.g. \'{"fall_penalty": 0}\'')
    parser.add_argument("--ppo", type=json.loads, default={}, help="JSON object of PPO settings to change")
    parser.add_argument("--net", type=json.loads, default={}, help="JSON object of network settings to change")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    env_kwargs = {**RECIPE_ENV, **args.env}
    ppo_kwargs = {**RECIPE_PPO, **args.ppo}
    net = {**RECIPE_NET, **args.net}
    config = {
        "env": env_kwargs, "ppo": ppo_kwargs, "net": net, "steps": args.steps, "envs": args.envs,
        "seed": args.seed, "commit": git_commit(), "torch_threads": 1,
        "command": " ".join(sys.argv),
    }
    (args.out / "config.json").write_text(json.dumps(config, indent=2) + "\n")

    # One torch thread: the envs' rayon threads use the cores, and a fixed thread count keeps
    # torch's CPU arithmetic the same from run to run.
    torch.set_num_threads(1)
    set_random_seed(args.seed)
    venv = HyQVecEnv(num_envs=args.envs, seed=args.seed, **env_kwargs)
    venv = VecMonitor(venv)
    venv = VecNormalize(venv, norm_obs=True, norm_reward=True, clip_obs=10.0, gamma=ppo_kwargs["gamma"])
    model = PPO(
        "MlpPolicy",
        venv,
        policy_kwargs={
            "net_arch": {"pi": net["pi"], "vf": net["vf"]},
            "activation_fn": torch.nn.Tanh,
            "log_std_init": net["log_std_init"],
        },
        seed=args.seed,
        device="cpu",
        verbose=0,
        **ppo_kwargs,
    )
    curve = Curve(args.out, args.curve_episodes)
    started = time.monotonic()
    model.learn(
        total_timesteps=args.steps,
        callback=CallbackList([curve, Checkpoints(args.out, args.checkpoint_every, curve, env_kwargs)]),
        progress_bar=True,
    )
    elapsed = time.monotonic() - started
    model.save(args.out / "model.zip")
    venv.save(str(args.out / "vecnormalize.pkl"))
    venv.close()

    result = evaluate(model, venv, env_kwargs)
    result["train_wall_s"] = elapsed
    result["train_env_steps"] = model.num_timesteps
    result["train_env_steps_per_s"] = model.num_timesteps / elapsed
    (args.out / "eval.json").write_text(json.dumps(result, indent=2) + "\n")
    print(
        f"{model.num_timesteps} env steps in {elapsed / 60:.1f} min "
        f"({model.num_timesteps / elapsed:.0f}/s); eval over {EVAL_EPISODES} episodes: "
        f"return {result['mean_return']:.2f}, distance {result['mean_distance_m']:.2f} m, "
        f"fell {result['fall_rate']:.0%}, joint limit {result['joint_limit_rate']:.0%}, "
        f"reached {result['reach_rate']:.0%}"
    )


if __name__ == "__main__":
    main()
