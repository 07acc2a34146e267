//! Invariant: a VecEnv of N envs gives, bit for bit, what N single envs give for the same seeds
//! (env i seeded s + i) and actions, whatever the thread count, in every autoreset mode
//! (next-step: the action after an end is ignored and the env resets; same-step: the reset
//! observation replaces the final one, which is kept; disabled: stepping an ended env is an
//! error that changes nothing).

mod common;

use common::config;
use hyq_env::policy::{Policy, RandomPolicy};
use hyq_env::{AutoReset, Env, ResetOptions, VecEnv, VecEnvError, VecStepOut};
use hyq_rapier::RapierBackend;

const N: usize = 3;
const STEPS: usize = 45;
const OVERRIDES: &[(&str, &str)] = &[
    ("task.max_time_steps", "15"),
    ("reset.joint_noise_rad", "0.05"),
    ("goal.mode", "random"),
];

/// The actions of step k for env i, fixed in advance (f32, as Python would pass them).
fn actions() -> Vec<Vec<f32>> {
    let mut policy = RandomPolicy::new(99);
    let model = hyq_physics::bundled::hyq();
    let env = Env::<RapierBackend>::new(model, config(OVERRIDES)).unwrap_or_else(|e| panic!("{e}"));
    let mut a = vec![0.0; 12];
    (0..STEPS)
        .map(|_| {
            (0..N)
                .flat_map(|_| {
                    policy.act(&env.policy_input(), &mut a);
                    a.iter().map(|v| *v as f32).collect::<Vec<_>>()
                })
                .collect()
        })
        .collect()
}

#[derive(Debug, PartialEq)]
struct Trace {
    obs: Vec<u32>,
    rewards: Vec<u64>,
    terminated: Vec<bool>,
    truncated: Vec<bool>,
    finals: Vec<Option<Vec<u32>>>,
}

