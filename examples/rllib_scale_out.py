"""Scale HyQ-v0 out with RLlib (Ray): many env runners, each stepping a batch of HyQ envs.

Not run in CI (it needs Ray and PyTorch):

    pip install "ray[rllib]==2.60.0" torch
    python examples/rllib_scale_out.py --runners 4 --envs-per-runner 8 --iterations 50

RLlib builds each env from one ``env_config`` dict; ``hyq.HyQEnv`` takes exactly that
(``HyQEnv(env_config={...})``, the same keys as its keyword arguments), so the class is
registered as is. Each env runner is a Ray actor (a process, on this machine or on any node of
a Ray cluster: start the cluster with ``ray start --head`` / ``ray start --address=...`` and
run this script on the head node); within a runner, RLlib vectorises its envs. Every env is
seeded by RLlib from the run's seed, and the episode length is the env's ``max_time_steps``
(default 1000, reported as truncation, which RLlib bootstraps).
"""

from __future__ import annotations

import argparse

from ray.rllib.algorithms.ppo import PPOConfig
from ray.tune.registry import register_env

import hyq


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runners", type=int, default=2, help="env runner processes")
    parser.add_argument("--envs-per-runner", type=int, default=4)
    parser.add_argument("--iterations", type=int, default=20)
    args = parser.parse_args()

    register_env("HyQ-v0", lambda env_config: hyq.HyQEnv(env_config=env_config))
    config = (
        PPOConfig()
        .environment("HyQ-v0", env_config={"norm_rew_scaling": 10.0, "fall_penalty": 5.0})
        .env_runners(
            num_env_runners=args.runners,
            num_envs_per_env_runner=args.envs_per_runner,
        )
        .training(train_batch_size_per_learner=4000, minibatch_size=1000, num_epochs=3)
    )
    algo = config.build_algo()
    for i in range(args.iterations):
        result = algo.train()
        returns = result.get("env_runners", {}).get("episode_return_mean")
        print(f"iteration {i + 1}: mean episode return {returns}")
    algo.stop()


if __name__ == "__main__":
    main()
