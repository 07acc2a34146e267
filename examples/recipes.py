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
import math
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

#: Go1 (12.7 kg, kp 35 servos) on the walk's environment with a fall costing four times as much
#: and legged_gym's action-rate regulariser: with the walk's own fall penalty its walkers fell in
#: 7-39 of 60 episodes (docs/training.md, "Go1").
GO1_WALK_ENV: dict[str, Any] = {
    **WALK_ENV,
    "fall_penalty": 20.0,
    "regularizers": {"action_rate": -0.01},
}

#: The velocity-command task (docs/velocity.md): follow a commanded forward and sideways speed
#: and yaw rate. MuJoCo Playground's reward preset (its orientation, stand-still and termination
#: terms teach a level trunk and a still stand at a zero command; legged_gym's 0.5 s air-time
#: threshold is a long swing for HyQ's size) and Playground's command rule (each component kept,
#: redrawn or zeroed after an exponential time of mean 5 s), with narrower ranges than either
#: anchor's (theirs are ±1 to 1.5 m/s for robots a tenth of HyQ's mass; a CPU run has a small
#: budget, spent around the commands the checkpoints are judged at); the walk's action mode
#: (Playground's action scale 0.5 rad) and reset noise.
VELOCITY_ENV: dict[str, Any] = {
    "task": {"kind": "velocity"},
    "velocity": {"preset": "playground"},
    "command": {
        "lin_vel_x": [-0.3, 0.8],
        "lin_vel_y": [-0.2, 0.2],
        "ang_vel_yaw": [-0.8, 0.8],
        "resampling": "keep_zero",
        "timing": "exponential",
        "resampling_time_s": 5.0,
        # Playground's 0.9, 0.25, 0.5 for (v_x, v_y, ω_z), with a share of whole standing
        # draws besides (mjlab's 0.1): the robot must learn to stand still, not to step in place.
        "keep_nonzero_probability": [0.9, 0.25, 0.5],
        "standing_probability": 0.1,
    },
    "action": {"mode": "offset", "max_offset_rad": 0.5},
    "reset": {"joint_noise_rad": 0.05, "yaw_noise_deg": 5.0},
}

#: The velocity task's first stage for HyQ, resumed from the rsl_rl walk at 150 iterations
#: (docs/velocity.md, "Why the runs stood"): forward commands of 0.3-0.6 m/s only, no standing or turning
#: draws; a narrower tracking kernel (σ 0.1, where standing at 0.3 m/s earns 0.41 of a tracking
#: term's maximum against 0.70 at Playground's 0.25); Playground's torque cost scaled down tenfold
#: (its −2e-4 is for Go1's torques, a twentieth of HyQ's); and the action rate fifty times
#: Playground's (−0.5): at −0.01 the runs' deterministic policy stood while the training noise
#: (σ 0.13 on the actions) shuffled the robot forward, 0.54 m/s at a 0.6 m/s command with the
#: noise and 0.01 m/s without it.
VELOCITY_FORWARD_ENV: dict[str, Any] = {
    **VELOCITY_ENV,
    "velocity": {**VELOCITY_ENV["velocity"], "tracking_sigma": 0.1, "torques_abs": -2e-5,
                 "action_rate": -0.5},
    "command": {**VELOCITY_ENV["command"], "lin_vel_x": [0.3, 0.6], "lin_vel_y": [0.0, 0.0],
                "ang_vel_yaw": [0.0, 0.0], "standing_probability": 0.0,
                "keep_nonzero_probability": [1.0, 0.25, 0.5]},
}

