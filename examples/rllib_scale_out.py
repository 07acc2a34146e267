"""Scale HyQ-v0 out with RLlib (Ray): many env runners, each stepping a batch of HyQ envs.

Not run in CI (Ray and PyTorch are 6.1 GB); `cargo xtask test --with rllib` runs it briefly:

    python3 -m venv target/rllib-venv
    target/rllib-venv/bin/pip install -r examples/requirements-rllib.txt
    (cd crates/hyq-py && VIRTUAL_ENV=$PWD/../../target/rllib-venv \\
        ../../target/rllib-venv/bin/maturin develop --release)
    target/rllib-venv/bin/python examples/rllib_scale_out.py --runners 2 --envs-per-runner 2

RLlib builds each env from one ``env_config`` dict; ``hyq.HyQEnv`` takes exactly that
(``HyQEnv(env_config={...})``, the same keys as its keyword arguments), so the class is
registered as is. The configuration is checked here first, by building one env in this
process, so a wrong key is the env's one-line error, not a crash of every env runner.

Each env runner is a Ray actor (a process); within a runner, RLlib steps its envs together. On
one machine Ray starts locally. For more machines, start a Ray cluster (``ray start --head`` on
one node, ``ray start --address=HEAD:6379`` on the others, each with this package installed) and
pass ``--address auto`` (or ``HEAD:6379``) to run on it: ``ray.init(address=...)``. Every env
is seeded by RLlib from the run's seed; the episode length is the env's ``max_time_steps``
(default 1000, reported as truncation, which RLlib bootstraps).
"""

from __future__ import annotations

import argparse
import json
import sys
import time

import ray
from ray.rllib.algorithms.ppo import PPOConfig
from ray.tune.registry import register_env

import hyq

#: The example's reward: the spec's default (k_exp = 5) plus the normalised reward of its
#: Figures 3-4 and a fall penalty, so that progress and falls both show in the return.
DEFAULT_ENV_CONFIG = {"norm_rew_scaling": 10.0, "fall_penalty": 5.0}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runners", type=int, default=2, help="env runner processes")
    parser.add_argument("--envs-per-runner", type=int, default=4)
    parser.add_argument("--iterations", type=int, default=20)
    parser.add_argument(
        "--batch", type=int, default=4000, help="env steps collected per training iteration"
    )
    parser.add_argument(
        "--env-config",
        type=json.loads,
        default=DEFAULT_ENV_CONFIG,
        help=f"the env's configuration as JSON (default: {json.dumps(DEFAULT_ENV_CONFIG)})",
    )
    parser.add_argument(
        "--address",
        default=None,
        help="a Ray cluster to run on (`auto`, or HOST:PORT); default: a local Ray",
    )
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()

    # Checked here, in this process: a bad key or value is the env's own one-line error.
    try:
        hyq.HyQEnv(env_config=args.env_config).close()
    except (ValueError, TypeError) as e:
        print(f"rllib_scale_out: error: --env-config: {e}", file=sys.stderr)
        return 2

    ray.init(address=args.address)
    register_env("HyQ-v0", lambda env_config: hyq.HyQEnv(env_config=env_config))
    config = (
        PPOConfig()
        .environment("HyQ-v0", env_config=args.env_config)
        .env_runners(
            num_env_runners=args.runners,
            num_envs_per_env_runner=args.envs_per_runner,
        )
        .training(
            train_batch_size_per_learner=args.batch,
            minibatch_size=max(args.batch // 4, 1),
            num_epochs=3,
        )
        .debugging(seed=args.seed)
    )
    algo = config.build_algo()
    print(
        f"PPO on HyQ-v0: {args.runners} env runners x {args.envs_per_runner} envs, "
        f"{args.batch} env steps per iteration"
    )
    print("iteration  env_steps  seconds  env_steps/s  mean_return  episodes")
    try:
        for i in range(1, args.iterations + 1):
            start = time.perf_counter()
            result = algo.train()
            seconds = time.perf_counter() - start
            runners = result.get("env_runners", {})
            steps = runners.get("num_env_steps_sampled", 0)
            mean_return = runners.get("episode_return_mean", float("nan"))
            episodes = runners.get("num_episodes", 0)
            print(
                f"{i:9d}  {steps:9d}  {seconds:7.1f}  {steps / seconds:11.0f}  "
                f"{mean_return:11.3f}  {episodes:8d}",
                flush=True,
            )
    finally:
        algo.stop()
        ray.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
