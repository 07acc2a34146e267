"""The rsl_rl adapter gives rsl_rl exactly what the Rust vector env gives, as torch tensors: the
same observations, rewards and dones for the same seeds and actions over a few hundred steps
across resets; `time_outs` marks exactly the truncated episodes, and rsl_rl's PPO bootstraps
them; the episodes' facts reach the logger; episode lengths are the core's."""

from __future__ import annotations

import numpy as np
import pytest
import torch
from gymnasium.vector import AutoresetMode
from rsl_rl.env import VecEnv
from rsl_rl.runners import OnPolicyRunner

from hyq.rsl_rl import HyQRslRlVecEnv
from hyq.vector import HyQVectorEnv

CONFIG = {"max_time_steps": 60, "action": {"mode": "offset"}, "fall_penalty": 5.0}
N = 6


def actions(steps: int) -> np.ndarray:
    rng = np.random.default_rng(11)
    return rng.uniform(-1.2, 1.2, size=(steps, N, 12)).astype(np.float32)


def test_it_is_an_rsl_rl_vec_env_with_torch_observations() -> None:
    env = HyQRslRlVecEnv(num_envs=N, seed=4, **CONFIG)
    assert isinstance(env, VecEnv)
    assert (env.num_envs, env.num_actions, env.max_episode_length) == (N, 12, 60)
    obs = env.get_observations()
    assert obs["policy"].dtype == torch.float32 and tuple(obs["policy"].shape) == (N, 39)
    reference = HyQVectorEnv(num_envs=N, autoreset_mode=AutoresetMode.SAME_STEP, **CONFIG)
    np.testing.assert_array_equal(obs["policy"].numpy(), reference.reset(seed=4)[0])


def test_three_hundred_steps_match_the_vector_env_and_time_outs_are_the_truncations() -> None:
    env = HyQRslRlVecEnv(num_envs=N, seed=4, **CONFIG)
    reference = HyQVectorEnv(num_envs=N, autoreset_mode=AutoresetMode.SAME_STEP, **CONFIG)
    reference.reset(seed=4)
    timeouts = terminations = logged = 0
    for a in actions(300):
        obs, rew, dones, extras = env.step(torch.as_tensor(a))
        r_obs, r_rew, r_term, r_trunc, _ = reference.step(a)
        np.testing.assert_array_equal(obs["policy"].numpy(), r_obs)
        np.testing.assert_array_equal(rew.numpy(), r_rew.astype(np.float32))
        np.testing.assert_array_equal(dones.numpy(), (r_term | r_trunc).astype(np.int64))
        np.testing.assert_array_equal(extras["time_outs"].numpy(), r_trunc & ~r_term)
        timeouts += int(r_trunc.sum())
        terminations += int(r_term.sum())
        ended = np.flatnonzero(r_term | r_trunc)
        if ended.size:
            logged += 1
            log = extras["log"]
            assert len(log["hyq/reach_rate"]) == ended.size
            for k, i in enumerate(ended):
                info = reference.final_info(int(i))
                assert log["hyq/fall_rate"][k].item() == float(info["fell"])
                assert log["hyq/episode_length"][k].item() == float(info["t"])
        else:
            assert "log" not in extras
        np.testing.assert_array_equal(
            env.episode_length_buf.numpy(),
            [0 if d else reference.env_info(i)["t"] for i, d in enumerate(r_term | r_trunc)],
        )
    # Both kinds of end happened, so both were compared.
    assert timeouts > 0 and terminations > 0 and logged > 0


def test_episode_lengths_cannot_be_set() -> None:
    env = HyQRslRlVecEnv(num_envs=2, **CONFIG)
    with pytest.raises(ValueError, match="episode_length_buf"):
        env.episode_length_buf = torch.zeros(2, dtype=torch.long)


