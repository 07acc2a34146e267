//! Invariant: an env step allocates nothing of its own. Counted per thread (allocation-counter's
//! global allocator, thread-local counts), on the thread that steps, so the test harness's
//! other threads and the other tests of this binary cannot disturb the count:
//! - on the allocation-free scripted backend, 1000 env steps (random actions, f64 and f32,
//!   timing off and on, with episode ends and resets between the counted steps) make zero
//!   allocations;
//! - on rapier, the env's steps make exactly the allocations made inside rapier's own
//!   `Backend::step` calls, measured by a forwarding backend, and none besides: the actuator,
//!   the state and contact reads, the observation and the spec's rules allocate nothing.
//!   rapier's own count per physics sub-step is printed (it allocates LU workspaces and solver
//!   buffers inside every step; no option of its public API avoids that);
//! - on MuJoCo (with `--features mujoco`), 1000 env steps make zero allocations: the backend
//!   reads and writes through the C shim into buffers it holds, and MuJoCo works in the arena
//!   it allocated when the world was built (its own allocations would not go through Rust's
//!   allocator; it makes none per step).

use std::sync::Arc;

use hyq_env::testing::ScriptedBackend;
use hyq_env::{Env, EnvConfig, Policy, RandomPolicy, ResetOptions};
use hyq_physics::na::{Isometry3, Vector3};
use hyq_physics::{
    Backend, Dynamics, MassProperties, PhysicsError, PhysicsParams, RobotModel, RobotState,
    Terrain, TrunkState,
};
use hyq_rapier::RapierBackend;

/// Allocations (and reallocations) made by `f` on this thread. allocation-counter installs a
/// global allocator that counts per thread; nested calls add to the enclosing count.
fn allocations<R>(f: impl FnOnce() -> R) -> (u64, R) {
    let mut out = None;
    let info = allocation_counter::measure(|| out = Some(f()));
    match out {
        Some(r) => (info.count_total, r),
        None => unreachable!("measure runs the closure once"),
    }
}

/// rapier behind a backend that tallies the allocations made inside its `step` calls.
struct Tallied {
    inner: RapierBackend,
    inside_step: u64,
    steps: u64,
}

impl Backend for Tallied {
    type Options = <RapierBackend as Backend>::Options;
    const NAME: &'static str = RapierBackend::NAME;

    fn build(
        model: Arc<RobotModel>,
        params: &PhysicsParams,
        options: &Self::Options,
    ) -> Result<Self, PhysicsError> {
        Ok(Self {
            inner: RapierBackend::build(model, params, options)?,
            inside_step: 0,
            steps: 0,
        })
    }
    fn model(&self) -> &Arc<RobotModel> {
        self.inner.model()
    }
    fn params(&self) -> &PhysicsParams {
        self.inner.params()
    }
    fn apply_state(&mut self, state: &RobotState) -> Result<(), PhysicsError> {
        self.inner.apply_state(state)
    }
    fn apply_joint_torques(&mut self, torques: &[f64]) -> Result<(), PhysicsError> {
        self.inner.apply_joint_torques(torques)
    }
    fn step(&mut self) -> Result<(), PhysicsError> {
        let (count, r) = allocations(|| self.inner.step());
        self.inside_step += count;
        self.steps += 1;
        r
    }
    fn joint_positions(&self, out: &mut [f64]) {
        self.inner.joint_positions(out);
    }
    fn joint_velocities(&self, out: &mut [f64]) {
        self.inner.joint_velocities(out);
    }
    fn trunk(&self) -> TrunkState {
        self.inner.trunk()
    }
    fn contacts(&self, out: &mut [bool]) {
        self.inner.contacts(out);
    }
    fn link_poses(&self, out: &mut [Isometry3<f64>]) {
        self.inner.link_poses(out);
    }
    fn total_mass(&self) -> f64 {
        self.inner.total_mass()
    }
    fn apply_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError> {
        self.inner.apply_dynamics(dynamics)
    }
    fn body_mass_properties(&self, link: usize) -> MassProperties {
        self.inner.body_mass_properties(link)
    }
    fn apply_trunk_velocity_change(&mut self, dv: &Vector3<f64>) -> Result<(), PhysicsError> {
        self.inner.apply_trunk_velocity_change(dv)
    }
    fn terrain(&self) -> &Terrain {
        self.inner.terrain()
    }
    fn apply_terrain(&mut self, terrain: &Terrain) -> Result<(), PhysicsError> {
        self.inner.apply_terrain(terrain)
    }
}

fn config(max_steps: &str) -> EnvConfig {
    let mut c = EnvConfig::default();
    c.set_all(&[("task.max_time_steps", max_steps)])
        .unwrap_or_else(|e| panic!("{e}"));
    c
}

/// `steps` env steps of random actions (drawn before counting), counted; resets happen
/// outside the count. Returns (allocations, steps taken, episodes ended).
fn counted_steps<B: Backend>(env: &mut Env<B>, steps: usize, seed: u64) -> (u64, usize, u64) {
    let n = env.action_space().len();
    let mut policy = RandomPolicy::new(seed);
    let mut actions = vec![0.0f64; steps * n];
    {
        let input = env.policy_input();
        for a in actions.chunks_exact_mut(n) {
            policy.act(&input, a);
        }
    }
    let actions32: Vec<f32> = actions.iter().map(|&a| a as f32).collect();
    let (mut total, mut ended) = (0, 0);
    for t in 0..steps {
        let (count, done) = allocations(|| {
            let s = if t % 2 == 0 {
                env.step(&actions[t * n..(t + 1) * n])
            } else {
                env.step(&actions32[t * n..(t + 1) * n])
            }
            .unwrap_or_else(|e| panic!("step {t}: {e}"));
            assert!(s.reward.is_finite() && s.observation_f32.iter().all(|x| x.is_finite()));
            s.terminated || s.truncated
        });
        total += count;
        if done {
            ended += 1;
            env.reset(None, &ResetOptions::default())
                .unwrap_or_else(|e| panic!("{e}"));
        }
    }
    (total, steps, ended)
}

