"""Train a PPO policy on HyQ-v0 with Stable-Baselines3 (not run in CI: it needs PyTorch).

    python3 -m venv target/train-venv
    target/train-venv/bin/pip install -r examples/requirements-train.txt   # PyTorch: 5.4 GB
    (cd crates/hyq-py && VIRTUAL_ENV=$PWD/../../target/train-venv \
        ../../target/train-venv/bin/maturin develop --release)
    target/train-venv/bin/python examples/train_sb3_ppo.py --steps 200000 --envs 8 --out runs/ppo

The envs step in Rust (hyq.sb3.HyQVecEnv: one call steps all of them on rayon, with SB3's
same-step resets, terminal_observation and TimeLimit.truncated, so PPO bootstraps timeouts
correctly). VecMonitor writes the episode returns to OUT/monitor.csv; the model is saved to
OUT/model.zip and the normalisation statistics to OUT/vecnormalize.pkl.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import VecMonitor, VecNormalize

from hyq.sb3 import HyQVecEnv


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=200_000, help="total env steps")
    parser.add_argument("--envs", type=int, default=8, help="parallel envs (1 to 4096)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, default=Path("runs/ppo"))
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    # The spec's default reward (k_exp = 5) plus the normalised reward of its Figures 3-4 and
    # a fall penalty, so that progress and falls both show in the return.
    venv = HyQVecEnv(num_envs=args.envs, seed=args.seed, norm_rew_scaling=10.0, fall_penalty=5.0)
    venv = VecMonitor(venv, str(args.out / "monitor.csv"))
    venv = VecNormalize(venv, norm_obs=True, norm_reward=True)

    # Few gradient steps per rollout keep a 2-core machine busy stepping rather than learning:
    # two mini-batches per epoch, whatever the number of envs (a mini-batch that does not
    # divide n_steps * n_envs makes SB3 warn and drop a truncated batch).
    n_steps = 256
    model = PPO(
        "MlpPolicy",
        venv,
        n_steps=n_steps,
        batch_size=n_steps * args.envs // 2,
        n_epochs=3,
        learning_rate=3e-4,
        seed=args.seed,
        device="cpu",
        verbose=1,
    )
    model.learn(total_timesteps=args.steps)
    model.save(args.out / "model.zip")
    venv.save(str(args.out / "vecnormalize.pkl"))
    venv.close()


if __name__ == "__main__":
    main()
