"""Invariant: the velocity recipe's checkpoint evaluation (examples/recipes.py's
``evaluate_velocity``) runs the policy at each fixed command of ``VELOCITY_EVAL_COMMANDS`` on its
own seeds and gives the forward-speed error, the yaw-rate error, the drift at a zero command and
the return as means with their 95 % bootstrap intervals and the fall rate with its Wilson
interval, all from hyq.stats; a known answer: the standing policy (zero offsets) stands, so its
errors are the commands it ignores and it does not drift; a repeated evaluation gives the same."""

import numpy as np

import hyq.stats


def test_the_standing_policy_misses_each_command_by_the_command_and_stands_still(recipes):
    r = recipes
    env = r.merge(r.RECIPES["velocity"]["env"], {"task": {"kind": "velocity", "max_time_steps": 40}})
    stand = lambda obs: np.zeros((obs.shape[0], 12), dtype=np.float32)  # noqa: E731
    result = r.evaluate_velocity(stand, env, "hyq", "rapier")
    done = result["episodes"]
    assert len(done) == r.EVAL_EPISODES
    assert sorted({tuple(e["command"]) for e in done}) == sorted(r.VELOCITY_EVAL_COMMANDS)
    e = result["estimates"]
    forward = [x["forward_error_mps"] for x in done if x["command"][1] == 0.0]
    assert e["forward_error_mps"] == hyq.stats.mean_ci(forward, seed=r.EVAL_SEED)
    # Commanded 0, 0.3 and 0.6 m/s and standing: the error is about the mean command, 0.3 m/s.
    assert abs(e["forward_error_mps"]["mean"] - 0.3) < 0.02, e["forward_error_mps"]
    assert abs(e["yaw_error_radps"]["mean"] - 0.5) < 0.02, e["yaw_error_radps"]
    assert 0.0 <= e["standing_drift_m"]["mean"] < 0.02, e["standing_drift_m"]
    assert e["fell"] == hyq.stats.wilson(0, r.EVAL_EPISODES)
    for key in ("mean_return", "forward_error_mps", "yaw_error_radps", "standing_drift_m", "fall_rate"):
        assert result[f"{key}_lo"] <= result[key] <= result[f"{key}_hi"], key
    line = r.velocity_eval_summary(result)
    assert hyq.stats.text(e["forward_error_mps"], 3) in line and "0/20 [0 %, 16 %]" in line, line
    # The checkpoint score prefers no falls, then smaller errors.
    better = dict(result, forward_error_mps=0.1)
    assert r.velocity_score(better) > r.velocity_score(result)
    assert r.velocity_score(dict(better, fall_rate=0.05)) < r.velocity_score(result)
    again = r.evaluate_velocity(stand, env, "hyq", "rapier")
    assert again["estimates"] == e


def test_the_velocity_recipe_trains_the_velocity_task_and_its_evaluation_fixes_the_command(recipes):
    r = recipes
    recipe = r.RECIPES["velocity"]
    assert recipe["env"]["task"]["kind"] == "velocity" and recipe["evaluation"] == "velocity"
    fixed = r.fixed_command(recipe["env"], 0.6, -0.5)
    assert fixed["command"]["lin_vel_x"] == [0.6, 0.6] and fixed["command"]["ang_vel_yaw"] == [-0.5, -0.5]
    assert fixed["command"]["standing_probability"] == 0.0
    # The recipe's other command keys stay.
    assert fixed["command"]["resampling_time_s"] == recipe["env"]["command"]["resampling_time_s"]
    assert r.Evaluation(recipe).kind == "velocity" and r.Evaluation(r.RECIPES["walk"]).kind == "goal"


def test_the_evaluation_finds_the_trunk_of_another_robot(recipes):
    # ANYmal C's trunk link is "base": its position rows are base_position_x/y, which the drift
    # measurement found by HyQ's names only (a ValueError before).
    r = recipes
    env = r.merge(r.RECIPES["velocity_forward"]["env"], {"task": {"kind": "velocity", "max_time_steps": 40}})
    stand = lambda obs: np.zeros((obs.shape[0], 12), dtype=np.float32)  # noqa: E731
    result = r.evaluate_velocity(stand, env, "anymal_c", "rapier")
    assert 0.0 <= result["estimates"]["standing_drift_m"]["mean"] < 0.02, result["estimates"]
    assert abs(result["estimates"]["forward_error_mps"]["mean"] - 0.3) < 0.02


def test_the_forward_recipe_is_the_velocity_recipe_with_forward_commands_and_its_costs(recipes):
    r = recipes
    base, forward = r.RECIPES["velocity"]["env"], r.RECIPES["velocity_forward"]["env"]
    assert forward["command"]["lin_vel_x"] == [0.3, 0.6] and forward["command"]["standing_probability"] == 0.0
    assert forward["command"]["lin_vel_y"] == [0.0, 0.0] and forward["command"]["ang_vel_yaw"] == [0.0, 0.0]
    assert forward["velocity"] == {**base["velocity"], "tracking_sigma": 0.1, "torques_abs": -2e-5,
                                   "action_rate": -0.5}
    assert {k: v for k, v in forward.items() if k not in ("command", "velocity")} == \
        {k: v for k, v in base.items() if k not in ("command", "velocity")}
    assert r.RECIPES["velocity_forward"]["evaluation"] == "velocity"
