"""Train a PPO policy on HyQ-v0 with Stable-Baselines3 (not run in CI: it needs PyTorch).

    python3 -m venv target/train-venv
    target/train-venv/bin/pip install -r examples/requirements-train.txt   # PyTorch: 5.4 GB
    cargo xtask setup mujoco
    (cd crates/hyq-py && VIRTUAL_ENV=$PWD/../../target/train-venv \\
        ../../target/train-venv/bin/maturin develop --release --features mujoco)
    target/train-venv/bin/python examples/train_sb3_ppo.py --recipe walk --out runs/walk
    target/train-venv/bin/python examples/train_sb3_ppo.py --recipe reach --out runs/reach

A recipe (examples/recipes.py; docs/training.md says why each setting is there) is the
environment, the robot and the engine; its PPO settings and budget are RECIPE_PPO, RECIPE_NET
and RECIPE_STEPS here. Every part can be changed from the command line (--robot, --backend,
--env, --ppo, --net, --steps, --seed), so the same script trains on other robots, engines and
environment settings; --backends rapier,dart,mujoco trains on several engines at once (the
envs assigned round-robin to them), evaluates every checkpoint on each and keeps the one whose
worst engine reaches most often (eval.json and evals.csv then hold each engine's figures);
--eps-curriculum START:END:STEPS[:STAGES] trains with a reach cube shrinking in stages (eval.json
then lists each change) while the checkpoints are judged on the environment's own cube;
--resume CHECKPOINT continues a run's model with its observation and reward statistics (a
second stage with other environment keys or PPO settings). N envs stepped in Rust (hyq.sb3.HyQVecEnv, same-step resets with SB3's
terminal_observation and TimeLimit.truncated, so PPO bootstraps timeouts), VecNormalize on
observations and rewards, a fixed budget of env steps. Same seed and --torch-threads: the same
run, bit for bit. It writes into OUT:

    progress.csv, progress.png   the learning curve: mean return, distance walked toward the
                                 goal (K - D^T), fall, joint-limit and reach rates, episode
                                 length, over env steps (each row: the episodes that ended since
                                 the previous row, at least --curve-episodes of them)
    evals.csv                    the deterministic policy on 20 seeded episodes at each checkpoint
    checkpoints/                 model_<steps>.zip and vecnormalize_<steps>.pkl
    model.zip, vecnormalize.pkl  the final agent
    eval.json                    the final agent on 20 seeded episodes with reset noise, and the
                                 run's timing: wall time, the part spent stepping the envs, the
                                 load average at the start and the end
    config.json                  every setting of the run

Export the result for the Rust replay (`hyq run --policy mlp:FILE`) and as ONNX with
examples/export_policy.py.
"""

from __future__ import annotations

import argparse
import json
import math
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

import recipes
from hyq.sb3 import HyQVecEnv

#: PPO's settings (Stable-Baselines3 names): SB3's defaults but for the rollout (256 steps per
#: env), the batch (1024) and the epochs (5), to update often on 2 cores.
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
RECIPE_NET: dict[str, Any] = {"pi": [128, 128], "vf": [128, 128], "log_std_init": -2.0, "activation": "tanh"}
#: Each recipe's budget of env steps and checkpoint interval (docs/training.md).
RECIPE_STEPS: dict[str, tuple[int, int]] = {
    "walk": (200_000, 100_000),
    "reach": (600_000, 100_000),
    "anymal_walk": (200_000, 100_000),
    "go1_walk": (600_000, 100_000),
    "walk_randomized": (400_000, 100_000),
    # Not yet run with SB3: the committed rough-ground policy is rsl_rl's fine-tuning of the
    # walker (docs/terrain.md), which SB3's recipe cannot start from (its observation is wider).
    "walk_rough": (1_000_000, 100_000),
}
#: Each recipe's changes to RECIPE_PPO. The reach: a learning rate falling linearly to 0 over the
#: budget ("lr_schedule"), since at a constant 3e-4 the deterministic policy reached the goal in
#: 7 of 20 episodes at 400k steps and then lost it again (2 to 4 of 20 at 600k to 1M steps, with
#: episodes walking backwards; docs/training.md).
#: Go1: a learning rate of 1e-3 falling linearly (at 3e-4 no gait was found in 600k steps), and
#: an update's epochs stopped once its KL divergence passes 0.02 (without it the run that found a
#: 2.4 m walker at 400k steps unlearnt it by 600k).
RECIPE_PPO_CHANGES: dict[str, dict[str, Any]] = {
    "reach": {"lr_schedule": "linear"},
    "go1_walk": {"learning_rate": 1e-3, "lr_schedule": "linear", "target_kl": 0.02},
}
#: Each recipe's changes to RECIPE_NET. Go1: an initial action noise of σ 0.37 (log_std -1): at
#: 0.14 its servos, against their Coulomb friction, moved too little for any gait to be found.
RECIPE_NET_CHANGES: dict[str, dict[str, Any]] = {
    "go1_walk": {"log_std_init": -1.0},
}
ACTIVATIONS = {"tanh": torch.nn.Tanh, "relu": torch.nn.ReLU, "elu": torch.nn.ELU}