#: name -> (environment, robot, backend (one engine, or several joined by commas), optionally
#: "envs" (the vector env's size, else 16), and, where the checkpoints' evaluation differs from
#: the training environment, "eval_env": changes merged over it). MuJoCo steps about 3x faster
#: than rapier (the README's speed table), and the env is most of a training run's time on 2
#: cores, so the recipes train there; the policy file runs on every engine (docs/training.md).
RECIPES: dict[str, dict[str, Any]] = {
    "walk": {"env": WALK_ENV, "robot": "hyq", "backend": "mujoco"},
    "reach": {"env": REACH_ENV, "robot": "hyq", "backend": "mujoco"},
    "anymal_walk": {"env": WALK_ENV, "robot": "anymal_c", "backend": "mujoco"},
    # Trained on the three engines at once (15 envs, five each), judged on each.
    "go1_walk": {"env": GO1_WALK_ENV, "robot": "go1", "backend": "rapier,dart,mujoco", "envs": 15},
    "walk_randomized": {"env": WALK_RANDOMIZED_ENV, "robot": "hyq", "backend": "mujoco"},
    # Its checkpoints are judged on the full relief: the curriculum's first level is a tenth of it.
    "walk_rough": {"env": WALK_ROUGH_ENV, "robot": "hyq", "backend": "mujoco",
                   "eval_env": {"terrain": {"curriculum": False}}},
    # Its checkpoints are judged by tracking error at fixed commands (VELOCITY_EVAL_COMMANDS).
    "velocity": {"env": VELOCITY_ENV, "robot": "hyq", "backend": "mujoco", "evaluation": "velocity"},
    "velocity_forward": {"env": VELOCITY_FORWARD_ENV, "robot": "hyq", "backend": "mujoco",
                         "evaluation": "velocity"},
}

#: The checkpoints' evaluation: EVAL_EPISODES episodes, env i seeded EVAL_SEED + i, with the
#: recipe's reset noise; the deterministic policy. These seeds choose the best checkpoint, so the
#: figures the docs report come from other episodes: `hyq compare --policy --seed 1000`
#: (seed 1000 and its continued streams).
EVAL_EPISODES = 20
EVAL_SEED = 2000


