"""Train a PPO policy on HyQ-v0 with rsl_rl's OnPolicyRunner (not run in CI: it needs PyTorch).

    target/train-venv/bin/pip install -r examples/requirements-train.txt   # rsl-rl-lib 5.5.1 too
    target/train-venv/bin/python examples/train_rsl_rl.py --recipe walk --out runs/rsl-walk

rsl_rl (the learner of legged_gym, Isaac Lab, Genesis and mjlab) over the Rust vector env
through hyq.rsl_rl.HyQRslRlVecEnv: observations as torch tensors, `time_outs` in the extras so
PPO bootstraps the time limit, the episodes' distance walked, reach, fall and joint-limit rates
in rsl_rl's logger (tensorboard files in OUT). The recipe's environment, robot and engine are
examples/recipes.py's, shared with examples/train_sb3_ppo.py; rsl_rl's settings are TRAIN_CFG
here (rsl_rl's own defaults but where the comment says why). Every part can be changed from the
command line (--robot, --backend, --env, --cfg, --iterations, --seed); --backends
rapier,dart,mujoco trains on several engines at once and evaluates on each, as
train_sb3_ppo.py does. Same seed and
--torch-threads: the same run, bit for bit. It writes into OUT:

    model_<iteration>.pt       rsl_rl's checkpoints (every --checkpoint-every iterations and the
                               last), each with the env steps behind it
    progress.csv, evals.csv,   the learning curve, as train_sb3_ppo.py writes it
    progress.png
    best.pt                    the best evaluated checkpoint (the goal recipes: the worst engine's
                               reach rate, then the return; the velocity recipe: its falls, then
                               its forward and yaw errors at fixed commands)
    evals.png                  the velocity recipe's evaluations (its progress.png has no points)
    eval.json                  the final policy on the 20 evaluation episodes, the best
                               checkpoint's env steps, and the run's timing
    config.json                every setting of the run

Export the policy for the Rust replay and as ONNX with examples/export_policy.py --run OUT.
"""

from __future__ import annotations

import argparse
import copy
import json
import math
import random
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch
from rsl_rl.runners import OnPolicyRunner

import recipes
from hyq.rsl_rl import HyQRslRlVecEnv

#: rsl_rl's configuration (rsl-rl-lib 5.5.1 names): its defaults, but a rollout of 256 steps
#: per env (16 envs here, not thousands on a GPU, so each iteration still sees 4096 steps and
#: the time limit of 1000), a smaller network, and an initial action noise of 0.15 (rsl_rl's
#: 1.0 would swing the joints across their whole offset range; SB3's recipe starts at 0.14
#: for the same reason, docs/training.md).
TRAIN_CFG: dict[str, Any] = {
    "num_steps_per_env": 256,
    "save_interval": 50,
    "obs_groups": {"actor": ["policy"], "critic": ["policy"]},
    "logger": "tensorboard",
    "check_for_nan": True,
    "actor": {
        "class_name": "MLPModel",
        "hidden_dims": [128, 128],
        "activation": "elu",
        "obs_normalization": True,
        "distribution_cfg": {"class_name": "GaussianDistribution", "init_std": 0.15, "std_type": "scalar"},
    },
    "critic": {
        "class_name": "MLPModel",
        "hidden_dims": [128, 128],
        "activation": "elu",
        "obs_normalization": True,
    },
    "algorithm": {
        "class_name": "PPO",
        "num_learning_epochs": 5,
        "num_mini_batches": 4,
        "clip_param": 0.2,
        "gamma": 0.99,
        "lam": 0.95,
        "value_loss_coef": 1.0,
        "entropy_coef": 0.0,
        "learning_rate": 1e-3,
        "max_grad_norm": 1.0,
        "schedule": "adaptive",
        "desired_kl": 0.01,
        "use_clipped_value_loss": True,
    },
}
#: Each recipe's training iterations and checkpoint interval (docs/training.md).
RECIPE_ITERATIONS: dict[str, tuple[int, int]] = {
    "walk": (60, 20),
    "reach": (250, 50),
    "anymal_walk": (80, 20),
    "walk_randomized": (64, 32),
    "walk_rough": (256, 32),
    "velocity": (400, 25),
    "velocity_forward": (400, 50),
}


