//! Invariant: in a vector env whose envs run on different engines (`VecEnv<AnyBackend>`, the
//! engines given as a list assigned round-robin to the slots), env i gives, bit for bit, what a
//! single env of its engine gives with seed s + i and the same actions, through resets; the mix
//! gives the same results whatever the number of threads; and each env names its engine. Run on
//! every engine this build has: rapier always, DART with `--features dart`, MuJoCo with
//! `--features mujoco`.

use hyq_engines::{AnyBackend, AnyOptions};
use hyq_env::policy::{Policy, RandomPolicy};
use hyq_env::{AutoReset, Env, EnvError, ResetOptions, VecEnv, VecStepOut};
use hyq_physics::Backend;

/// Vector steps per run: with episodes of 12 steps, every env resets a few times.
const STEPS: usize = 30;
const SEED: u64 = 7;
const OVERRIDES: &[(&str, &str)] = &[
    ("task.max_time_steps", "12"),
    ("reset.joint_noise_rad", "0.05"),
    ("goal.mode", "random"),
];

/// What one env reported on each step: observation bits, reward bits and both flags.
type Trace = Vec<(Vec<u32>, u64, bool, bool)>;

fn built() -> Vec<&'static str> {
    hyq_engines::built().map(|e| e.name).collect()
}

/// The mix of `engines` (round-robin over `n` slots) on `threads` threads.
fn mixed(engines: &[&str], n: usize, threads: usize) -> VecEnv<AnyBackend> {
    let config = spec_tests::config(OVERRIDES);
    let physics = config.physics.clone();
    VecEnv::<AnyBackend>::with_options(spec_tests::robot(), config, n, AutoReset::NextStep, |i| {
        let name = engines[i % engines.len()];
        let options = AnyOptions::read(name, &physics)?;
        Ok(options.unwrap_or_else(|| panic!("{name} is built but has no AnyOptions")))
    })
    .and_then(|v| v.with_threads(threads))
    .unwrap_or_else(|e| panic!("{e}"))
}

/// The actions of every step for `n` envs, env-major within a step.
fn actions(n: usize, action_len: usize) -> Vec<Vec<f64>> {
    let mut policy = RandomPolicy::new(99);
    let env = spec_tests::env::<DefaultEngine>(OVERRIDES);
    let mut a = vec![0.0; action_len];
    (0..STEPS)
        .map(|_| {
            (0..n)
                .flat_map(|_| {
                    policy.act(&env.policy_input(), &mut a);
                    a.clone()
                })
                .collect()
        })
        .collect()
}

/// The default engine's backend, for the action space alone (the same on every engine).
type DefaultEngine = hyq_engines::backends::Rapier;

/// Each env's trace in the mix.
fn mixed_traces(engines: &[&str], n: usize, threads: usize, actions: &[Vec<f64>]) -> Vec<Trace> {
    let mut venv = mixed(engines, n, threads);
    let mut obs = vec![0.0f32; n * venv.observation_len()];
    let (mut rew, mut term, mut trunc) = (vec![0.0; n], vec![false; n], vec![false; n]);
    venv.reset(Some(SEED), &mut obs)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut traces = vec![Trace::new(); n];
    for step in actions {
        venv.step(
            step,
            VecStepOut {
                observations: &mut obs,
                rewards: &mut rew,
                terminated: &mut term,
                truncated: &mut trunc,
            },
        )
        .unwrap_or_else(|e| panic!("{e}"));
        for (i, trace) in traces.iter_mut().enumerate() {
            let o = &obs[i * venv.observation_len()..(i + 1) * venv.observation_len()];
            let bits = o.iter().map(|x| x.to_bits()).collect();
            trace.push((bits, rew[i].to_bits(), term[i], trunc[i]));
        }
    }
    for (i, name) in (0..n).map(|i| (i, engines[i % engines.len()])) {
        assert_eq!(venv.env(i).engine_name(), name, "env {i}");
    }
    traces
}