def tiny_cfg() -> dict:
    return {
        "num_steps_per_env": 70, "save_interval": 10, "logger": "tensorboard",
        "obs_groups": {"actor": ["policy"], "critic": ["policy"]},
        "actor": {"class_name": "MLPModel", "hidden_dims": [16], "activation": "elu",
                  "obs_normalization": True,
                  "distribution_cfg": {"class_name": "GaussianDistribution", "init_std": 0.3}},
        "critic": {"class_name": "MLPModel", "hidden_dims": [16], "activation": "elu"},
        "algorithm": {"class_name": "PPO", "num_learning_epochs": 1, "num_mini_batches": 2},
    }


def test_ppo_bootstraps_exactly_the_timed_out_envs() -> None:
    torch.manual_seed(0)
    env = HyQRslRlVecEnv(num_envs=N, seed=1, **{**CONFIG, "max_time_steps": 3})
    runner = OnPolicyRunner(env, tiny_cfg(), log_dir=None, device="cpu")
    alg = runner.alg
    obs = env.get_observations()
    seen = 0
    for _ in range(3):
        with torch.inference_mode():
            a = alg.act(obs)
            values = alg.transition.values.clone().squeeze(1)
            obs, rew, dones, extras = env.step(a)
            step = alg.storage.step
            alg.process_env_step(obs, rew, dones, extras)
        stored = alg.storage.rewards[step].squeeze(1)
        expected = rew + alg.gamma * values * extras["time_outs"].float()
        torch.testing.assert_close(stored, expected, rtol=0, atol=1e-6)
        seen += int(extras["time_outs"].sum())
    # The third step is every env's time limit (unless it fell or hit a joint limit first).
    assert seen > 0


def test_on_policy_runner_learns_on_it_and_logs_the_episodes(tmp_path) -> None:
    torch.manual_seed(0)
    env = HyQRslRlVecEnv(num_envs=N, seed=1, **CONFIG)
    runner = OnPolicyRunner(env, tiny_cfg(), log_dir=str(tmp_path), device="cpu")
    runner.learn(num_learning_iterations=2)
    assert list(tmp_path.glob("model_*.pt"))
    from tensorboard.backend.event_processing.event_accumulator import EventAccumulator

    events = EventAccumulator(str(tmp_path))
    events.Reload()
    assert "hyq/distance_m" in events.Tags()["scalars"]


def test_numpy_actions_are_taken_as_tensors_and_junk_is_refused_by_name() -> None:
    env = HyQRslRlVecEnv(num_envs=2, seed=4)
    obs_np, rewards_np, _, _ = env.step(np.zeros((2, 12)))
    env2 = HyQRslRlVecEnv(num_envs=2, seed=4)
    obs_t, rewards_t, _, _ = env2.step(torch.zeros((2, 12)))
    assert torch.equal(rewards_np, rewards_t)
    assert torch.equal(obs_np["policy"], obs_t["policy"])
    with pytest.raises(ValueError, match="actions: expected a tensor or an array of numbers"):
        env.step([["a"] * 12] * 2)
    env.close()
    env2.close()


def test_a_list_of_engines_is_the_mixed_vector_env() -> None:
    import hyq

    engines = list(hyq.BACKENDS)
    env = HyQRslRlVecEnv(num_envs=N, seed=4, backend=engines, **CONFIG)
    expected = tuple(engines[i % len(engines)] for i in range(N))
    assert env.backends == expected
    reference = HyQVectorEnv(num_envs=N, autoreset_mode=AutoresetMode.SAME_STEP,
                             backend=engines, **CONFIG)
    obs, infos = reference.reset(seed=4)
    assert tuple(infos["backend"]) == expected
    np.testing.assert_array_equal(env.get_observations()["policy"].numpy(), obs)
    a = actions(1)[0]
    got, rewards, _, _ = env.step(torch.as_tensor(a))
    want, want_rewards, *_ = reference.step(a)
    np.testing.assert_array_equal(got["policy"].numpy(), want)
    np.testing.assert_array_equal(rewards.numpy(), want_rewards.astype(np.float32))