#: The best evaluated checkpoint's file in OUT (recipes.Evaluation's score: the reach rate, or
#: the velocity recipe's falls and tracking errors).
BEST = "best.pt"


class TimedEnv(HyQRslRlVecEnv):
    """The adapter, adding the time spent in each step to `clock.env_s` and writing the
    training episodes' curve (`progress`)."""

    def __init__(self, clock: recipes.Clock, episodes: recipes.EpisodeLog,
                 progress: recipes.CurveFile, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.clock = clock
        self.episodes = episodes
        self.progress = progress
        self.steps = 0

    def step(self, actions: torch.Tensor):  # noqa: ANN201 - rsl_rl's signature
        start = time.monotonic()
        out = super().step(actions)
        self.clock.env_s += time.monotonic() - start
        self.steps += self.num_envs
        for _, info, ret, length in self.ended:
            self.episodes.add(ret, float(length), info)
        row = self.episodes.row(self.steps, time.monotonic() - self.clock.start)
        if row is not None:
            self.progress.add(row)
        return out


class Runner(OnPolicyRunner):
    """OnPolicyRunner whose checkpoints name the robot and its observation rows (what
    examples/export_policy.py checks a model against) and the env steps behind them (those of
    this run, and of the run a resumed one started from: `steps_before`)."""

    steps_before = 0

    def save(self, path: str, infos: dict | None = None) -> None:
        env = self.env
        super().save(path, {**(infos or {}), "robot": env.cfg["robot"],
                            "observation": env.observation_names,
                            "env_steps": self.steps_before + env.steps})


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True, help="output directory")
    # go1_walk is SB3's recipe only: rsl_rl, tried once, had found no Go1 gait by 307k steps
    # (docs/training.md, "Go1").
    parser.add_argument("--recipe", choices=sorted(RECIPE_ITERATIONS), default="walk",
                        help="the environment, robot and engine (examples/recipes.py; default: walk)")
    parser.add_argument("--robot", help="the robot (default: the recipe's)")
    parser.add_argument("--backend", help="the engine (default: the recipe's)")
    parser.add_argument("--backends", metavar="A,B,...",
                        help="train on several engines at once: the vector env's envs assigned "
                             "round-robin to these engines (e.g. rapier,dart,mujoco; --envs at "
                             "least their number), each checkpoint evaluated on every one of "
                             "them and the best chosen by the worst engine's reach rate")
    parser.add_argument("--iterations", type=int, help="learning iterations (default: the recipe's)")
    parser.add_argument("--envs", type=int, help="parallel envs (default: the recipe's, else 16)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--torch-threads", type=int, default=1,
                        help="PyTorch's CPU threads (default: 1; part of what makes a run repeat)")
    parser.add_argument("--checkpoint-every", type=int,
                        help="iterations between checkpoints and evaluations (default: the recipe's)")
    parser.add_argument("--curve-episodes", type=int, default=32, help="least episodes per curve row")
    parser.add_argument("--env", type=json.loads, default={},
                        help='JSON object of environment keys to change, e.g. \'{"fall_penalty": 0}\'')
    parser.add_argument("--resume", type=Path, metavar="CHECKPOINT",
                        help="start from an rsl_rl checkpoint (model_N.pt: its networks, observation "
                             "normalisers, action noise and optimiser) instead of from scratch, e.g. "
                             "the walk recipe's final one to fine-tune it with randomisation, or on "
                             "rough ground with the height scan added to its rows; --iterations then "
                             "counts the iterations added")
    parser.add_argument("--action-noise", type=float, metavar="STD",
                        help="set the policy's action noise (the Gaussian's standard deviation, every "
                             "action) to STD before training, after --resume: a resumed policy whose "
                             "noise lets training escape states its deterministic mean keeps, e.g. a "
                             "stand at a walking command (docs/velocity.md, ANYmal C)")
    parser.add_argument("--cfg", type=json.loads, default={},
                        help='JSON object merged into rsl_rl\'s configuration, e.g. \'{"algorithm": {"entropy_coef": 0.005}}\'')
    return parser.parse_args()


