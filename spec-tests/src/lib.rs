//! The HyQ walk-to-goal spec, section by section, on the real simulators.
//!
//! The tests live in `tests/spec/`, one module per spec section (`s3_observations`,
//! `s4_rewards`, `s5_1_orientation`, …). Each module writes its test bodies once, inside
//! [`for_each_backend!`], which instantiates them once per physics backend that is built: a
//! `rapier` module always, a `dart` module when this crate is built with the `dart` feature
//! (it needs Debian's libdart) and a `mujoco` module with the `mujoco` feature (it needs
//! MuJoCo's library, `cargo xtask setup mujoco`), the way rustls instantiates one test module
//! per crypto provider.
//! Inside, the type alias `Engine` is the backend:
//!
//! ```text
//! spec_tests::for_each_backend! {
//!     #[test]
//!     fn standing_flags() {
//!         let mut env = spec_tests::env::<Engine>(&[]);
//!         // ...
//!     }
//! }
//! ```
//!
//! gives `s3_observations::rapier::standing_flags` and, with `--features dart`,
//! `s3_observations::dart::standing_flags`.
//!
//! Run: `cargo test -p spec-tests` (rapier), `cargo test -p spec-tests --features dart`
//! (rapier and DART), `--features mujoco` (rapier and MuJoCo), or both features.
//!
//! This library holds what the sections share: building environments from `key=value`
//! overrides, the standing action, stepping a policy (or a fixed action) while collecting its
//! records.

use std::sync::Arc;

use hyq_env::{Env, EnvConfig, Policy, PolicyInput, ResetOptions, StepRecord};
use hyq_physics::na::{Point3, Quaternion, UnitQuaternion};
use hyq_physics::{Backend, RobotModel};
use hyq_spec::ObservationLayout;

/// Instantiates the test bodies it is given once per engine that is built (hyq-engines'
/// `for_each_engine!`): in a module `rapier`, in a module `dart` when this crate has the `dart`
/// feature, and in a module `mujoco` with the `mujoco` feature. In each, the type alias `Engine`
/// is that backend and the enclosing module's items are in scope.
pub use hyq_engines::for_each_engine as for_each_backend;

/// The bundled HyQ.
pub fn robot() -> Arc<RobotModel> {
    hyq_physics::bundled::hyq()
}

/// The default configuration with `key=value` overrides (dotted keys, as `hyq --set`).
///
/// # Panics
/// If an override is refused (a test's own mistake).
pub fn config(overrides: &[(&str, &str)]) -> EnvConfig {
    let mut c = EnvConfig::default();
    c.set_all(overrides)
        .unwrap_or_else(|e| panic!("test configuration {overrides:?}: {e}"));
    c
}

/// An environment on backend `B` with the default configuration and `overrides`.
///
/// # Panics
/// If it cannot be built.
pub fn env<B: Backend>(overrides: &[(&str, &str)]) -> Env<B> {
    Env::new(robot(), config(overrides))
        .unwrap_or_else(|e| panic!("{} environment with {overrides:?}: {e}", B::NAME))
}

/// Resets `env` with `seed` and the default options.
///
/// # Panics
/// If the reset is refused.
pub fn reset<B: Backend>(env: &mut Env<B>, seed: u64) {
    env.reset(Some(seed), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("reset on {}: {e}", B::NAME));
}

/// The action (in the env's action mode) whose joint targets are the standing pose.
pub fn stand_action<B: Backend>(env: &Env<B>) -> Vec<f64> {
    let mut a = vec![0.0; env.action_space().len()];
    env.action_space()
        .action_for_targets(env.model().standing_pose(), env.joint_angles(), &mut a);
    a
}

/// One env step with `action`.
///
/// # Panics
/// If the step is refused.
pub fn step<B: Backend>(env: &mut Env<B>, action: &[f64]) -> StepRecord<'static> {
    env.step(action)
        .unwrap_or_else(|e| panic!("step on {}: {e}", B::NAME));
    owned_record(env, action)
}

/// The record of `env`'s last step with `action`, as written to JSONL and read back (so the
/// tests see exactly what a user's record holds).
///
/// # Panics
/// If the record does not read back (a schema bug).
pub fn owned_record<B: Backend>(env: &Env<B>, action: &[f64]) -> StepRecord<'static> {
    let line = StepRecord::from_env(env, action).to_json_line();
    StepRecord::from_json_line(&line).unwrap_or_else(|e| panic!("record {line}: {e}"))
}

/// Steps `policy` until the episode ends or `max_steps` steps were taken; returns the records.
///
/// # Panics
/// If a step is refused.
pub fn run_policy<B: Backend>(
    env: &mut Env<B>,
    policy: &mut dyn Policy,
    max_steps: u64,
) -> Vec<StepRecord<'static>> {
    let mut action = vec![0.0; env.action_space().len()];
    let mut records = Vec::new();
    for _ in 0..max_steps {
        policy.act(&env.policy_input(), &mut action);
        let record = step(env, &action);
        let done = record.terminated || record.truncated;
        records.push(record);
        if done {
            break;
        }
    }
    records
}

/// Steps the fixed `action` until the episode ends or `max_steps` steps were taken; returns the
/// records.
///
/// # Panics
/// If a step is refused.
pub fn run_action<B: Backend>(
    env: &mut Env<B>,
    action: &[f64],
    max_steps: u64,
) -> Vec<StepRecord<'static>> {
    run_policy(env, &mut Fixed(action), max_steps)
}

/// A policy that always takes the same action.
struct Fixed<'a>(&'a [f64]);

impl Policy for Fixed<'_> {
    fn name(&self) -> &'static str {
        "fixed"
    }

    fn act(&mut self, _input: &PolicyInput<'_>, action: &mut [f64]) {
        action.copy_from_slice(self.0);
    }
}

/// C^t, the trunk position rows of an observation (through the layout's named range).
pub fn position(layout: &ObservationLayout, obs: &[f64]) -> Point3<f64> {
    let p = &obs[layout.trunk_position()];
    Point3::new(p[0], p[1], p[2])
}

/// The trunk orientation rows (w, x, y, z) of an observation, as the unit quaternion they hold.
pub fn orientation(layout: &ObservationLayout, obs: &[f64]) -> UnitQuaternion<f64> {
    let q = &obs[layout.trunk_rotation()];
    UnitQuaternion::new_unchecked(Quaternion::new(q[0], q[1], q[2], q[3]))
}