class TimedVecEnv(HyQVecEnv):
    """HyQVecEnv that adds the time spent in each step to `clock.env_s`."""

    def __init__(self, clock: recipes.Clock, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.clock = clock

    def step_wait(self):  # noqa: ANN201 - SB3's signature
        start = time.monotonic()
        out = super().step_wait()
        self.clock.env_s += time.monotonic() - start
        return out


class Curve(BaseCallback):
    """Writes the learning curve from the final info of every training episode, and every
    `every` env steps saves a checkpoint and evaluates the deterministic policy (a row of
    evals.csv). Training episodes run the stochastic policy, whose action noise alone can
    shuffle the robot forward; the deterministic one is what gets exported, so the curve shows
    both."""

    def __init__(self, out: Path, min_episodes: int, every: int, run: dict[str, Any],
                 clock: recipes.Clock, eval_mode: str = "checkpoints",
                 stop_at: int | None = None) -> None:
        super().__init__()
        #: What is evaluated (--eval): "checkpoints" (each, and the final model), "final", "none".
        self.eval_mode = eval_mode
        #: Training stops at the first step at or past this many env steps (--stop-at).
        self.stop_at = stop_at
        self.clock = clock
        self.out = out
        self.episodes = recipes.EpisodeLog(min_episodes)
        self.progress = recipes.CurveFile(out / "progress.csv", recipes.PROGRESS_FIELDS)
        self.evals = recipes.CurveFile(out / "evals.csv", recipes.eval_fields(run["backends"]))
        self.every = every
        self.next = every
        self.run = run
        self.start = time.monotonic()
        #: ((reach rate, mean return), env steps) of the best evaluated checkpoint.
        self.best: tuple[tuple[float, float], int] | None = None
        (out / "checkpoints").mkdir(parents=True, exist_ok=True)

    def _on_step(self) -> bool:
        for done, info in zip(self.locals["dones"], self.locals["infos"]):
            if done:
                self.episodes.add(float(info["episode"]["r"]), float(info["episode"]["l"]), info)
        if self.num_timesteps >= self.next:
            self.next += self.every
            self.checkpoint()
        # False ends model.learn at once, before the rollout's update: the model then is the
        # one a checkpoint written at this step holds.
        return self.stop_at is None or self.num_timesteps < self.stop_at

    def checkpoint(self) -> None:
        norm = self.model.get_vec_normalize_env()
        self.model.save(self.out / "checkpoints" / f"model_{self.num_timesteps}.zip")
        norm.save(str(self.out / "checkpoints" / f"vecnormalize_{self.num_timesteps}.pkl"))
        if self.eval_mode != "checkpoints":
            print(f"[{self.num_timesteps} env steps] checkpoint written, not evaluated "
                  f"(--eval {self.eval_mode})", flush=True)
            return
        start = time.monotonic()
        result = evaluate(self.model, norm, self.run)
        self.clock.eval_s += time.monotonic() - start
        self.evals.add(recipes.eval_row(self.num_timesteps, result, self.evals.fields))
        score = recipes.checkpoint_score(result)
        if self.best is None or score > self.best[0]:
            self.best = (score, self.num_timesteps)
        print(f"[{self.num_timesteps} env steps] deterministic eval: {recipes.eval_summary(result)}", flush=True)
        self.plot()

    def _on_rollout_end(self) -> None:
        row = self.episodes.row(self.num_timesteps, time.monotonic() - self.start)
        if row is not None:
            self.progress.add(row)
            self.logger.record("hyq/distance_m", row["mean_distance_m"])
            self.logger.record("hyq/reach_rate", row["reach_rate"])

    def plot(self) -> None:
        title = (f"PPO (Stable-Baselines3) on {self.run['robot']}, {self.run['backend']}: "
                 f"examples/train_sb3_ppo.py --recipe {self.run['recipe']}")
        recipes.plot_curve(self.progress.rows, self.evals.rows, self.out / "progress.png", title)

    def _on_training_end(self) -> None:
        self.progress.close()
        self.evals.close()
        self.plot()


class EpsCurriculum(BaseCallback):
    """`--eps-curriculum`: at the end of the first rollout of each new stage
    (recipes.curriculum_stage), replaces the training envs by envs whose reach cube is the
    stage's side. The envs' configuration is fixed when they are built (a reach cube that
    changed under a running episode would change its rules), so the stage's envs are new ones,
    seeded `seed + 100000·stage + i`, and the episodes running at the change end there
    unrecorded: PPO has already bootstrapped the rollout's last values, as for a time limit.
    The checkpoints are judged on the recipe's cube all along (run["eval_env"])."""

    def __init__(self, curriculum: dict[str, Any], make_env: Any, seed: int) -> None:
        super().__init__()
        self.curriculum = curriculum
        self.make_env = make_env
        self.seed = seed
        self.stage = 0
        #: (env steps, cube side) at each change, the first at 0.
        self.changes: list[tuple[int, float]] = [(0, recipes.curriculum_stage(curriculum, 0)[1])]

    def _on_step(self) -> bool:
        return True

    def _on_rollout_end(self) -> None:
        stage, side = recipes.curriculum_stage(self.curriculum, self.num_timesteps)
        if stage == self.stage:
            return
        self.stage = stage
        norm = self.model.get_vec_normalize_env()
        monitor = norm.venv
        monitor.venv.close()
        monitor.venv = self.make_env(side, self.seed + 100_000 * stage)
        self.model._last_obs = norm.reset()
        self.model._last_episode_starts = np.ones(norm.num_envs, dtype=bool)
        self.changes.append((self.num_timesteps, side))
        print(f"[{self.num_timesteps} env steps] reach cube in training: {side:g} m", flush=True)


def evaluate(model: PPO, obs_norm: VecNormalize, run: dict[str, Any]) -> dict[str, Any]:
    """The deterministic policy on the evaluation episodes (recipes.evaluate)."""

    def act(obs: np.ndarray) -> np.ndarray:
        action, _ = model.predict(obs_norm.normalize_obs(obs), deterministic=True)
        return action

    return recipes.evaluate_engines(act, run["eval_env"], run["robot"], run["backends"])


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True, help="output directory")
    # The velocity recipes are rsl_rl's (examples/train_rsl_rl.py): SB3 has no budget for them.
    parser.add_argument("--recipe", choices=sorted(RECIPE_STEPS), default="walk",
                        help="the environment, robot and engine (examples/recipes.py; default: walk)")
    parser.add_argument("--robot", help="the robot (default: the recipe's)")
    parser.add_argument("--backend", help="the engine (default: the recipe's)")
    parser.add_argument("--backends", metavar="A,B,...",
                        help="train on several engines at once: the vector env's envs assigned "
                             "round-robin to these engines (e.g. rapier,dart,mujoco; --envs at "
                             "least their number), each checkpoint evaluated on every one of "
                             "them and the best chosen by the worst engine's reach rate")
    parser.add_argument("--steps", type=int, help="total env steps (default: the recipe's)")
    parser.add_argument("--envs", type=int, help="parallel envs (default: the recipe's, else 16)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--torch-threads", type=int, default=1,
                        help="PyTorch's CPU threads (default: 1; part of what makes a run repeat)")
    parser.add_argument("--checkpoint-every", type=int,
                        help="env steps between checkpoints and evaluations (default: the recipe's)")
    parser.add_argument("--curve-episodes", type=int, default=32, help="least episodes per curve row")
    parser.add_argument("--eps-curriculum", metavar="START:END:STEPS[:STAGES]",
                        help="train with a reach cube (accepted_error) shrinking from START to "
                             "END m in STAGES stages (default 5), the last from STEPS env steps "
                             "on; the checkpoints are judged on the environment's own cube "
                             "(default: off, the cube fixed)")
    parser.add_argument("--resume", type=Path, metavar="MODEL",
                        help="start from a saved model (RUN/model.zip or RUN/checkpoints/model_N.zip) "
                             "and the VecNormalize statistics saved with it, instead of from scratch; "
                             "--ppo's settings and the learning rate's schedule apply from its first "
                             "step, --steps counts the steps added (--net is refused: the networks "
                             "are the model's)")
    parser.add_argument("--action-noise", type=float, metavar="STD",
                        help="set the policy's action noise (the Gaussian's standard deviation, every "
                             "action) to STD before training, after --resume: e.g. lower, so that "
                             "training meets the states the deterministic policy it will be judged as "
                             "falls from (docs/training.md, the reach on three engines)")
    parser.add_argument("--stop-at", type=int, metavar="N",
                        help="stop at the first step at or past N env steps and save the model there "
                             "(model.zip: the model a checkpoint written at that step holds); the "
                             "learning rate's schedule stays that of --steps")
    parser.add_argument("--eval", choices=("checkpoints", "final", "none"), default="checkpoints",
                        help="what the deterministic policy is evaluated on: every checkpoint and the "
                             "final model (the default), the final model alone, or nothing (for the "
                             "stages of a staged recipe whose stopping points are fixed; evaluations "
                             "are about 45 %% of a reach stage's time)")
    parser.add_argument("--env", type=json.loads, default={},
                        help='JSON object of environment keys to change, e.g. \'{"fall_penalty": 0}\'')
    parser.add_argument("--ppo", type=json.loads, default={}, help="JSON object of PPO settings to change")
    parser.add_argument("--net", type=json.loads, default={},
                        help='JSON object of network settings to change: pi, vf, log_std_init, activation')
    return parser.parse_args()