def evaluate(runner: OnPolicyRunner, run: dict[str, Any], judge: recipes.Evaluation) -> dict[str, Any]:
    """The deterministic policy (the Gaussian's mean) on the evaluation episodes, as the
    recipe's checkpoints are judged (`judge`)."""
    policy = runner.alg.get_policy()
    runner.alg.eval_mode()

    def act(obs: np.ndarray) -> np.ndarray:
        with torch.inference_mode():
            group = {"policy": torch.as_tensor(obs)}
            return policy(group).numpy()

    try:
        return judge.evaluate(act, run["eval_env"], run["robot"], run["backends"])
    finally:
        runner.alg.train_mode()


def resume(runner: Runner, path: Path, names: list[str], per_iteration: int) -> None:
    """Loads checkpoint `path` into `runner`, whose checkpoints then count the env steps behind
    it (`steps_before`). A checkpoint whose observation rows are the first
    rows of this env's (the walk's 39 before the rough recipe's height scan) is widened: the
    added rows get zero weights in the first layers, so the policy starts as the checkpoint's
    exactly, and a normalisation of mean 0 and deviation 1 whose count is one iteration's
    steps, so their statistics are learnt within a few iterations while the others' hold; the
    optimiser starts afresh (its moments have the old shapes)."""
    saved = torch.load(path, map_location="cpu", weights_only=False)
    runner.steps_before = steps_behind(saved, path)
    rows = (saved.get("infos") or {}).get("observation", names)
    if rows == names:
        runner.load(str(path))
        return
    if rows != names[: len(rows)]:
        raise SystemExit(f"error: --resume {path}: its observation rows are neither this env's "
                         f"nor their first {len(rows)}")
    extra = len(names) - len(rows)
    for part in ("actor_state_dict", "critic_state_dict"):
        state = saved[part]
        state["mlp.0.weight"] = torch.cat([state["mlp.0.weight"], torch.zeros(state["mlp.0.weight"].shape[0], extra)], 1)
        for key, fill in (("_mean", 0.0), ("_var", 1.0), ("_std", 1.0)):
            old = state[f"obs_normalizer.{key}"]
            state[f"obs_normalizer.{key}"] = torch.cat([old, torch.full((1, extra), fill)], 1)
        state["obs_normalizer.count"] = torch.tensor(per_iteration, dtype=state["obs_normalizer.count"].dtype)
    runner.alg.load(saved, {"actor": True, "critic": True, "iteration": True}, strict=True)
    runner.current_learning_iteration = saved["iter"]


def set_action_noise(runner: Runner, std: float) -> None:
    """Sets every action's noise deviation of `runner`'s policy to `std` (`--action-noise`)."""
    params = [(name, p) for name, p in runner.alg.actor.named_parameters() if name.endswith("std_param")]
    if len(params) != 1:
        raise SystemExit(f"error: --action-noise: the policy has {len(params)} noise parameters, not one")
    name, param = params[0]
    with torch.no_grad():
        # rsl_rl keeps the deviation itself ("scalar") or its logarithm ("log").
        param.fill_(math.log(std) if name.endswith("log_std_param") else std)


def steps_behind(saved: dict[str, Any], path: Path) -> int:
    """The env steps behind checkpoint `saved` (read from `path`): its own count, else (a
    checkpoint written before checkpoints counted them) its run's whole budget."""
    steps = (saved.get("infos") or {}).get("env_steps")
    if steps is None and (path.parent / "config.json").is_file():
        steps = json.loads((path.parent / "config.json").read_text())["steps"]
    return int(steps or 0)


