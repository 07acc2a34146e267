//! `Env::step` on rapier under uniformly random actions redrawn every step, resetting on any
//! episode end (fall, joint limit or 1000 steps): the workload of the anchor harness's
//! `env_random` case. After criterion's figure, one timed run of 3000 steps prints the share of
//! the step spent in the actuator, the physics, the observation and the spec's rules.

use criterion::{Criterion, criterion_group};
use hyq_env::policy::{Policy, RandomPolicy};
use hyq_env::{Env, EnvConfig, ResetOptions};
use hyq_rapier::RapierBackend;
use std::hint::black_box;

fn env() -> Env<RapierBackend> {
    let mut env = Env::new(hyq_physics::bundled::hyq(), EnvConfig::default())
        .unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(0), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    env
}

fn step(env: &mut Env<RapierBackend>, policy: &mut RandomPolicy, action: &mut [f64]) -> f64 {
    if env.needs_reset() {
        env.reset(None, &ResetOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
    }
    policy.act(&env.policy_input(), action);
    env.step(action)
        .map(|s| s.reward)
        .unwrap_or_else(|e| panic!("{e}"))
}

fn bench_step(c: &mut Criterion) {
    let mut env = env();
    let mut policy = RandomPolicy::new(1);
    let mut action = vec![0.0; 12];
    c.bench_function("env_step/rapier/random_actions", |b| {
        b.iter(|| black_box(step(&mut env, &mut policy, &mut action)))
    });
}

fn print_shares() {
    let mut env = env();
    let mut policy = RandomPolicy::new(2);
    let mut action = vec![0.0; 12];
    for _ in 0..200 {
        step(&mut env, &mut policy, &mut action);
    }
    env.set_timing(true);
    env.clear_timing();
    let steps = 3000;
    for _ in 0..steps {
        step(&mut env, &mut policy, &mut action);
    }
    let t = *env.timing();
    let total = t.total.as_secs_f64();
    let n = t.steps as f64;
    let part = |name: &str, d: std::time::Duration| {
        format!(
            "{name} {:.2} µs ({:.2} %)",
            1e6 * d.as_secs_f64() / n,
            100.0 * d.as_secs_f64() / total
        )
    };
    println!(
        "env_step/rapier/random_actions, {} timed steps: {:.1} µs/step = {}, {}, {}, {}, {}",
        t.steps,
        1e6 * total / n,
        part("physics", t.physics),
        part("actuator", t.actuator),
        part("observation", t.observation),
        part("spec evaluation", t.spec),
        part("other", t.other()),
    );
}

criterion_group!(benches, bench_step);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    print_shares();
}
