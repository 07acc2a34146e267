"""What the training examples share: the environments they train in (the recipes), the
deterministic evaluation, the learning curve and the run's timing and load.

Imported by examples/train_sb3_ppo.py and examples/train_rsl_rl.py (run them as scripts from
anywhere: Python puts this directory on the import path). Needs numpy and the `hyq` package;
matplotlib only to draw a curve.

A recipe is the environment a policy trains in, as the package's keyword arguments, with the
robot and the engine it trains on. Every key is a spec user variable or one of the project's
own tables; docs/training.md has the experiments behind each value.
"""

from __future__ import annotations

import csv
import json
import os
import subprocess
import time
from pathlib import Path
from typing import Any, Callable

import numpy as np

import hyq
import hyq.stats
from hyq.vector import HyQVectorEnv

#: The walk: the spec's task (the goal 5 m ahead, the default 1 mm reach cube) with shaping
#: from its user variables and the project's `offset` action mode.
WALK_ENV: dict[str, Any] = {
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

#: The reach: the walk with a 10 cm reach cube (spec §6.1: the trunk centre within 5 cm of the
#: goal on x, y and z) and a bonus for entering it (§4.4). The bonus is larger than everything
#: else an episode can earn (r_n's k_norm = 10 plus r_e's (e^5 − 1)/5 ≈ 29.5), so walking
#: through the cube beats walking near it; and reaching ends the episode, so the policy no
#: longer pays back r_n and r_e by walking past the goal.
REACH_ENV: dict[str, Any] = {
    **WALK_ENV,
    "accepted_error": 0.1,
    "reach_target_bonus_reward": 50.0,
}

#: The walk with randomised dynamics, actuator, observation noise and pushes ([randomize],
#: docs/robustness.md), each range from an anchor where one has it: the policy must walk on
#: ground, masses, gains and delays it was not tuned to, and keep walking when pushed, so that
#: it transfers to the engines it did not train on (docs/robustness.md has the evaluation).
WALK_RANDOMIZED_ENV: dict[str, Any] = {
    **WALK_ENV,
    "randomize": {
        # legged_gym's friction range: the committed walker's travel falls with friction.
        "ground_friction": [0.5, 1.25],
        # Isaac Lab's base-mass range (±5 kg; 6 % of HyQ's 87 kg) and its centre-of-mass shift.
        "trunk_added_mass_kg": [-5.0, 5.0],
        "trunk_com_offset_m": [[-0.05, 0.05], [-0.05, 0.05], [-0.01, 0.01]],
        # MuJoCo Playground's link-mass factor.
        "link_mass_scale": [0.9, 1.1],
        # Gains ±10 % and a delay of up to 2 ms (2 sub-steps): HyQ's hydraulic valves lag.
        "kp_scale": [0.9, 1.1],
        "kd_scale": [0.9, 1.1],
        "actuator_delay_substeps": [0, 2],
        # legged_gym's joint-angle noise; a light joint-speed noise.
        "obs_noise": {"joint_angle": 0.01, "joint_speed": 0.1},
        # The pushes the policy is judged under: up to 0.5 m/s every 2-4 s.
        "push_interval_s": [2.0, 4.0],
        "push_velocity_xy_mps": [0.0, 0.5],
    },
}

#: The walk on rough ground (docs/terrain.md): bumps of up to 5 cm (legged_gym's random
#: terrain is 2-10 cm), new ground every episode from the reset seed, legged_gym's curriculum
#: (the relief grows by tenths as episodes get half way to the goal, and shrinks when they do
#: not get a quarter of the way), and the height scan around the trunk (17 x 11 points, 10 cm
#: apart: legged_gym's measured points) beside the spec's 39 rows.
WALK_ROUGH_ENV: dict[str, Any] = {
    **WALK_ENV,
    "terrain": {"kind": "rough", "amplitude_m": 0.05, "seed": "episode", "curriculum": True},
    "observation": {"extra": ["height_scan"]},
}

#: name -> (environment, robot, backend, and, where the checkpoints' evaluation differs from
#: the training environment, "eval_env": changes merged over it). MuJoCo steps about 3x faster
#: than rapier (the README's speed table), and the env is most of a training run's time on 2
#: cores, so the recipes train there; the policy file runs on every engine (docs/training.md).
RECIPES: dict[str, dict[str, Any]] = {
    "walk": {"env": WALK_ENV, "robot": "hyq", "backend": "mujoco"},
    "reach": {"env": REACH_ENV, "robot": "hyq", "backend": "mujoco"},
    "anymal_walk": {"env": WALK_ENV, "robot": "anymal_c", "backend": "mujoco"},
    "walk_randomized": {"env": WALK_RANDOMIZED_ENV, "robot": "hyq", "backend": "mujoco"},
    # Its checkpoints are judged on the full relief: the curriculum's first level is a tenth of it.
    "walk_rough": {"env": WALK_ROUGH_ENV, "robot": "hyq", "backend": "mujoco",
                   "eval_env": {"terrain": {"curriculum": False}}},
}

#: The checkpoints' evaluation: EVAL_EPISODES episodes, env i seeded EVAL_SEED + i, with the
#: recipe's reset noise; the deterministic policy. These seeds choose the best checkpoint, so the
#: figures the docs report come from other episodes: `hyq compare --policy --seed 1000`
#: (seed 1000 and its continued streams).
EVAL_EPISODES = 20
EVAL_SEED = 2000


def check_backend(backend: str, option: str | None = None) -> None:
    """Exits with one line when the package was built without `backend` (asked for by
    `option`, `--backend <name>` unless given)."""
    if backend not in hyq.BACKENDS:
        raise SystemExit(
            f"error: {option or '--backend ' + backend}: this build of the hyq package has {list(hyq.BACKENDS)}; "
            f"build it with `maturin develop --release --features {backend}` (after `cargo xtask "
            f"setup mujoco` for MuJoCo) or pass --backend rapier"
        )


def engines_of(backend: str | None, backends: str | None, default: str) -> list[str]:
    """The engines a run trains on: `--backends A,B,...` (each env of the vector env on the next
    engine of the list, round-robin), else `--backend`, else the recipe's; each built in."""
    if backend is not None and backends is not None:
        raise SystemExit("error: --backend and --backends: give one of them")
    if backends is None:
        names = [backend or default]
    else:
        names = [name.strip() for name in backends.split(",")]
        if not all(names):
            raise SystemExit(f"error: --backends {backends!r}: expected engine names separated "
                             "by commas, e.g. rapier,dart,mujoco")
    for name in dict.fromkeys(names):
        check_backend(name, None if backends is None else f"--backends {backends}")
    return names


def merge(base: dict[str, Any], changes: dict[str, Any]) -> dict[str, Any]:
    """`base` with `changes` applied; a table given as a dict is merged key by key, so
    `{"reset": {"yaw_noise_deg": 0}}` keeps the other reset keys."""
    out = dict(base)
    for key, value in changes.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = {**out[key], **value}
        else:
            out[key] = value
    return out


def distance_walked(info: dict[str, Any]) -> float:
    """K - D^T: how much closer to the goal the trunk ended than it started (m)."""
    goal = np.asarray(info["goal"], dtype=np.float64)
    start = np.asarray(info["initial_position"], dtype=np.float64)
    return float(np.linalg.norm(goal - start) - info["distance_to_goal"])


def evaluate(
    act: Callable[[np.ndarray], np.ndarray],
    env: dict[str, Any],
    robot: str,
    backend: str,
) -> dict[str, Any]:
    """The deterministic policy `act` (a batch of float32 observations to a batch of actions)
    on EVAL_EPISODES episodes: env i seeded EVAL_SEED + i, its first episode counts."""
    venv = HyQVectorEnv(num_envs=EVAL_EPISODES, robot=robot, backend=backend,
                        autoreset_mode="SameStep", **env)
    obs, _ = venv.reset(seed=EVAL_SEED)
    episodes: list[dict[str, Any] | None] = [None] * EVAL_EPISODES
    returns = np.zeros(EVAL_EPISODES)
    while any(e is None for e in episodes):
        obs, rewards, terminated, truncated, _ = venv.step(act(obs))
        for i in range(EVAL_EPISODES):
            if episodes[i] is None:
                returns[i] += rewards[i]
                if terminated[i] or truncated[i]:
                    info = venv.final_info(i)
                    episodes[i] = {
                        "return": float(returns[i]),
                        "distance_m": distance_walked(info),
                        "steps": int(info["t"]),
                        # The reasons that held, joined by "+" ("reached", "joint_limit+fell").
                        "reasons": info["reasons"].split("+"),
                    }
    venv.close()
    return summarize([e for e in episodes if e is not None])


def summarize(done: list[dict[str, Any]]) -> dict[str, Any]:
    """An evaluation's result from its episodes: the means and rates, their 95 % intervals
    (`estimates`) and evals.csv's interval columns."""
    estimates = eval_estimates(done)
    result: dict[str, Any] = {
        "episodes": done,
        "mean_return": estimates["return"]["mean"],
        "mean_distance_m": estimates["distance_m"]["mean"],
        "fall_rate": estimates["fell"]["mean"],
        "joint_limit_rate": estimates["joint_limit"]["mean"],
        "reach_rate": estimates["reached"]["mean"],
        # Each figure as report.json gives it: {"mean", "ci95": [lo, hi]} (a rate adds k, n).
        "estimates": estimates,
    }
    for column, key in EVAL_INTERVALS.items():
        lo, hi = estimates[key]["ci95"]
        result[f"{column}_lo"], result[f"{column}_hi"] = lo, hi
    return result


#: The evaluation's figures whose 95 % interval ends evals.csv records (as `<column>_lo` and
#: `<column>_hi`), with their key in `estimates`.
EVAL_INTERVALS = {
    "mean_return": "return",
    "mean_distance_m": "distance_m",
    "fall_rate": "fell",
    "joint_limit_rate": "joint_limit",
    "reach_rate": "reached",
}


def eval_estimates(done: list[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """The evaluation episodes' mean return and distance walked with their 95 % bootstrap
    intervals (seeded with EVAL_SEED, so a repeated run records the same), and the rates of
    falling, a joint limit and reaching the goal with their Wilson 95 % intervals, all from the
    Rust hyq-stats through `hyq.stats` (the code `hyq compare --policy` reports with)."""
    n = len(done)
    rate = lambda reason: hyq.stats.wilson(sum(reason in e["reasons"] for e in done), n)  # noqa: E731
    return {
        "return": hyq.stats.mean_ci([e["return"] for e in done], seed=EVAL_SEED),
        "distance_m": hyq.stats.mean_ci([e["distance_m"] for e in done], seed=EVAL_SEED),
        "fell": rate("fell"),
        "joint_limit": rate("joint_limit"),
        "reached": rate("reached"),
    }


def evaluate_engines(
    act: Callable[[np.ndarray], np.ndarray],
    env: dict[str, Any],
    robot: str,
    backends: list[str],
) -> dict[str, Any]:
    """`evaluate` on every engine of `backends` (each once, in the list's order). One engine:
    its result as `evaluate` gives it. Several: the means over all their episodes, each
    engine's result under `per_engine`, and `worst_reach_rate`, the lowest engine's reach rate,
    which chooses the best checkpoint (`checkpoint_score`): a policy must reach on every engine
    it was trained on."""
    engines = list(dict.fromkeys(backends))
    per_engine = {name: evaluate(act, env, robot, name) for name in engines}
    if len(engines) == 1:
        return per_engine[engines[0]]
    done = [e for result in per_engine.values() for e in result["episodes"]]
    return {
        **summarize(done),
        "worst_reach_rate": min(r["reach_rate"] for r in per_engine.values()),
        "per_engine": per_engine,
    }


def checkpoint_score(result: dict[str, Any]) -> tuple[float, float]:
    """What the best checkpoint maximises: the reach rate (on several engines, the worst
    engine's), then the mean return."""
    return (result.get("worst_reach_rate", result["reach_rate"]), result["mean_return"])


def eval_fields(backends: list[str]) -> list[str]:
    """evals.csv's columns: EVAL_FIELDS, then, on several engines, each engine's distance and
    reach rate (`<engine>_mean_distance_m`, `<engine>_reach_rate`)."""
    engines = list(dict.fromkeys(backends))
    if len(engines) == 1:
        return EVAL_FIELDS
    return EVAL_FIELDS + [f"{e}_{k}" for e in engines for k in ("mean_distance_m", "reach_rate")]


def eval_row(env_steps: int, result: dict[str, Any], fields: list[str]) -> dict[str, float]:
    """evals.csv's row of `result` (see `eval_fields`)."""
    row = {"env_steps": env_steps, **{k: result[k] for k in EVAL_FIELDS[1:]}}
    for engine, r in result.get("per_engine", {}).items():
        for key in ("mean_distance_m", "reach_rate"):
            row[f"{engine}_{key}"] = r[key]
    return {k: row[k] for k in fields}


def eval_summary(result: dict[str, Any]) -> str:
    """One line of an evaluation's means with their 95 % intervals and its rates as k/n with
    their Wilson 95 % intervals (on several engines, then each engine's distance and reach)."""
    e = result["estimates"]
    text = hyq.stats.text
    line = (
        f"return {text(e['return'], 2)}, distance {text(e['distance_m'], 2)} m, "
        f"fell {text(e['fell'])}, joint limit {text(e['joint_limit'])}, "
        f"reached {text(e['reached'])} (mean [95 % CI])"
    )
    for engine, r in result.get("per_engine", {}).items():
        line += (f"; {engine}: distance {text(r['estimates']['distance_m'], 2)} m, "
                 f"reached {text(r['estimates']['reached'])}")
    return line


def git_commit() -> str:
    """The commit of the checkout the script runs from ("unknown" outside git)."""
    try:
        return subprocess.run(
            ["git", "rev-parse", "HEAD"], capture_output=True, text=True, check=True,
            cwd=Path(__file__).resolve().parent,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def load_average() -> list[float]:
    """The 1, 5 and 15 minute load averages (what `uptime` prints)."""
    return [round(x, 2) for x in os.getloadavg()]


class Clock:
    """The run's wall time, the part of it spent stepping the training envs (`env_s`, summed
    by whoever steps them) and the part spent in the checkpoints' evaluations (`eval_s`), with
    the load average at the start and the end: a figure taken while other work shares the
    cores is not the recipe's own."""

    def __init__(self) -> None:
        self.start = time.monotonic()
        self.load_start = load_average()
        self.env_s = 0.0
        self.eval_s = 0.0

    def summary(self, env_steps: int) -> dict[str, Any]:
        wall = time.monotonic() - self.start
        return {
            "wall_s": wall,
            "env_steps": env_steps,
            "env_steps_per_s": env_steps / wall,
            "env_stepping_s": self.env_s,
            "evaluation_s": self.eval_s,
            "learning_and_rest_s": wall - self.env_s - self.eval_s,
            "load_average_start": self.load_start,
            "load_average_end": load_average(),
            "cpu_count": os.cpu_count(),
        }


def timing_line(t: dict[str, Any]) -> str:
    """One line of a run's timing."""
    return (
        f"{t['env_steps']} env steps in {t['wall_s'] / 60:.2f} min ({t['env_steps_per_s']:.0f}/s): "
        f"env stepping {t['env_stepping_s']:.0f} s, checkpoint evaluations {t['evaluation_s']:.0f} s, "
        f"learning and the rest "
        f"{t['learning_and_rest_s']:.0f} s; load average {t['load_average_start']} at the start, "
        f"{t['load_average_end']} at the end"
    )


class CurveFile:
    """Rows of a CSV file, flushed as they come, kept for the plot."""

    def __init__(self, path: Path, fields: list[str]) -> None:
        self.fields = fields
        self.rows: list[dict[str, float]] = []
        self.file = open(path, "w", newline="")
        self.writer = csv.DictWriter(self.file, fieldnames=fields)
        self.writer.writeheader()

    def add(self, row: dict[str, float]) -> None:
        self.writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
        self.file.flush()
        self.rows.append(row)

    def close(self) -> None:
        self.file.close()


#: The columns of progress.csv (the training episodes) and evals.csv (the deterministic
#: evaluations).
PROGRESS_FIELDS = [
    "env_steps", "episodes", "mean_return", "mean_distance_m", "fall_rate",
    "joint_limit_rate", "reach_rate", "mean_length", "env_steps_per_s",
]
EVAL_FIELDS = [
    "env_steps", "mean_return", "mean_distance_m", "fall_rate", "joint_limit_rate", "reach_rate",
    *(f"{column}_{end}" for column in EVAL_INTERVALS for end in ("lo", "hi")),
]


class EpisodeLog:
    """The training episodes' final facts, pooled until a curve row is written."""

    def __init__(self, min_episodes: int) -> None:
        self.min_episodes = min_episodes
        self.pending: list[dict[str, float]] = []

    def add(self, ret: float, length: float, info: dict[str, Any]) -> None:
        self.pending.append({
            "return": ret,
            "length": length,
            "distance": distance_walked(info),
            "fell": float(info["fell"]),
            "joint_limit": float(info["joint_limit"]),
            "reached": float(info["reached"]),
        })

    def row(self, env_steps: int, elapsed_s: float) -> dict[str, float] | None:
        """A progress row of the pooled episodes (and forget them), or None while fewer than
        `min_episodes` ended."""
        if len(self.pending) < self.min_episodes:
            return None
        mean = lambda key: float(np.mean([e[key] for e in self.pending]))  # noqa: E731
        row = {
            "env_steps": env_steps,
            "episodes": len(self.pending),
            "mean_return": mean("return"),
            "mean_distance_m": mean("distance"),
            "fall_rate": mean("fell"),
            "joint_limit_rate": mean("joint_limit"),
            "reach_rate": mean("reached"),
            "mean_length": mean("length"),
            "env_steps_per_s": env_steps / elapsed_s,
        }
        self.pending.clear()
        return row


def plot_curve(rows: list[dict[str, float]], evals: list[dict[str, float]], path: Path, title: str) -> None:
    """The learning curve as a 2x2 PNG (matplotlib, no display): the training episodes
    (stochastic policy) as lines, the deterministic evaluations as points."""
    if not rows and not evals:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x = np.array([r["env_steps"] for r in rows]) / 1e6
    col = lambda key: np.array([r[key] for r in rows])  # noqa: E731
    ex = np.array([r["env_steps"] for r in evals]) / 1e6
    ecol = lambda key: np.array([r[key] for r in evals])  # noqa: E731
    fig, axes = plt.subplots(2, 2, figsize=(10, 6.5), sharex=True)
    if rows:
        axes[0, 0].plot(x, col("mean_return"), label="training episodes")
        axes[0, 1].plot(x, col("mean_distance_m"))
        axes[1, 0].plot(x, col("fall_rate"), label="fell", color="C0")
        axes[1, 0].plot(x, col("joint_limit_rate"), label="joint limit", color="C1")
        axes[1, 0].plot(x, col("reach_rate"), label="reached", color="C2")
        axes[1, 1].plot(x, col("mean_length") / 100.0)
    if evals:
        # The evaluations' means with their 95 % intervals as error bars (rows of an evals.csv
        # written before the intervals were recorded have none).
        def bars(key: str) -> np.ndarray | None:
            if not all(f"{key}_lo" in r for r in evals):
                return None
            return np.abs(np.array([ecol(f"{key}_lo"), ecol(f"{key}_hi")]) - ecol(key))

        axes[0, 0].errorbar(ex, ecol("mean_return"), yerr=bars("mean_return"), fmt="o", color="C3",
                            label="deterministic, 20 eval episodes, 95 % CI")
        axes[0, 1].errorbar(ex, ecol("mean_distance_m"), yerr=bars("mean_distance_m"), fmt="o", color="C3")
        axes[1, 0].plot(ex, ecol("fall_rate"), "o", color="C0")
        axes[1, 0].plot(ex, ecol("joint_limit_rate"), "o", color="C1")
        axes[1, 0].plot(ex, ecol("reach_rate"), "s", color="C2")
    axes[0, 0].set_ylabel("mean episode return")
    axes[0, 0].legend(loc="best")
    axes[0, 1].set_ylabel("distance walked toward the goal (m)")
    axes[1, 0].set_ylabel("fraction of episodes")
    axes[1, 0].set_ylim(-0.02, 1.02)
    if rows:
        axes[1, 0].legend(loc="best")
    axes[1, 1].set_ylabel("mean episode length (s)")
    for ax in axes[1]:
        ax.set_xlabel("env steps (millions)")
    for ax in axes.flat:
        ax.grid(alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def write_json(path: Path, data: Any) -> None:
    path.write_text(json.dumps(data, indent=2) + "\n")
