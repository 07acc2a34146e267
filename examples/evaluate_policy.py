"""Evaluate a trained policy file on every engine with the Rust replay, against the random and
zero-action baselines (standard library only: it runs the `hyq` command).

    cargo build --release -p hyq-cli --features dart,mujoco
    python3 examples/evaluate_policy.py --hyq target/release/hyq \\
        --policy assets/policies/hyq_walk.safetensors --out target/eval

For each backend and policy: `hyq run --episodes 20 --seed 1000 --json` with the evaluation's
reset noise (reset.joint_noise_rad = 0.05, reset.yaw_noise_deg = 5). The trained policy runs in
the environment its file names (`--policy mlp:FILE`); the baselines run in the same
environment (the file's configuration written as a --config file): `random` draws uniform
actions in the same action space, `zero` is the all-zero action, which in the offset mode holds
the standing pose (hyq's `stand` policy). Writes OUT/<backend>_<policy>.jsonl (one summary per
episode) and prints a Markdown table: mean distance walked toward the goal (K − D^T) with its
standard deviation and minimum, the trunk's travel along the start-to-goal direction (which,
unlike K − D^T, keeps growing past the goal), the final distance to the goal D^T, the mean
return, and how the episodes ended.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
from pathlib import Path

RESET_NOISE = ["--set", "reset.joint_noise_rad=0.05", "--set", "reset.yaw_noise_deg=5"]


def policy_config(policy: Path) -> dict[str, str]:
    """The `env_config` metadata entry of a policy file (dotted keys to TOML values)."""
    data = policy.read_bytes()
    n = int.from_bytes(data[:8], "little")
    header = json.loads(data[8 : 8 + n])
    return json.loads(header["__metadata__"]["env_config"])


def write_toml(pairs: dict[str, str], path: Path) -> None:
    tables: dict[str, list[str]] = {}
    for key, value in sorted(pairs.items()):
        table, _, name = key.rpartition(".")
        tables.setdefault(table, []).append(f"{name} = {value}")
    path.write_text("".join(f"[{t}]\n" + "\n".join(rows) + "\n\n" for t, rows in tables.items()))


def run(hyq: str, backend: str, args: list[str], episodes: int, seed: int, out: Path) -> list[dict]:
    cmd = [hyq, "run", "--backend", backend, "--episodes", str(episodes), "--seed", str(seed),
           "--json", *RESET_NOISE, *args]
    print("$", " ".join(cmd), file=sys.stderr)
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed: {done.stderr.strip()}")
    out.write_text(done.stdout)
    return [json.loads(line) for line in done.stdout.splitlines() if line.strip()]


def travel(r: dict) -> float:
    """How far the trunk moved along the start-to-goal direction (m): past the goal it keeps
    counting, where K − D^T falls."""
    d = [g - c for g, c in zip(r["goal"][:2], r["initial_position"][:2])]
    m = [f - c for f, c in zip(r["final_position"][:2], r["initial_position"][:2])]
    return (d[0] * m[0] + d[1] * m[1]) / max(1e-12, (d[0] ** 2 + d[1] ** 2) ** 0.5)


def summarise(rows: list[dict]) -> dict:
    dist = [r["initial_distance_to_goal"] - r["final_distance_to_goal"] for r in rows]
    reasons: dict[str, int] = {}
    for r in rows:
        for reason in r["reasons"]:
            reasons[reason] = reasons.get(reason, 0) + 1
    return {
        "episodes": len(rows),
        "distance_mean": statistics.fmean(dist),
        "distance_sd": statistics.stdev(dist) if len(dist) > 1 else 0.0,
        "distance_min": min(dist),
        "travel_mean": statistics.fmean(travel(r) for r in rows),
        "final_to_goal_mean": statistics.fmean(r["final_distance_to_goal"] for r in rows),
        "return_mean": statistics.fmean(r["return"] for r in rows),
        "steps_mean": statistics.fmean(r["steps"] for r in rows),
        "reasons": reasons,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hyq", default="target/release/hyq", help="the hyq binary")
    parser.add_argument("--policy", type=Path, default=Path("assets/policies/hyq_walk.safetensors"))
    parser.add_argument("--backends", default="rapier,dart,mujoco")
    parser.add_argument("--episodes", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1000)
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    config = args.out / "trained_env.toml"
    write_toml(policy_config(args.policy), config)

    policies = {
        "trained": ["--policy", f"mlp:{args.policy}"],
        "random": ["--policy", "random", "--config", str(config)],
        "zero": ["--policy", "stand", "--config", str(config)],
    }
    results = {}
    for backend in args.backends.split(","):
        for name, extra in policies.items():
            rows = run(args.hyq, backend, extra, args.episodes, args.seed,
                       args.out / f"{backend}_{name}.jsonl")
            results[(backend, name)] = summarise(rows)
    (args.out / "summary.json").write_text(json.dumps(
        {f"{b}/{p}": s for (b, p), s in results.items()}, indent=2) + "\n")

    print("| engine | policy | distance walked K − D^T (m), mean ± sd [min] | trunk travel toward the goal (m) | D^T (m) | return | episode length (steps) | ended by |")
    print("|---|---|---|---|---|---|---|---|")
    for (backend, name), s in results.items():
        ended = ", ".join(f"{k} {v}" for k, v in sorted(s["reasons"].items()))
        print(f"| {backend} | {name} | {s['distance_mean']:.2f} ± {s['distance_sd']:.2f} "
              f"[{s['distance_min']:.2f}] | {s['travel_mean']:.2f} | {s['final_to_goal_mean']:.2f} | {s['return_mean']:.2f} | {s['steps_mean']:.0f} | {ended} |")


if __name__ == "__main__":
    main()
