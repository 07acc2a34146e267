//! Invariant (spec §3, rows 33–35): the trunk acceleration is (v^t − v^{t−1}) / Δt_env, the
//! change of the trunk frame origin's world velocity over the env step divided by
//! sub-steps × dt; it is 0 after reset, whatever the velocity at reset.

mod common;

use common::scripted;
use hyq_env::ResetOptions;

#[test]
fn acceleration_is_the_velocity_change_over_the_env_step() {
    for (substeps, dt) in [(10u32, 0.001), (4, 0.0025), (1, 0.002)] {
        let mut env = scripted(&[
            ("control.sim_steps_per_env_step", &substeps.to_string()),
            ("physics.dt", &dt.to_string()),
        ]);
        let mut state = env.model().spawn_state();
        state.trunk.linvel.x = 0.25;
        let accel = env.observation_layout().trunk_acceleration();
        let r = env
            .reset(
                Some(0),
                &ResetOptions {
                    state: Some(state),
                    ..ResetOptions::default()
                },
            )
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(&r.observation[accel.clone()], &[0.0; 3], "0 after reset");
        // The script adds a known velocity in each sub-step: 0.01, 0.02, ... m/s in x, y, z.
        env.backend_mut().set_script(|w| {
            w.trunk.linvel.x += 0.01;
            w.trunk.linvel.y -= 0.02;
            w.trunk.linvel.z += 0.03;
            Ok(())
        });
        let env_dt = f64::from(substeps) * dt;
        assert_eq!(env.env_dt(), env_dt);
        let mut v_prev = env.trunk().linvel;
        for _ in 0..3 {
            let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
            let a = s.observation[accel.clone()].to_vec();
            let v = env.trunk().linvel;
            let expected = (v - v_prev) / env_dt;
            assert_eq!(a, expected.as_slice().to_vec(), "{substeps} x {dt}");
            let n = f64::from(substeps);
            assert!((a[0] - 0.01 * n / env_dt).abs() < 1e-9);
            assert!((a[1] + 0.02 * n / env_dt).abs() < 1e-9);
            assert!((a[2] - 0.03 * n / env_dt).abs() < 1e-9);
            v_prev = v;
        }
    }
}
