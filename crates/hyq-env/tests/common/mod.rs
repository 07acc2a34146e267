//! Helpers shared by the integration tests: environments on the scripted and rapier backends,
//! the action that holds the standing pose, and a trot episode run to its truncation.
#![allow(dead_code)]

use hyq_env::policy::{Policy, Trot};
use hyq_env::testing::ScriptedBackend;
use hyq_env::{Env, EnvConfig, ResetOptions};
use hyq_physics::Backend;
use hyq_rapier::RapierBackend;

/// A configuration from `key=value` overrides of the defaults.
pub fn config(overrides: &[(&str, &str)]) -> EnvConfig {
    let mut c = EnvConfig::default();
    c.set_all(overrides).unwrap_or_else(|e| panic!("{e}"));
    c
}

pub fn env<B: Backend>(overrides: &[(&str, &str)]) -> Env<B> {
    Env::new(hyq_physics::bundled::hyq(), config(overrides)).unwrap_or_else(|e| panic!("{e}"))
}

pub fn scripted(overrides: &[(&str, &str)]) -> Env<ScriptedBackend> {
    env(overrides)
}

pub fn rapier(overrides: &[(&str, &str)]) -> Env<RapierBackend> {
    env(overrides)
}

pub fn reset<B: Backend>(env: &mut Env<B>, seed: u64) {
    env.reset(Some(seed), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
}

/// The action (in the env's mode) that targets the standing pose.
pub fn stand_action<B: Backend>(env: &Env<B>) -> Vec<f64> {
    let mut a = vec![0.0; env.action_space().len()];
    env.action_space()
        .action_for_targets(env.model().standing_pose(), env.joint_angles(), &mut a);
    a
}

/// Runs the robot profile's trot from the env's current state until the episode is truncated, asserting
/// at every step that the trunk never touched the ground and that nothing terminated the
/// episode; returns the step at which it was truncated.
pub fn trot_until_truncated<B: Backend>(env: &mut Env<B>) -> u64 {
    let model = env.model().clone();
    let mut trot = Trot::from_profile(&model).unwrap_or_else(|e| panic!("{e}"));
    let mut a = vec![0.0; env.action_space().len()];
    let trunk_row = env.observation_layout().trunk_contact();
    loop {
        trot.act(&env.policy_input(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        let t = s.info.t;
        assert_eq!(
            s.observation[trunk_row], 0.0,
            "trunk touched the ground at t = {t}"
        );
        assert!(!s.terminated, "terminated at t = {t}: {:?}", s.info.reasons);
        if s.truncated {
            return t;
        }
    }
}
