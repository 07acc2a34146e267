//! `VecEnv::step` on rapier, 2 envs, on a pool of 1 and of 2 threads, under uniformly random
//! actions redrawn every step (the anchor harness's `env_random` workload in each env) with
//! Gymnasium's next-step autoreset. Criterion reports the time per vector step (2 env steps);
//! the ratio of the two is the vector env's scaling over cores, which reaches 2 only when both
//! cores are free (`cargo xtask bench-vs-anchors` measures it beside the anchors).

use criterion::{Criterion, criterion_group};
use hyq_env::policy::{Policy, RandomPolicy};
use hyq_env::{AutoReset, EnvConfig, VecEnv, VecStepOut};
use hyq_rapier::RapierBackend;
use std::hint::black_box;

const N: usize = 2;

/// A vector env of N envs on `threads` threads, its buffers and a policy per env.
struct Bench {
    vec: VecEnv<RapierBackend>,
    policies: Vec<RandomPolicy>,
    actions: Vec<f64>,
    observations: Vec<f32>,
    rewards: Vec<f64>,
    terminated: Vec<bool>,
    truncated: Vec<bool>,
}

impl Bench {
    fn new(threads: usize) -> Self {
        let vec = VecEnv::new(
            hyq_physics::bundled::hyq(),
            EnvConfig::default(),
            N,
            AutoReset::NextStep,
        )
        .and_then(|v| v.with_threads(threads))
        .unwrap_or_else(|e| panic!("{e}"));
        let (obs, act) = (vec.observation_len(), vec.action_len());
        let mut b = Self {
            vec,
            policies: (0..N as u64).map(RandomPolicy::new).collect(),
            actions: vec![0.0; N * act],
            observations: vec![0.0; N * obs],
            rewards: vec![0.0; N],
            terminated: vec![false; N],
            truncated: vec![false; N],
        };
        b.vec
            .reset(Some(0), &mut b.observations)
            .unwrap_or_else(|e| panic!("{e}"));
        b
    }

    fn step(&mut self) -> f64 {
        let act = self.vec.action_len();
        {
            let input = self.vec.env(0).policy_input();
            for (p, a) in self
                .policies
                .iter_mut()
                .zip(self.actions.chunks_exact_mut(act))
            {
                p.act(&input, a);
            }
        }
        self.vec
            .step(
                &self.actions,
                VecStepOut {
                    observations: &mut self.observations,
                    rewards: &mut self.rewards,
                    terminated: &mut self.terminated,
                    truncated: &mut self.truncated,
                },
            )
            .unwrap_or_else(|e| panic!("{e}"));
        self.rewards.iter().sum()
    }
}

fn bench_vec_step(c: &mut Criterion) {
    for threads in [1, 2] {
        let mut b = Bench::new(threads);
        c.bench_function(
            &format!("vec_env_step/rapier/{N}_envs/{threads}_threads"),
            |bench| bench.iter(|| black_box(b.step())),
        );
    }
}

criterion_group!(benches, bench_vec_step);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
}