#[test]
fn scripted_env_steps_allocate_nothing() {
    for timing in [false, true] {
        let mut env = Env::<ScriptedBackend>::new(hyq_physics::bundled::hyq(), config("100"))
            .unwrap_or_else(|e| panic!("{e}"));
        env.set_timing(timing);
        env.reset(Some(3), &ResetOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        // A warm-up step outside the count.
        let zero = vec![0.0f64; env.action_space().len()];
        env.step(&zero).unwrap_or_else(|e| panic!("{e}"));
        let (count, steps, ended) = counted_steps(&mut env, 1000, 4);
        assert!(
            ended >= 5,
            "timeouts every 100 steps: {ended} episodes ended"
        );
        assert_eq!(
            count, 0,
            "timing {timing}: {count} allocations in {steps} env steps"
        );
    }
}

/// With every gait regulariser on, a step still allocates nothing (their state is built with
/// the environment).
#[test]
fn scripted_env_steps_with_regularisers_allocate_nothing() {
    let mut c = config("100");
    c.set_all(&[
        ("regularizers.preset", "legged_gym"),
        ("regularizers.foot_slip", "-0.1"),
        ("regularizers.base_height", "-1"),
    ])
    .unwrap_or_else(|e| panic!("{e}"));
    let mut env = Env::<ScriptedBackend>::new(hyq_physics::bundled::hyq(), c)
        .unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(3), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let zero = vec![0.0f64; env.action_space().len()];
    env.step(&zero).unwrap_or_else(|e| panic!("{e}"));
    assert!(env.info().regularizers.is_some());
    let (count, steps, ended) = counted_steps(&mut env, 1000, 4);
    assert!(ended >= 5, "{ended} episodes ended");
    assert_eq!(count, 0, "{count} allocations in {steps} env steps");
}

#[test]
fn the_counter_sees_allocations_on_this_thread_only() {
    let (here, v) = allocations(|| vec![1u8; 64]);
    assert_eq!((here, v.len()), (1, 64));
    // A first spawn outside the count: the standard library caches settings on the first one.
    let warm = std::thread::scope(|s| s.spawn(|| vec![0u8; 8].len()).join().ok());
    assert_eq!(warm, Some(8));
    // Spawning allocates on this thread (the thread's handle and result slot), the same each
    // time; the other thread's 100 vectors must not be counted.
    let (spawn_only, _) = allocations(|| std::thread::scope(|s| s.spawn(|| 0).join().ok()));
    let (with_work, n) = allocations(|| {
        std::thread::scope(|s| {
            s.spawn(|| (0..100).map(|i| vec![i as u8; 64].len()).sum::<usize>())
                .join()
                .ok()
        })
    });
    assert_eq!(n, Some(6400));
    assert_eq!(
        with_work, spawn_only,
        "the other thread's allocations were counted"
    );
}

#[test]
fn rapier_env_steps_allocate_only_inside_rapier() {
    let mut env = Env::<Tallied>::new(hyq_physics::bundled::hyq(), config("1000"))
        .unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(5), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let zero = vec![0.0f64; env.action_space().len()];
    env.step(&zero).unwrap_or_else(|e| panic!("{e}"));
    for timing in [false, true] {
        env.set_timing(timing);
        let b = env.backend_mut();
        b.inside_step = 0;
        b.steps = 0;
        let (count, steps, _) = counted_steps(&mut env, 300, 6);
        let b = env.backend_mut();
        assert_eq!(b.steps, 10 * steps as u64, "10 sub-steps per env step");
        assert_eq!(
            count, b.inside_step,
            "timing {timing}: {count} allocations in {steps} env steps, {} of them inside \
             rapier's step: the env's own code allocated",
            b.inside_step
        );
        println!(
            "timing {timing}: {count} allocations in {steps} env steps, all inside rapier's \
             step ({:.1} per physics sub-step)",
            b.inside_step as f64 / b.steps as f64
        );
    }
}

#[cfg(feature = "mujoco")]
#[test]
fn mujoco_env_steps_allocate_nothing() {
    for timing in [false, true] {
        let mut env =
            Env::<hyq_mujoco::MujocoBackend>::new(hyq_physics::bundled::hyq(), config("100"))
                .unwrap_or_else(|e| panic!("{e}"));
        env.set_timing(timing);
        env.reset(Some(7), &ResetOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let zero = vec![0.0f64; env.action_space().len()];
        env.step(&zero).unwrap_or_else(|e| panic!("{e}"));
        let (count, steps, ended) = counted_steps(&mut env, 1000, 8);
        assert!(
            ended >= 5,
            "episodes end every 100 steps at most: {ended} ended"
        );
        assert_eq!(
            count, 0,
            "timing {timing}: {count} allocations in {steps} env steps on MuJoCo"
        );
    }
}