/// A single env on `B` seeded `seed`, given `actions` as the vector env's next-step autoreset
/// gives them: after an episode ends, the next action is ignored and the env resets.
fn single_trace<B: Backend>(seed: u64, actions: &[&[f64]]) -> Trace {
    let mut env = Env::<B>::new(spec_tests::robot(), spec_tests::config(OVERRIDES))
        .unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(seed), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let mut pending = false;
    let mut trace = Trace::new();
    for action in actions {
        if pending {
            pending = false;
            let r = env
                .reset(None, &ResetOptions::default())
                .unwrap_or_else(|e| panic!("{e}"));
            let bits = r.observation_f32.iter().map(|x| x.to_bits()).collect();
            trace.push((bits, 0f64.to_bits(), false, false));
            continue;
        }
        let s = env.step(action).unwrap_or_else(|e| panic!("{e}"));
        pending = s.terminated || s.truncated;
        let bits = s.observation_f32.iter().map(|x| x.to_bits()).collect();
        trace.push((bits, s.reward.to_bits(), s.terminated, s.truncated));
    }
    assert_eq!(env.engine_name(), B::NAME);
    trace
}

#[test]
fn each_env_of_the_mix_is_a_single_env_of_its_engine() {
    let engines = built();
    let n = 2 * engines.len();
    let action_len = 12;
    let actions = actions(n, action_len);
    let traces = mixed_traces(&engines, n, 2, &actions);
    for (i, trace) in traces.iter().enumerate() {
        let name = engines[i % engines.len()];
        let own: Vec<&[f64]> = actions
            .iter()
            .map(|step| &step[i * action_len..(i + 1) * action_len])
            .collect();
        let single = hyq_engines::with_engine!(name, B => single_trace::<B>(SEED + i as u64, &own))
            .unwrap_or_else(|| panic!("{name} is built"));
        assert_eq!(trace, &single, "env {i} on {name}");
        // The episodes ended and restarted within the run, so the resets were compared too.
        assert!(
            trace.iter().any(|(_, _, _, truncated)| *truncated),
            "env {i}"
        );
    }
}

#[test]
fn the_mix_gives_the_same_results_on_one_thread_and_on_two() {
    let engines = built();
    let n = 2 * engines.len() + 1;
    let actions = actions(n, 12);
    assert_eq!(
        mixed_traces(&engines, n, 1, &actions),
        mixed_traces(&engines, n, 2, &actions)
    );
}

/// Every engine this build has is in the mix the tests above run (DART and MuJoCo join it
/// under their features).
#[test]
fn the_mix_holds_every_built_engine() {
    let engines = built();
    assert_eq!(engines.first(), Some(&hyq_engines::DEFAULT.name));
    assert_eq!(
        engines.contains(&"dart"),
        cfg!(feature = "dart"),
        "{engines:?}"
    );
    assert_eq!(
        engines.contains(&"mujoco"),
        cfg!(feature = "mujoco"),
        "{engines:?}"
    );
}

/// A name that is no engine, or one this build lacks, gives no options (the fronts turn that
/// into their usual not-built error); options naming no engine are refused by name.
#[test]
fn an_engine_not_built_gives_no_options_and_unset_options_are_refused() {
    let physics = spec_tests::config(&[]).physics;
    assert!(matches!(AnyOptions::read("bullet", &physics), Ok(None)));
    for engine in hyq_engines::ENGINES.iter() {
        let read = AnyOptions::read(engine.name, &physics).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            read.as_ref().and_then(AnyOptions::engine),
            engine.built.then_some(engine.name)
        );
    }
    let refused = Env::<AnyBackend>::new(spec_tests::robot(), spec_tests::config(&[]));
    let Err(EnvError::Physics(e)) = refused else {
        panic!("an env on unset AnyOptions was built");
    };
    assert!(e.to_string().contains("no engine chosen"), "{e}");
}

/// A bad engine table is the error of the env that reads it, by key.
#[test]
fn a_bad_engine_table_is_named() {
    let name = hyq_engines::DEFAULT.name;
    let config = spec_tests::config(&[(&format!("physics.{name}.no_such_key"), "1")]);
    let Err(e) = AnyOptions::read(name, &config.physics) else {
        panic!("a bad table was read");
    };
    assert!(e.to_string().contains(&format!("physics.{name}")), "{e}");
}
