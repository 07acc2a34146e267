"""The train x deploy matrix: a walker trained on each engine, each pair and all three, judged on every engine.

    python examples/transfer_matrix.py --out runs/matrix [--rows rapier,dart+mujoco,...]
        [--recipe walk] [--env JSON] [--envs 12] [--episodes 100] [--seed 1000] [--hyq PATH]
    python examples/transfer_matrix.py --out runs/matrix --table-only

For each row (a set of training engines, written with "+": `rapier`, `dart+mujoco`,
`rapier+dart+mujoco`) it runs, in `OUT/ROW/`:

1. `examples/train_sb3_ppo.py --recipe RECIPE --backends ROW --envs ENVS [--env JSON] --out
   OUT/ROW/run` (the checkpoint chosen on the training engines' own evaluation episodes, seeds
   2000 on; `--env` changes the training environment, e.g. randomised contact, while the
   judging episodes of step 3 stay on the default environment with the reset noise);
2. `examples/export_policy.py --run OUT/ROW/run --checkpoint best --out OUT/ROW/policy.safetensors`;
3. `hyq compare --backends rapier,dart,mujoco --policy mlp:OUT/ROW/policy.safetensors --episodes
   EPISODES --seed SEED --set reset.joint_noise_rad=0.05 --set reset.yaw_noise_deg=5 --out
   OUT/ROW/compare` (fresh episodes: seeds 1000 on chose no checkpoint).

A step whose output is already there is not run again, so an interrupted matrix resumes. Every
row has the same recipe, env count, steps and seed; only its engines differ. At the end (and
alone with `--table-only`) it writes `OUT/matrix.md` and `OUT/matrix.json`: each row's trunk
travel toward the goal per engine (mean with its 95 % bootstrap interval), reach rate and the
episodes that fell or hit a joint limit (Wilson 95 %), its training wall time with the load
average at its start and end (as the trainer measured them), and for each engine the row did not train on, the held-out ratio:
its mean travel over the training engines' mean (the per-episode mean of the training engines,
paired by episode), with the bootstrap interval (`hyq.stats.ratio_of_means`).
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
from pathlib import Path

import hyq.stats

ENGINES = ["rapier", "dart", "mujoco"]
ROWS = ["rapier", "dart", "mujoco", "rapier+dart", "rapier+mujoco", "dart+mujoco", "rapier+dart+mujoco"]
EXAMPLES = Path(__file__).resolve().parent
#: The scripts run from the checkout's root, named relative to it, so that the command a policy
#: file records (`training_command`) names no machine's folders but the output's.
REPO = EXAMPLES.parent
RESET_NOISE = ["--set", "reset.joint_noise_rad=0.05", "--set", "reset.yaw_noise_deg=5"]


def parse_rows(text: str) -> list[str]:
    rows = [r.strip() for r in text.split(",") if r.strip()]
    for row in rows:
        engines = row.split("+")
        if not engines or any(e not in ENGINES for e in engines) or len(set(engines)) != len(engines):
            raise SystemExit(f"error: --rows {row!r}: a row is engines from {ENGINES} joined by '+', each once")
    if not rows:
        raise SystemExit("error: --rows: no row given")
    return rows


def run_step(command: list[str], log: Path) -> None:
    """Runs `command`, its output to `log`; a failure stops the matrix with one line."""
    print("$", " ".join(command), flush=True)
    with open(log, "w", encoding="utf-8") as out:
        done = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, check=False, cwd=REPO)
    if done.returncode != 0:
        raise SystemExit(f"error: `{' '.join(command)}` failed ({done.returncode}); its output is in {log}")


def train_row(args: argparse.Namespace, row: str, directory: Path) -> None:
    run = directory / "run"
    policy = directory / "policy.safetensors"
    report = directory / "compare" / "report.json"
    directory.mkdir(parents=True, exist_ok=True)
    if not (run / "eval.json").exists():
        command = [sys.executable, "examples/train_sb3_ppo.py", "--recipe", args.recipe,
                   "--backends", row.replace("+", ","), "--envs", str(args.envs),
                   "--seed", str(args.train_seed), "--out", str(run)]
        if args.steps:
            command += ["--steps", str(args.steps)]
        if args.env:
            command += ["--env", args.env]
        run_step(command, directory / "train.log")
    if not policy.exists():
        run_step([sys.executable, "examples/export_policy.py", "--run", str(run), "--checkpoint", "best",
                  "--out", str(policy)], directory / "export.log")
    if not report.exists():
        run_step([args.hyq, "compare", "--backends", ",".join(ENGINES), "--policy", f"mlp:{policy}",
                  "--episodes", str(args.episodes), "--seed", str(args.seed), *RESET_NOISE,
                  "--out", str(directory / "compare")], directory / "compare.log")


def load_json(path: Path) -> dict:
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as err:
        raise SystemExit(f"error: {path}: {err}") from None


def row_result(row: str, directory: Path) -> dict:
    """One row's figures from its run's eval.json, load.json and its compare report.json."""
    report = load_json(directory / "compare" / "report.json")
    try:
        sides = {side["engine"]: side for side in report["sides"]}
        missing = [e for e in ENGINES if e not in sides]
        if missing:
            raise SystemExit(f"error: {directory}/compare/report.json: no side for {missing}")
        travel = {e: [ep["travel_m"] for ep in sides[e]["episodes"]] for e in ENGINES}
        per_engine = {
            e: {
                "travel_m": sides[e]["travel_m"],
                "reached": sides[e]["rates"]["reached"],
                "fell": sides[e]["rates"]["fell"],
                "joint_limit": sides[e]["rates"]["joint_limit"],
            }
            for e in ENGINES
        }
    except (KeyError, TypeError) as err:
        raise SystemExit(f"error: {directory}/compare/report.json: not a `hyq compare --policy` report ({err})") from None
    trained = row.split("+")
    held_out = {}
    if len(trained) < len(ENGINES):
        n = len(travel[trained[0]])
        if any(len(v) != n for v in travel.values()):
            raise SystemExit(f"error: {directory}/compare/report.json: the engines ran different episode counts")
        trained_mean = [sum(travel[e][k] for e in trained) / len(trained) for k in range(n)]
        for engine in ENGINES:
            if engine not in trained:
                held_out[engine] = hyq.stats.ratio_of_means(travel[engine], trained_mean, seed=0, paired=True)
    timing = load_json(directory / "run" / "eval.json").get("timing", {})
    return {"row": row, "engines": per_engine, "held_out": held_out, "timing": timing,
            "episodes": report.get("episodes"), "seed": report.get("seed")}


def rate_text(rate: dict) -> str:
    lo, hi = rate["ci95"]
    return f"{rate['k']} [{100 * lo:.0f}, {100 * hi:.0f}]"


def table(results: list[dict]) -> str:
    """The matrix as markdown: travel per engine, then reach and falls, held-out ratios, times."""
    head = "| trained on | " + " | ".join(f"travel on {e} (m)" for e in ENGINES) + \
        " | held out / trained | reached, k [95 %, in %]: r / D / M | fell or joint limit, k: r / D / M | training |"
    lines = [head, "|" + "---|" * (len(ENGINES) + 5)]
    for r in results:
        trained = r["row"].split("+")
        cells = []
        for e in ENGINES:
            text = hyq.stats.text(r["engines"][e]["travel_m"], digits=2)
            cells.append(f"**{text}**" if e in trained else text)
        held = "; ".join(f"{e} {hyq.stats.text(v)}" for e, v in r["held_out"].items()) or "none held out"
        reached = " / ".join(rate_text(r["engines"][e]["reached"]) for e in ENGINES)
        ends = " / ".join(
            str(r["engines"][e]["fell"]["k"] + r["engines"][e]["joint_limit"]["k"]) for e in ENGINES)
        t = r["timing"]
        train = f"{t['wall_s'] / 60:.2f} min, {t['env_steps']} steps" if "wall_s" in t else "?"
        if "load_average_start" in t:
            # The trainer records `uptime`'s three figures; the first is the last minute's.
            train += f" (load {t['load_average_start'][0]:.1f}-{t['load_average_end'][0]:.1f})"
        lines.append(f"| {r['row'].replace('+', ' + ')} | " + " | ".join(cells) +
                     f" | {held} | {reached} | {ends} | {train} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True, help="the matrix's directory (one folder per row)")
    parser.add_argument("--rows", default=",".join(ROWS), help="rows, comma-separated (default: all seven)")
    parser.add_argument("--recipe", default="walk", help="train_sb3_ppo.py's recipe (default: walk)")
    parser.add_argument("--env", help="JSON object of training-environment keys to change (train_sb3_ppo.py --env)")
    parser.add_argument("--envs", type=int, default=12, help="training envs, split round-robin over the row's engines")
    parser.add_argument("--steps", type=int, help="training env steps (default: the recipe's)")
    parser.add_argument("--train-seed", type=int, default=0)
    parser.add_argument("--episodes", type=int, default=100, help="evaluation episodes per engine")
    parser.add_argument("--seed", type=int, default=1000, help="the evaluation's first seed")
    parser.add_argument("--hyq", default=shutil.which("hyq") or "hyq",
                        help="a hyq built with --features dart,mujoco (default: hyq on PATH)")
    parser.add_argument("--table-only", action="store_true", help="only write the table from the rows already run")
    args = parser.parse_args()
    rows = parse_rows(args.rows)
    args.out = args.out.resolve()
    if not args.table_only:
        for row in rows:
            train_row(args, row, args.out / row)
    results = [row_result(row, args.out / row) for row in rows]
    text = table(results)
    (args.out / "matrix.md").write_text(text, encoding="utf-8")
    (args.out / "matrix.json").write_text(json.dumps(results, indent=1), encoding="utf-8")
    print(text, end="")


if __name__ == "__main__":
    sys.exit(main())
