"""Invariant: the training scripts' evaluations (examples/recipes.py's ``evaluate``, which both
examples/train_sb3_ppo.py and examples/train_rsl_rl.py call) give each mean with its 95 %
bootstrap interval and each rate with its Wilson interval, computed by hyq.stats (the Rust
hyq-stats), printed and recorded in evals.csv; a repeated evaluation records the same."""

import numpy as np

import hyq.stats


def test_an_evaluation_gives_every_figure_with_its_interval(recipes):
    r = recipes
    # Reset noise makes the short episodes differ; a zero action stands the robot still.
    env = {"env_config": {"task.max_time_steps": 40, "reset.joint_noise_rad": 0.05}}
    act = lambda obs: np.zeros((obs.shape[0], 12), dtype=np.float32)  # noqa: E731
    result = r.evaluate(act, env, "hyq", "rapier")
    e = result["estimates"]
    returns = [x["return"] for x in result["episodes"]]
    assert e["return"] == hyq.stats.mean_ci(returns, seed=r.EVAL_SEED)
    lo, hi = e["distance_m"]["ci95"]
    assert lo < e["distance_m"]["mean"] < hi, e["distance_m"]
    for key in ("fell", "joint_limit", "reached"):
        k = sum(key in x["reasons"] for x in result["episodes"])
        assert e[key] == hyq.stats.wilson(k, r.EVAL_EPISODES), key
    # evals.csv's columns, each interval end beside its mean.
    for column in r.EVAL_FIELDS[1:]:
        assert isinstance(result[column], float), column
    assert result["mean_return_lo"] <= result["mean_return"] <= result["mean_return_hi"]
    assert result["reach_rate_hi"] == e["reached"]["ci95"][1]
    line = r.eval_summary(result)
    assert hyq.stats.text(e["distance_m"], 2) in line and "0/20 [0 %, 16 %]" in line, line
    again = r.evaluate(act, env, "hyq", "rapier")
    assert again["estimates"] == e