def check_action_noise(std: float | None) -> None:
    """Exits with one line unless `std` (`--action-noise`, None when not given) is a finite
    number above 0."""
    if std is not None and not (math.isfinite(std) and std > 0):
        raise SystemExit(f"error: --action-noise {std}: must be a finite number above 0")


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
    engine of the list, round-robin), else `--backend`, else the recipe's (one engine, or several
    separated by commas); each built in."""
    if backend is not None and backends is not None:
        raise SystemExit("error: --backend and --backends: give one of them")
    if backends is None:
        names = [backend] if backend is not None else default.split(",")
    else:
        names = [name.strip() for name in backends.split(",")]
        if not all(names):
            raise SystemExit(f"error: --backends {backends!r}: expected engine names separated "
                             "by commas, e.g. rapier,dart,mujoco")
    for name in dict.fromkeys(names):
        check_backend(name, None if backends is None else f"--backends {backends}")
    return names


def envs_of(envs: int | None, recipe: dict[str, Any]) -> int:
    """The vector env's size: `--envs`, else the recipe's, else 16."""
    return envs if envs is not None else recipe.get("envs", 16)


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


def eps_curriculum(text: str) -> dict[str, Any]:
    """`--eps-curriculum START:END:STEPS[:STAGES]`: the reach cube's side (`accepted_error`, m)
    in the training envs goes from START to END in STAGES equal stages (default 5), the last
    (END) starting at STEPS env steps: a large cube first, so that the reach bonus is found
    while the gait is still crude, and the recipe's cube from STEPS on. One-line error on bad
    input."""
    fields = text.split(":")
    usage = (f"error: --eps-curriculum {text!r}: expected START:END:STEPS[:STAGES], e.g. "
             "0.5:0.1:600000 (the cube's side in m from START to END, in STAGES stages, the "
             "last from STEPS env steps on)")
    if len(fields) not in (3, 4):
        raise SystemExit(usage)
    try:
        start, end = float(fields[0]), float(fields[1])
        steps = int(fields[2])
        stages = int(fields[3]) if len(fields) == 4 else 5
    except ValueError:
        raise SystemExit(usage) from None
    if not (np.isfinite(start) and np.isfinite(end) and start > 0.0 and end > 0.0):
        raise SystemExit(f"error: --eps-curriculum {text!r}: START and END must be finite sides "
                         "above 0 m")
    if steps < 1 or stages < 2:
        raise SystemExit(f"error: --eps-curriculum {text!r}: STEPS must be at least 1 and STAGES "
                         "at least 2")
    return {"start": start, "end": end, "steps": steps, "stages": stages}


def curriculum_stage(curriculum: dict[str, Any], env_steps: int) -> tuple[int, float]:
    """The stage (0 first) and its cube side after `env_steps`: stage k of n starts at
    k·STEPS/(n − 1) env steps with the side START + (END − START)·k/(n − 1)."""
    last = curriculum["stages"] - 1
    stage = min(last, env_steps * last // curriculum["steps"])
    # Written so that the first stage is START and the last END to the bit.
    f = stage / last
    return stage, curriculum["start"] * (1.0 - f) + curriculum["end"] * f


def git_commit() -> str:
    """The commit of the checkout the script runs from ("unknown" outside git)."""
    try:
        return subprocess.run(
            ["git", "rev-parse", "HEAD"], capture_output=True, text=True, check=True,
            cwd=Path(__file__).resolve().parent,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def command_with_prior(argv: list[str], resume: Path | None) -> str:
    """The run's command (`argv` joined); a resumed run's is preceded by the command of the run
    it resumes, read from that run's config.json (beside `resume`, or one folder up from a
    `checkpoints/` folder), so the exported file names every stage."""
    command = " ".join(argv)
    if resume is not None:
        run = resume.parent.parent if resume.parent.name == "checkpoints" else resume.parent
        prior = run / "config.json"
        if prior.is_file():
            command = f"{json.loads(prior.read_text())['command']} && {command}"
    return command


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


# The velocity recipe's evaluation: tracking error at fixed commands, not the goal's reach.

#: The fixed commands (v_x in m/s, ω_z in rad/s; v_y = 0) the velocity recipe's checkpoints
#: are judged at: standing, two forward speeds, and turning on the spot both ways (the
#: commands docs/velocity.md reports); VELOCITY_EVAL_PER_COMMAND episodes each, so
#: EVAL_EPISODES in all, env j of command k seeded EVAL_SEED + k * VELOCITY_EVAL_PER_COMMAND + j.
VELOCITY_EVAL_COMMANDS: list[tuple[float, float]] = [(0.0, 0.0), (0.3, 0.0), (0.6, 0.0), (0.0, 0.5), (0.0, -0.5)]
VELOCITY_EVAL_PER_COMMAND = EVAL_EPISODES // len(VELOCITY_EVAL_COMMANDS)


def fixed_command(env: dict[str, Any], vx: float, yaw: float) -> dict[str, Any]:
    """`env` with the command fixed at (vx, 0, yaw) for the whole episode: every range a point,
    no standing draws, legged_gym's redraw rule (which keeps a point range's value)."""
    return merge(env, {"command": {
        "lin_vel_x": [vx, vx], "lin_vel_y": [0.0, 0.0], "ang_vel_yaw": [yaw, yaw],
        "resampling": "uniform", "standing_probability": 0.0, "min_lin_vel_mps": 0.0,
    }})


def trunk_xy_rows(names: list[str]) -> list[int]:
    """The observation rows of the trunk's horizontal position: the spec's position rows, named
    after the robot's trunk link (`trunk_position_x` on HyQ, `base_position_x` on ANYmal C)."""
    rows = [i for axis in "xy" for i, name in enumerate(names) if name.endswith(f"_position_{axis}")]
    if len(rows) != 2:
        raise ValueError(f"expected one trunk position row per axis, found {[names[i] for i in rows]}")
    return rows


def track_command(act: Callable[[np.ndarray], np.ndarray], env: dict[str, Any], robot: str,
                  backend: str, command: tuple[float, float], seed: int) -> list[dict[str, Any]]:
    """VELOCITY_EVAL_PER_COMMAND first episodes of the deterministic `act` at the fixed
    `command`, env j seeded `seed` + j: each one's mean |c_x − v_x| and |c_yaw − ω_z| over its
    steps (v and ω in the trunk's frame, as the task tracks them), the trunk's horizontal drift
    from its start, its return, steps and end reasons."""
    n = VELOCITY_EVAL_PER_COMMAND
    venv = HyQVectorEnv(num_envs=n, robot=robot, backend=backend, autoreset_mode="SameStep",
                        **fixed_command(env, *command))
    xy = trunk_xy_rows([row.name for row in venv.observation_table])
    obs, _ = venv.reset(seed=seed)
    start = obs[:, xy]
    sums = np.zeros((n, 3))  # forward error, yaw error, return
    episodes: list[dict[str, Any] | None] = [None] * n
    while any(e is None for e in episodes):
        obs, rewards, terminated, truncated, infos = venv.step(act(obs))
        for i in range(n):
            if episodes[i] is not None:
                continue
            done = bool(terminated[i] or truncated[i])
            info = venv.final_info(i) if done else {k: infos[k][i] for k in ("velocity.command",
                                                                             "velocity.lin_vel", "velocity.ang_vel")}
            c, v, w = (np.asarray(info[k]) for k in ("velocity.command", "velocity.lin_vel", "velocity.ang_vel"))
            sums[i] += (abs(c[0] - v[0]), abs(c[2] - w[2]), rewards[i])
            if done:
                steps = int(info["t"])
                end = venv.final_observation(i)[xy]
                episodes[i] = {
                    "command": list(command), "steps": steps, "return": float(sums[i, 2]),
                    "forward_error_mps": float(sums[i, 0] / steps),
                    "yaw_error_radps": float(sums[i, 1] / steps),
                    "drift_m": float(np.linalg.norm(end - start[i])),
                    "reasons": info["reasons"].split("+"),
                }
    venv.close()
    return [e for e in episodes if e is not None]