def main() -> None:
    args = parse_args()
    recipe = recipes.RECIPES[args.recipe]
    iterations, every = RECIPE_ITERATIONS[args.recipe]
    args.envs = recipes.envs_of(args.envs, recipe)
    iterations = args.iterations or iterations
    every = args.checkpoint_every or every
    env_keys = recipes.merge(recipe["env"], args.env)
    run = {
        "recipe": args.recipe,
        "robot": args.robot or recipe["robot"],
        "backends": recipes.engines_of(args.backend, args.backends, recipe["backend"]),
        "env": env_keys,
        "eval_env": recipes.merge(env_keys, recipe.get("eval_env", {})),
    }
    # The engines' names joined, for titles and config.json ("mujoco"; "rapier,dart,mujoco").
    run["backend"] = ",".join(run["backends"])
    recipes.check_action_noise(args.action_noise)
    if args.resume and not args.resume.is_file():
        # Before OUT is made, so a mistyped checkpoint leaves nothing behind.
        raise SystemExit(f"error: --resume {args.resume}: no such checkpoint file")
    cfg = copy.deepcopy(TRAIN_CFG)
    for key, value in args.cfg.items():
        cfg[key] = {**cfg[key], **value} if isinstance(value, dict) and isinstance(cfg.get(key), dict) else value
    cfg["save_interval"] = every
    args.out.mkdir(parents=True, exist_ok=True)
    config = {
        **run, "trainer": "rsl_rl", "rsl_rl": cfg, "iterations": iterations, "envs": args.envs,
        "steps": iterations * cfg["num_steps_per_env"] * args.envs, "seed": args.seed,
        "torch_threads": args.torch_threads, "commit": recipes.git_commit(),
        "resume": str(args.resume) if args.resume else None,
        "command": recipes.command_with_prior(sys.argv, args.resume),
    }
    recipes.write_json(args.out / "config.json", config)

    torch.set_num_threads(args.torch_threads)
    torch.manual_seed(args.seed)
    np.random.seed(args.seed)
    random.seed(args.seed)
    clock = recipes.Clock()
    episodes = recipes.EpisodeLog(args.curve_episodes)
    progress = recipes.CurveFile(args.out / "progress.csv", recipes.PROGRESS_FIELDS)
    env = TimedEnv(clock, episodes, progress, num_envs=args.envs, seed=args.seed, robot=run["robot"],
                   backend=run["backends"], **run["env"])
    runner = Runner(env, copy.deepcopy(cfg), log_dir=str(args.out), device="cpu")
    per_iteration = cfg["num_steps_per_env"] * args.envs
    if args.resume:
        resume(runner, args.resume, env.observation_names, per_iteration)
    if args.action_noise is not None:
        set_action_noise(runner, args.action_noise)
    judge = recipes.Evaluation(recipe)
    evals = recipes.CurveFile(args.out / "evals.csv", judge.fields(run["backends"]))
    title = (f"PPO (rsl_rl) on {run['robot']}, {run['backend']}: "
             f"examples/train_rsl_rl.py --recipe {args.recipe}")
    done = 0
    best: tuple[tuple[float, float], int] | None = None
    while done < iterations:
        # learn() in chunks of `every` iterations, with an evaluation after each.
        chunk = min(every, iterations - done)
        runner.learn(num_learning_iterations=chunk)
        done += chunk
        steps = done * per_iteration
        start = time.monotonic()
        result = evaluate(runner, run, judge)
        clock.eval_s += time.monotonic() - start
        evals.add(judge.row(steps, result, evals.fields))
        print(f"[{steps} env steps] deterministic eval: {judge.summary(result)}", flush=True)
        if best is None or judge.score(result) > best[0]:
            # The checkpoint as evaluated (a later chunk's first save can reuse its model_N.pt).
            best = (judge.score(result), runner.steps_before + steps)
            runner.save(str(args.out / BEST))
        if judge.kind == "velocity":
            recipes.plot_curve(progress.rows, [], args.out / "progress.png", title)
            recipes.plot_velocity_evals(evals.rows, args.out / "evals.png", title)
        else:
            recipes.plot_curve(progress.rows, evals.rows, args.out / "progress.png", title)
    timing = clock.summary(done * per_iteration)
    progress.close()
    evals.close()
    env.close()
    result["timing"] = timing
    if best is not None:
        # Chosen on the evaluation seeds (recipes.EVAL_SEED), not the seeds figures are
        # reported on; export it with export_policy.py --run OUT --model OUT/best.pt.
        result["best_checkpoint"] = BEST
        result["best_checkpoint_env_steps"] = best[1]
    recipes.write_json(args.out / "eval.json", result)
    print(recipes.timing_line(timing))
    per = " per engine" if len(set(run["backends"])) > 1 else ""
    print(f"eval over {recipes.EVAL_EPISODES} episodes{per}: {judge.summary(result)}")


if __name__ == "__main__":
    main()
