"""One env driven from Python against the same env in Rust: the `env_random` workload of
`hyq bench` (uniform random normalized actions, drawn before the timed part; an ended episode
is reset inside it), env steps per CPU second, alternating the two in each repetition.

    python examples/bench_single_env.py --backend mujoco --hyq target/release/hyq

needs a release build of the package (`maturin develop --release --features mujoco`) and of
the command (`cargo build --release -p hyq-cli --features mujoco`). Prints one line per
repetition and the median ratio Python / Rust.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import time

import numpy as np

import hyq


def python_rate(backend: str, robot: str, steps: int, seed: int) -> float:
    env = hyq.HyQEnv(backend=backend, robot=robot)
    rng = np.random.default_rng(seed)
    actions = rng.uniform(-1.0, 1.0, size=(steps, env.action_space.shape[0]))
    env.reset(seed=seed)
    step = env.step
    cpu0 = time.process_time()
    for a in actions:
        _, _, terminated, truncated, _ = step(a)
        if terminated or truncated:
            env.reset()
    return steps / (time.process_time() - cpu0)


def rust_rate(hyq_cli: str, backend: str, robot: str, steps: int, seed: int) -> float:
    out = subprocess.run(
        [hyq_cli, "bench", "--backend", backend, "--robot", robot, "--steps", str(steps),
         "--seed", str(seed), "--json"],
        check=True, capture_output=True, text=True,
    )
    return json.loads(out.stdout)["env_steps_per_s_cpu"]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--backend", default="mujoco")
    p.add_argument("--robot", default="hyq")
    p.add_argument("--hyq", required=True, help="the release `hyq` command")
    p.add_argument("--steps", type=int, default=20000)
    p.add_argument("--reps", type=int, default=5)
    args = p.parse_args()
    ratios = []
    for rep in range(args.reps):
        py = python_rate(args.backend, args.robot, args.steps, rep)
        rs = rust_rate(args.hyq, args.backend, args.robot, args.steps, rep)
        ratios.append(py / rs)
        print(f"rep {rep + 1}: Python {py:,.0f}, Rust {rs:,.0f} env steps/s (CPU): {py / rs:.3f}")
    print(
        f"median Python / Rust: {statistics.median(ratios):.3f} "
        f"(min {min(ratios):.3f}, max {max(ratios):.3f}, {args.reps} repetitions)"
    )


if __name__ == "__main__":
    main()
