//! Invariant: every `[randomize]` mass range the configuration and the robot check accept
//! draws only bodies that every engine holds: finite masses and principal moments inside the
//! robot bounds table (`hyq_physics::bounds::BODY_MASS`, `BODY_MOMENT`, the same rows a robot's
//! own bodies are held to), which rapier, DART and MuJoCo then simulate without an error or an
//! abort. DART used to abort the process (an assertion, exit 134) on ranges that passed
//! validation (`trunk_added_mass_kg = [1e308, 1e308]`, `link_mass_scale = [1e-30, 1e-30]`).
//!
//! A property test draws ranges aimed at the edges (factors from far below the smallest one
//! allowed to the cap of 100, added masses up to past ±1e6 kg): a refused range must be refused
//! by name, an accepted one must give bodies inside the table on every reset and step on each
//! engine compiled in (rapier always; DART and MuJoCo with `--features dart,mujoco`).

use hyq_env::{Env, EnvConfig, ResetOptions};
use hyq_physics::bounds::{BODY_MASS, BODY_MOMENT};
use hyq_physics::{Backend, RobotModel};
use proptest::prelude::*;
use std::sync::Arc;

/// The smallest mass factor the robot's bodies allow: below it a body's mass or a principal
/// moment leaves the table.
fn smallest_scale(model: &RobotModel) -> f64 {
    model
        .links()
        .iter()
        .map(|l| {
            let smallest_moment = l.inertia.symmetric_eigenvalues().min();
            (BODY_MASS.low / l.mass).max(BODY_MOMENT.low / smallest_moment)
        })
        .fold(0.0, f64::max)
}

/// Builds an environment with these ranges on `B`; `None` when the ranges are refused (by
/// name: the test checks the message).
fn build<B: Backend>(model: &Arc<RobotModel>, scale: [f64; 2], added: [f64; 2]) -> Option<Env<B>> {
    let pairs = [
        (
            "randomize.link_mass_scale",
            format!("[{:?}, {:?}]", scale[0], scale[1]),
        ),
        (
            "randomize.trunk_added_mass_kg",
            format!("[{:?}, {:?}]", added[0], added[1]),
        ),
        ("task.max_time_steps", "5".to_owned()),
    ];
    let refused = |e: String| {
        assert!(
            !e.contains('\n')
                && (e.contains("randomize.link_mass_scale")
                    || e.contains("randomize.trunk_added_mass_kg")),
            "a refusal names the key: {e}"
        );
        None
    };
    let config = match EnvConfig::load::<&str, String>(None, &pairs) {
        Ok(c) => c,
        Err(e) => return refused(e.to_string()),
    };
    match Env::<B>::new(model.clone(), config) {
        Ok(env) => Some(env),
        Err(e) => refused(e.to_string()),
    }
}

/// Resets and steps an accepted environment: every drawn body inside the table, the engine
/// takes it, and nothing non-finite comes out.
fn run<B: Backend>(env: &mut Env<B>, seed: u64) {
    let zeros = vec![0.0; env.action_space().len()];
    for episode in 0..2 {
        let reset = env
            .reset(Some(seed.wrapping_add(episode)), &ResetOptions::default())
            .unwrap_or_else(|e| panic!("an accepted draw is reset: {e}"));
        assert!(reset.observation.iter().all(|v| v.is_finite()));
        let draw = env.episode_draw().expect("randomisation is on").clone();
        let dynamics = draw
            .dynamics
            .dynamics(env.model())
            .unwrap_or_else(|e| panic!("an accepted draw is valid: {e}"));
        for body in &dynamics.bodies {
            assert!(BODY_MASS.check(body.mass).is_ok(), "mass {}", body.mass);
            for m in body.inertia.symmetric_eigenvalues().iter() {
                assert!(BODY_MOMENT.check(*m).is_ok(), "moment {m}");
            }
        }
        for _ in 0..5 {
            let step = env
                .step(&zeros)
                .unwrap_or_else(|e| panic!("an accepted draw steps: {e}"));
            assert!(step.observation.iter().all(|v| v.is_finite()));
            assert!(step.reward.is_finite());
            if step.terminated || step.truncated {
                break;
            }
        }
    }
}

/// Every engine compiled into this test run.
fn on_every_engine(model: &Arc<RobotModel>, scale: [f64; 2], added: [f64; 2], seed: u64) {
    if let Some(mut env) = build::<hyq_rapier::RapierBackend>(model, scale, added) {
        run(&mut env, seed);
    }
    #[cfg(feature = "dart")]
    if let Some(mut env) = build::<hyq_dart::DartBackend>(model, scale, added) {
        run(&mut env, seed);
    }
    #[cfg(feature = "mujoco")]
    if let Some(mut env) = build::<hyq_mujoco::MujocoBackend>(model, scale, added) {
        run(&mut env, seed);
    }
}

#[test]
fn the_edges_of_the_allowed_ranges_run_on_every_engine() {
    let model = hyq_physics::bundled::hyq();
    let s_min = smallest_scale(&model);
    let trunk = model.links()[0].mass;
    // The lightest and the heaviest robot the table allows, and the two mixed.
    for (scale, added) in [
        ([s_min * 1.001, s_min * 1.001], [0.0, 0.0]),
        ([100.0, 100.0], [0.0, 0.0]),
        ([1.0, 1.0], [0.0, BODY_MASS.high - trunk - 1.0]),
        ([s_min * 1.001, 100.0], [0.0, 1e5]),
    ] {
        assert!(
            build::<hyq_rapier::RapierBackend>(&model, scale, added).is_some(),
            "{scale:?}, {added:?} is allowed"
        );
        on_every_engine(&model, scale, added, 3);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn every_accepted_mass_range_draws_bodies_every_engine_holds(
        lo_exp in -8.0f64..2.0,
        hi_share in 0.0f64..1.0,
        added_lo in prop_oneof![-2e6f64..2e6, -100.0f64..100.0, Just(-1e6), Just(1e6)],
        added_span in prop_oneof![Just(0.0), 0.0f64..1e6],
        seed in any::<u64>(),
    ) {
        let model = hyq_physics::bundled::hyq();
        let lo = 10f64.powf(lo_exp);
        let scale = [lo, lo + hi_share * (100.0 - lo)];
        let added = [added_lo, added_lo + added_span];
        on_every_engine(&model, scale, added, seed);
    }
}