def evaluate_velocity(act: Callable[[np.ndarray], np.ndarray], env: dict[str, Any], robot: str,
                      backend: str) -> dict[str, Any]:
    """The deterministic policy `act` at every command of VELOCITY_EVAL_COMMANDS
    (`track_command`), summarised by `summarize_velocity`."""
    done: list[dict[str, Any]] = []
    for k, command in enumerate(VELOCITY_EVAL_COMMANDS):
        done += track_command(act, env, robot, backend, command, EVAL_SEED + k * VELOCITY_EVAL_PER_COMMAND)
    return summarize_velocity(done)


def summarize_velocity(done: list[dict[str, Any]]) -> dict[str, Any]:
    """A velocity evaluation's figures with their 95 % intervals (hyq.stats, bootstrap seeded
    with EVAL_SEED; rates Wilson's): the forward-speed error over the episodes commanded to
    walk forward or stand, the yaw-rate error over those commanded to turn, the drift over the
    standing episodes, the return and the fall rate."""
    mean = lambda key, keep: hyq.stats.mean_ci([e[key] for e in done if keep(e["command"])], seed=EVAL_SEED)  # noqa: E731
    estimates = {
        "return": mean("return", lambda c: True),
        "forward_error_mps": mean("forward_error_mps", lambda c: c[1] == 0.0),
        "yaw_error_radps": mean("yaw_error_radps", lambda c: c[1] != 0.0),
        "standing_drift_m": mean("drift_m", lambda c: c == [0.0, 0.0]),
        "fell": hyq.stats.wilson(sum("fell" in e["reasons"] for e in done), len(done)),
    }
    result: dict[str, Any] = {"episodes": done, "estimates": estimates,
                              "fall_rate": estimates["fell"]["mean"]}
    for key in VELOCITY_EVAL_FIELDS[1:]:
        figure = "fell" if key == "fall_rate" else key.removeprefix("mean_")
        result[key] = estimates[figure]["mean"]
        result[f"{key}_lo"], result[f"{key}_hi"] = estimates[figure]["ci95"]
    return result


#: evals.csv's columns under the velocity recipe, each figure followed by its interval's ends.
VELOCITY_EVAL_FIELDS = ["env_steps", "mean_return", "forward_error_mps", "yaw_error_radps",
                        "standing_drift_m", "fall_rate"]


def evaluate_velocity_engines(act: Callable[[np.ndarray], np.ndarray], env: dict[str, Any], robot: str,
                              backends: list[str]) -> dict[str, Any]:
    """`evaluate_velocity` on every engine of `backends`; on several, the pooled figures, each
    engine's under `per_engine` and the worst engine's errors and fall rate (`worst`)."""
    engines = list(dict.fromkeys(backends))
    per_engine = {name: evaluate_velocity(act, env, robot, name) for name in engines}
    if len(engines) == 1:
        return per_engine[engines[0]]
    pooled = summarize_velocity([e for r in per_engine.values() for e in r["episodes"]])
    worst = {key: max(r[key] for r in per_engine.values())
             for key in ("forward_error_mps", "yaw_error_radps", "fall_rate")}
    return {**pooled, "worst": worst, "per_engine": per_engine}