def statistics_of(model: Path) -> Path:
    """The VecNormalize statistics saved with `model`: checkpoints/vecnormalize_N.pkl beside a
    checkpoint, RUN/vecnormalize.pkl beside a run's final model."""
    if model.stem.startswith("model_"):
        return model.with_name(f"vecnormalize_{model.stem[len('model_'):]}.pkl")
    return model.with_name("vecnormalize.pkl")


def main() -> None:
    args = parse_args()
    recipe = recipes.RECIPES[args.recipe]
    steps, every = RECIPE_STEPS[args.recipe]
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
    ppo_kwargs = {**RECIPE_PPO, **RECIPE_PPO_CHANGES.get(args.recipe, {}), **args.ppo}
    net = {**RECIPE_NET, **RECIPE_NET_CHANGES.get(args.recipe, {}), **args.net}
    args.envs = recipes.envs_of(args.envs, recipe)
    if net["activation"] not in ACTIVATIONS:
        raise SystemExit(f"error: --net activation {net['activation']!r}: expected one of {sorted(ACTIVATIONS)}")
    curriculum = None if args.eps_curriculum is None else recipes.eps_curriculum(args.eps_curriculum)
    recipes.check_action_noise(args.action_noise)
    budget = args.steps or steps
    if args.stop_at is not None and not 0 < args.stop_at <= budget:
        raise SystemExit(f"error: --stop-at {args.stop_at}: expected 1 to the run's {budget} env steps")
    if args.resume is not None:
        # Before OUT is made, so a mistyped model leaves nothing behind.
        for path in (args.resume, statistics_of(args.resume)):
            if not path.is_file():
                raise SystemExit(f"error: --resume {args.resume}: no such file {path}")
        if args.net:
            raise SystemExit(f"error: --net {', '.join(sorted(args.net))}: a resumed model keeps its "
                             "networks (--action-noise sets its noise)")
    args.out.mkdir(parents=True, exist_ok=True)
    config = {
        **run, "trainer": "sb3", "ppo": ppo_kwargs, "net": net, "steps": budget,
        **({} if args.stop_at is None else {"stop_at": args.stop_at}),
        "envs": args.envs, "seed": args.seed, "torch_threads": args.torch_threads,
        **({} if curriculum is None else {"eps_curriculum": curriculum}),
        "commit": recipes.git_commit(),
        "command": recipes.command_with_prior(sys.argv, args.resume),
        "resume": None if args.resume is None else str(args.resume),
    }
    recipes.write_json(args.out / "config.json", config)

    # A fixed thread count keeps torch's CPU arithmetic the same from run to run; one thread
    # leaves the other core to the envs' rayon threads.
    torch.set_num_threads(args.torch_threads)
    set_random_seed(args.seed)
    clock = recipes.Clock()

    def make_env(env_keys: dict[str, Any], seed: int) -> TimedVecEnv:
        return TimedVecEnv(clock, num_envs=args.envs, seed=seed, robot=run["robot"],
                           backend=run["backends"], **env_keys)

    callbacks: list[BaseCallback] = []
    if curriculum is None:
        venv = make_env(run["env"], args.seed)
    else:
        def make_stage_env(side: float, seed: int) -> TimedVecEnv:
            return make_env({**run["env"], "accepted_error": side}, seed)

        callbacks.append(EpsCurriculum(curriculum, make_stage_env, args.seed))
        venv = make_stage_env(callbacks[0].changes[0][1], args.seed)
    if args.resume is None:
        venv = VecNormalize(VecMonitor(venv), norm_obs=True, norm_reward=True, clip_obs=10.0,
                            gamma=ppo_kwargs["gamma"])
    else:
        # The statistics go on learning, as they did in the run resumed.
        venv = VecNormalize.load(str(statistics_of(args.resume)), VecMonitor(venv))
        venv.training, venv.norm_reward, venv.gamma = True, True, ppo_kwargs["gamma"]
    # Saved with the statistics, so an export can tell them from another robot's.
    venv.hyq_robot = run["robot"]
    sb3_kwargs = {k: v for k, v in ppo_kwargs.items() if k != "lr_schedule"}
    schedule = ppo_kwargs.get("lr_schedule", "constant")
    if schedule == "linear":
        # SB3 calls it with the fraction of the budget still to go (1 at the start, 0 at the end).
        start_lr = sb3_kwargs["learning_rate"]
        sb3_kwargs["learning_rate"] = lambda remaining: start_lr * remaining
    elif schedule != "constant":
        raise SystemExit(f"error: --ppo lr_schedule {schedule!r}: expected constant or linear")
    if args.resume is None:
        model = PPO(
            "MlpPolicy",
            venv,
            policy_kwargs={
                "net_arch": {"pi": net["pi"], "vf": net["vf"]},
                "activation_fn": ACTIVATIONS[net["activation"]],
                "log_std_init": net["log_std_init"],
            },
            seed=args.seed,
            device="cpu",
            verbose=0,
            **sb3_kwargs,
        )
    else:
        # The saved networks, with this run's PPO settings and schedule.
        model = PPO.load(args.resume, env=venv, device="cpu", custom_objects=sb3_kwargs)
        model.set_random_seed(args.seed)
    if args.action_noise is not None:
        with torch.no_grad():
            model.policy.log_std.fill_(math.log(args.action_noise))
    curve = Curve(args.out, args.curve_episodes, args.checkpoint_every or every, run, clock,
                  args.eval, args.stop_at)
    model.learn(total_timesteps=config["steps"], callback=CallbackList([curve, *callbacks]),
                progress_bar=True)
    timing = clock.summary(model.num_timesteps)
    model.save(args.out / "model.zip")
    venv.save(str(args.out / "vecnormalize.pkl"))
    venv.close()

    # --eval none: the run's timing alone (a stage whose model the next one resumes).
    result = {} if args.eval == "none" else evaluate(model, venv, run)
    result["timing"] = timing
    if curve.best is not None:
        # The checkpoint that reached the goal most often (then: the highest mean return) on the
        # evaluation episodes; export it with --checkpoint best.
        result["best_checkpoint_env_steps"] = curve.best[1]
    if callbacks:
        # Each change of the training envs' reach cube: [env steps, side in m].
        result["eps_curriculum_changes"] = [list(c) for c in callbacks[0].changes]
    recipes.write_json(args.out / "eval.json", result)
    print(recipes.timing_line(timing))
    if args.eval != "none":
        per = " per engine" if len(set(run["backends"])) > 1 else ""
        print(f"eval over {recipes.EVAL_EPISODES} episodes{per}: {recipes.eval_summary(result)}")


if __name__ == "__main__":
    main()