fn bits32(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// `threads`: a dedicated pool's count, or `None` for rayon's global pool.
fn vec_run(mode: AutoReset, threads: Option<usize>) -> Trace {
    let model = hyq_physics::bundled::hyq();
    let venv = VecEnv::<RapierBackend>::new(model, config(OVERRIDES), N, mode);
    let mut venv = match threads {
        Some(t) => venv.and_then(|v| v.with_threads(t)),
        None => venv,
    }
    .unwrap_or_else(|e| panic!("{e}"));
    let mut obs = vec![0.0f32; N * venv.observation_len()];
    let (mut rew, mut term, mut trunc) = (vec![0.0; N], vec![false; N], vec![false; N]);
    venv.reset(Some(20), &mut obs)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut trace = Trace {
        obs: bits32(&obs),
        rewards: vec![],
        terminated: vec![],
        truncated: vec![],
        finals: vec![],
    };
    for a in actions() {
        let out = VecStepOut {
            observations: &mut obs,
            rewards: &mut rew,
            terminated: &mut term,
            truncated: &mut trunc,
        };
        venv.step(&a, out).unwrap_or_else(|e| panic!("{e}"));
        trace.obs.extend(bits32(&obs));
        trace.rewards.extend(rew.iter().map(|r| r.to_bits()));
        trace.terminated.extend(&term);
        trace.truncated.extend(&trunc);
        for i in 0..N {
            trace.finals.push(venv.final_observation(i).map(bits32));
        }
    }
    trace
}

/// The same with N single envs and the documented autoreset semantics written out by hand.
fn single_run(mode: AutoReset) -> Trace {
    let model = hyq_physics::bundled::hyq();
    let mut envs: Vec<Env<RapierBackend>> = (0..N)
        .map(|_| Env::new(model.clone(), config(OVERRIDES)).unwrap_or_else(|e| panic!("{e}")))
        .collect();
    let mut trace = Trace {
        obs: vec![],
        rewards: vec![],
        terminated: vec![],
        truncated: vec![],
        finals: vec![],
    };
    for (i, env) in envs.iter_mut().enumerate() {
        let r = env
            .reset(Some(20 + i as u64), &ResetOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        trace.obs.extend(bits32(r.observation_f32));
    }
    let mut pending = [false; N];
    for a in actions() {
        for (i, env) in envs.iter_mut().enumerate() {
            let action = &a[i * 12..(i + 1) * 12];
            let mut fin = None;
            if pending[i] {
                pending[i] = false;
                let r = env
                    .reset(None, &ResetOptions::default())
                    .unwrap_or_else(|e| panic!("{e}"));
                trace.obs.extend(bits32(r.observation_f32));
                trace.rewards.push(0f64.to_bits());
                trace.terminated.push(false);
                trace.truncated.push(false);
            } else {
                let s = env.step(action).unwrap_or_else(|e| panic!("{e}"));
                let (obs, reward, te, tr) = (
                    s.observation_f32.to_vec(),
                    s.reward,
                    s.terminated,
                    s.truncated,
                );
                trace.rewards.push(reward.to_bits());
                trace.terminated.push(te);
                trace.truncated.push(tr);
                if te || tr {
                    if mode == AutoReset::NextStep {
                        pending[i] = true;
                        trace.obs.extend(bits32(&obs));
                    } else {
                        fin = Some(bits32(&obs));
                        let r = env
                            .reset(None, &ResetOptions::default())
                            .unwrap_or_else(|e| panic!("{e}"));
                        trace.obs.extend(bits32(r.observation_f32));
                    }
                } else {
                    trace.obs.extend(bits32(&obs));
                }
            }
            trace.finals.push(fin);
        }
    }
    trace
}

#[test]
fn next_step_autoreset_matches_single_envs_on_any_thread_count() {
    let expected = single_run(AutoReset::NextStep);
    assert!(expected.truncated.iter().filter(|t| **t).count() >= N * 2);
    // One thread (the caller alone), two and N + 1 (more threads than envs), and the global pool.
    for threads in [Some(1), Some(2), Some(N + 1), None] {
        assert_eq!(
            vec_run(AutoReset::NextStep, threads),
            expected,
            "{threads:?} threads"
        );
    }
}

#[test]
fn same_step_autoreset_matches_single_envs_and_keeps_the_final_observation() {
    let expected = single_run(AutoReset::SameStep);
    assert!(expected.finals.iter().any(Option::is_some));
    assert_eq!(vec_run(AutoReset::SameStep, Some(2)), expected);
    assert_eq!(vec_run(AutoReset::SameStep, Some(1)), expected);
}

#[test]
fn disabled_autoreset_refuses_to_step_an_ended_env_until_it_is_reset() {
    let model = hyq_physics::bundled::hyq();
    let mut venv = VecEnv::<RapierBackend>::new(
        model,
        config(&[("task.max_time_steps", "2")]),
        2,
        AutoReset::Disabled,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut obs = vec![0.0f32; 2 * 39];
    let (mut rew, mut term, mut trunc) = (vec![0.0; 2], vec![false; 2], vec![false; 2]);
    let actions = vec![0.0f64; 24];
    let mut step = |venv: &mut VecEnv<RapierBackend>, obs: &mut Vec<f32>| {
        venv.step(
            &actions,
            VecStepOut {
                observations: obs,
                rewards: &mut rew,
                terminated: &mut term,
                truncated: &mut trunc,
            },
        )
        .map(|()| trunc.clone())
    };
    let err = step(&mut venv, &mut obs).err();
    assert!(
        matches!(err, Some(VecEnvError::Env { index: 0, .. })),
        "{err:?}"
    );
    venv.reset(Some(0), &mut obs)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(step(&mut venv, &mut obs).ok(), Some(vec![false, false]));
    assert_eq!(step(&mut venv, &mut obs).ok(), Some(vec![true, true]));
    let before = obs.clone();
    let msg = step(&mut venv, &mut obs)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        msg.contains("env 0") && msg.contains("without reset"),
        "{msg}"
    );
    assert_eq!(obs, before);
    venv.reset_env(0, None, &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    venv.reset_env(1, None, &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(step(&mut venv, &mut obs).ok(), Some(vec![false, false]));
}

#[test]
fn bad_buffers_and_actions_are_refused_before_any_env_steps() {
    let model = hyq_physics::bundled::hyq();
    let mut venv = VecEnv::<RapierBackend>::new(model, config(&[]), 2, AutoReset::NextStep)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut obs = vec![0.0f32; 2 * 39];
    venv.reset(Some(0), &mut obs)
        .unwrap_or_else(|e| panic!("{e}"));
    let (mut rew, mut term, mut trunc) = (vec![0.0; 2], vec![false; 2], vec![false; 2]);
    let mut bad = vec![0.0f64; 24];
    bad[14] = f64::NAN;
    let err = venv
        .step(
            &bad,
            VecStepOut {
                observations: &mut obs,
                rewards: &mut rew,
                terminated: &mut term,
                truncated: &mut trunc,
            },
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(err.contains("env 1") && err.contains("action[2]"), "{err}");
    assert_eq!(venv.info(0).t, 0, "env 0 did not step either");
    let err = venv
        .step(
            &[0.0f64; 23],
            VecStepOut {
                observations: &mut obs,
                rewards: &mut rew,
                terminated: &mut term,
                truncated: &mut trunc,
            },
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(err.contains("actions") && err.contains("24"), "{err}");
    assert!(
        VecEnv::<RapierBackend>::new(
            hyq_physics::bundled::hyq(),
            config(&[]),
            0,
            AutoReset::NextStep
        )
        .is_err()
    );
}

#[test]
fn env_and_thread_counts_are_bounded_and_checked_before_anything_is_built() {
    // Python's make_vec(num_envs=10**8) used to build envs until memory ran out.
    let model = hyq_physics::bundled::hyq();
    let build = |n: usize| {
        VecEnv::<hyq_env::testing::ScriptedBackend>::new(
            model.clone(),
            config(&[]),
            n,
            AutoReset::NextStep,
        )
    };
    for n in [0, hyq_env::MAX_ENVS + 1, 100_000_000] {
        let e = build(n).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(
            e.contains("num_envs") && e.contains("4096") && e.contains(&n.to_string()),
            "{n}: {e}"
        );
    }
    for threads in [0, hyq_env::MAX_THREADS + 1] {
        let e = build(2)
            .and_then(|v| v.with_threads(threads))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            e.contains("threads") && e.contains("4096"),
            "{threads}: {e}"
        );
    }
    assert!(build(2).and_then(|v| v.with_threads(1)).is_ok());
}

/// A panic inside one env's step (a scripted backend's, standing for a bug in an engine) reaches
/// the caller as that panic on any thread count, rather than leaving the threads that wait for
/// the env's step waiting forever.
#[test]
fn a_panic_in_one_envs_step_reaches_the_caller_instead_of_hanging() {
    use hyq_env::testing::ScriptedBackend;
    use std::panic::{AssertUnwindSafe, catch_unwind};
    use std::sync::mpsc;
    use std::time::Duration;

    for threads in [1, 2, 3] {
        let (sent, received) = mpsc::channel();
        std::thread::spawn(move || {
            let model = hyq_physics::bundled::hyq();
            let mut venv =
                VecEnv::<ScriptedBackend>::new(model, config(&[]), 4, AutoReset::NextStep)
                    .and_then(|v| v.with_threads(threads))
                    .unwrap_or_else(|e| panic!("{e}"));
            let mut obs = vec![0.0f32; 4 * venv.observation_len()];
            venv.reset(Some(0), &mut obs)
                .unwrap_or_else(|e| panic!("{e}"));
            // Envs 0-2 take 2 ms a sub-step, so the calling thread is still busy with its own
            // block when a pool thread reaches env 3 (on 2 and 3 threads the last block's).
            for i in 0..3 {
                venv.env_mut(i).backend_mut().set_script(|_| {
                    std::thread::sleep(Duration::from_millis(2));
                    Ok(())
                });
            }
            venv.env_mut(3)
                .backend_mut()
                .set_script(|_| panic!("scripted failure"));
            let actions = vec![0.0f32; 4 * venv.action_len()];
            let (mut rew, mut term, mut trunc) = (vec![0.0; 4], vec![false; 4], vec![false; 4]);
            let stepped = catch_unwind(AssertUnwindSafe(|| {
                venv.step(
                    &actions,
                    VecStepOut {
                        observations: &mut obs,
                        rewards: &mut rew,
                        terminated: &mut term,
                        truncated: &mut trunc,
                    },
                )
            }));
            let message = stepped
                .err()
                .and_then(|p| p.downcast_ref::<&str>().map(|s| s.to_string()));
            let _ = sent.send(message);
        });
        let message = received
            .recv_timeout(Duration::from_secs(60))
            .unwrap_or_else(|_| panic!("{threads} threads: the step hung for 60 s"));
        assert_eq!(
            message.as_deref(),
            Some("scripted failure"),
            "{threads} threads"
        );
    }
}