def velocity_score(result: dict[str, Any]) -> tuple[float, float]:
    """What the velocity recipe's best checkpoint maximises: no falls first (the worst engine's
    fall rate), then the smallest sum of the forward and yaw errors (the worst engine's)."""
    w = result.get("worst", result)
    return (-w["fall_rate"], -(w["forward_error_mps"] + w["yaw_error_radps"]))


def velocity_eval_fields(backends: list[str]) -> list[str]:
    """evals.csv's columns under the velocity recipe (see VELOCITY_EVAL_FIELDS), then on
    several engines each engine's forward error and fall rate."""
    fields = [VELOCITY_EVAL_FIELDS[0]] + [f"{k}{end}" for k in VELOCITY_EVAL_FIELDS[1:] for end in ("", "_lo", "_hi")]
    engines = list(dict.fromkeys(backends))
    if len(engines) > 1:
        fields += [f"{e}_{k}" for e in engines for k in ("forward_error_mps", "fall_rate")]
    return fields


def velocity_eval_row(env_steps: int, result: dict[str, Any], fields: list[str]) -> dict[str, float]:
    """evals.csv's row of a velocity evaluation (see `velocity_eval_fields`)."""
    row = {"env_steps": env_steps, **{k: result[k] for k in fields if k in result}}
    for engine, r in result.get("per_engine", {}).items():
        for key in ("forward_error_mps", "fall_rate"):
            row[f"{engine}_{key}"] = r[key]
    return {k: row[k] for k in fields}


def velocity_eval_summary(result: dict[str, Any]) -> str:
    """One line of a velocity evaluation: each figure with its 95 % interval, the fall rate as
    k/n (on several engines, then each engine's forward error and falls)."""
    e, text = result["estimates"], hyq.stats.text
    line = (f"forward error {text(e['forward_error_mps'], 3)} m/s, yaw error "
            f"{text(e['yaw_error_radps'], 3)} rad/s, standing drift {text(e['standing_drift_m'], 3)} m, "
            f"return {text(e['return'], 2)}, fell {text(e['fell'])} (mean [95 % CI])")
    for engine, r in result.get("per_engine", {}).items():
        line += (f"; {engine}: forward error {text(r['estimates']['forward_error_mps'], 3)} m/s, "
                 f"fell {text(r['estimates']['fell'])}")
    return line


class Evaluation:
    """How a recipe's checkpoints are judged: the evaluation on the recipe's engines, evals.csv's
    columns and rows, the printed line and the score the best checkpoint maximises."""

    def __init__(self, recipe: dict[str, Any]) -> None:
        velocity = recipe.get("evaluation") == "velocity"
        self.kind = "velocity" if velocity else "goal"
        self.evaluate = evaluate_velocity_engines if velocity else evaluate_engines
        self.fields = velocity_eval_fields if velocity else eval_fields
        self.row = velocity_eval_row if velocity else eval_row
        self.summary = velocity_eval_summary if velocity else eval_summary
        self.score = velocity_score if velocity else checkpoint_score


def plot_velocity_evals(evals: list[dict[str, float]], path: Path, title: str) -> None:
    """The velocity recipe's checkpoint evaluations as a 1x3 PNG: the forward and yaw errors,
    the standing drift, and the fall rate, each with its 95 % interval."""
    if not evals:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x = np.array([r["env_steps"] for r in evals]) / 1e6
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    panels = (("forward_error_mps", "m/s", "forward-speed error"), ("yaw_error_radps", "rad/s", "yaw-rate error"),
              ("standing_drift_m", "m", "drift at a zero command"))
    for ax, (key, unit, name) in zip(axes, panels):
        y = np.array([r[key] for r in evals])
        bars = np.abs(np.array([[r[f"{key}_lo"] for r in evals], [r[f"{key}_hi"] for r in evals]]) - y)
        ax.errorbar(x, y, yerr=bars, fmt="o-", label=name)
        ax.set_ylabel(f"{name} ({unit})")
    axes[2].plot(x, [r["fall_rate"] for r in evals], "s", color="C3", label="fall rate (share)")
    for ax in axes:
        ax.set_xlabel("env steps (millions)")
        ax.grid(alpha=0.3)
        ax.legend(loc="best")
    fig.suptitle(f"{title}: deterministic, {EVAL_EPISODES} eval episodes at fixed commands, 95 % CI")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
