//! Invariant: `Env::step` allocates nothing per env step (the hot path reuses the env's
//! buffers): after a warm-up step, 1000 steps of the env's own code, on the allocation-free
//! scripted backend, make no allocation, with timing off and on. (rapier itself allocates small
//! solver buffers inside each of its steps; that is rapier's, not the env's.)

use hyq_env::testing::ScriptedBackend;
use hyq_env::{Env, EnvConfig, ResetOptions};
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};
use std::alloc::System;

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

#[test]
fn stepping_allocates_nothing() {
    let mut config = EnvConfig::default();
    config
        .set_all(&[
            ("task.norm_rew_scaling", "10"),
            ("task.base_rew_scaling", "1"),
            ("task.max_time_steps", "100000"),
        ])
        .unwrap_or_else(|e| panic!("{e}"));
    for timing in [false, true] {
        let mut env = Env::<ScriptedBackend>::new(hyq_physics::bundled::hyq(), config.clone())
            .unwrap_or_else(|e| panic!("{e}"));
        env.set_timing(timing);
        env.reset(Some(1), &ResetOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let trunk = env.model().trunk_tracked_index();
        let standing = env.model().standing_pose().to_vec();
        // The toy joints would run into their limits; hold them near standing instead.
        env.backend_mut().set_script(move |w| {
            for (q, s) in w.q.iter_mut().zip(&standing) {
                *q = s + 0.5 * (*q - s);
            }
            w.trunk.linvel.x = 0.3;
            w.contacts[trunk] = false;
            Ok(())
        });
        let mut action = [0.0f64; 12];
        let mut action32 = [0.0f32; 12];
        env.step(&action).unwrap_or_else(|e| panic!("{e}"));
        let region = Region::new(GLOBAL);
        let mut total = 0.0;
        for t in 0..1000 {
            action[t % 12] = ((t as f64) * 0.37).sin() * 1.2; // sometimes clipped
            let s = if t % 2 == 0 {
                env.step(&action)
            } else {
                action32[t % 12] = action[t % 12] as f32;
                env.step(&action32)
            }
            .unwrap_or_else(|e| panic!("{e}"));
            total += s.reward + f64::from(s.observation_f32[38]);
        }
        let stats = region.change();
        assert!(total.is_finite());
        assert_eq!(env.info().t, 1001);
        assert_eq!(
            stats.allocations + stats.reallocations,
            0,
            "timing {timing}: {stats:?} in 1000 steps"
        );
    }
}
