//! Spec §3 (Observations): 39 values in the table's order and units, not
//! clipped. Rows 24–28 are 1 when that body touched the ground in any sub-step of the step;
//! 29–32 the trunk quaternion (w, x, y, z, world); 33–35 the trunk's coordinate acceleration
//! (v^t − v^{t−1}) / Δt_env, 0 at rest and after reset, gravity not included; 36–38 the trunk
//! position C^t.
//!
//! Invariant, on every backend: the rows are the spec table's, in its order; after reset the
//! acceleration is exactly 0 and the position is C^0; HyQ standing still reads contact flags
//! (1, 1, 1, 1, 0), a quaternion close to identity, an acceleration close to 0, and exactly the
//! trunk position and joint angles the engine reports; while it trots, rows 33–35 are exactly
//! (v^t − v^{t−1}) / Δt_env of the trunk velocity the engine reports.

use hyq_env::{Policy, Trot, TrotParams};
use hyq_spec::SPEC_TABLE;
use hyq_spec::observation::trunk_acceleration;
use spec_tests::{env, position, reset, stand_action, step};

spec_tests::for_each_backend! {
    #[test]
    fn rows_are_the_spec_table_in_its_order() {
        let env = env::<Engine>(&[]);
        let rows = env.observation_layout().rows();
        assert_eq!(rows.len(), 39);
        for (row, spec) in rows.iter().zip(SPEC_TABLE.iter()) {
            assert_eq!((row.index, &row.name), (spec.index, &spec.name));
            // The joint rows' bounds are the URDF's limits, which the spec prints to six
            // significant digits.
            assert!((row.min - spec.min).abs() < 1e-5 && (row.max - spec.max).abs() < 1e-5, "{}: [{}, {}] vs the table's [{}, {}]", row.name, row.min, row.max, spec.min, spec.max);
            assert_eq!(row.estimated, spec.estimated, "{}", row.name);
        }
    }

    #[test]
    fn after_reset_acceleration_is_zero_and_position_is_the_initial_position() {
        let mut env = env::<Engine>(&[]);
        reset(&mut env, 0);
        let layout = env.observation_layout().clone();
        let obs = env.observation().to_vec();
        assert_eq!(&obs[layout.trunk_acceleration()], &[0.0, 0.0, 0.0]);
        let c0 = env.info().initial_position;
        assert_eq!(position(&layout, &obs).coords.as_slice(), &c0);
        let t = env.trunk().pose.translation.vector;
        assert_eq!([t.x, t.y, t.z], c0);
        assert_eq!(&obs[layout.joint_angles()], env.joint_angles());
    }

    #[test]
    fn values_while_standing() {
        let mut env = env::<Engine>(&[]);
        reset(&mut env, 0);
        let layout = env.observation_layout().clone();
        let model = env.model().clone();
        let action = stand_action(&env);
        // One simulated second to settle from the spawn height onto the feet.
        for _ in 0..100 {
            step(&mut env, &action);
        }
        let record = step(&mut env, &action);
        let obs = &record.obs;
        assert_eq!(obs.len(), 39);

        let mut flags: Vec<f64> = obs[layout.foot_contacts()].to_vec();
        flags.push(obs[layout.trunk_contact()]);
        assert_eq!(flags, [1.0, 1.0, 1.0, 1.0, 0.0], "feet lf, lh, rf, rh, then the trunk");

        // Level to within about 1°: |q − identity| < 0.01 per component.
        let q = &obs[layout.trunk_rotation()];
        assert!((q[0] - 1.0).abs() < 1e-3 && q[1..].iter().all(|v| v.abs() < 0.01), "quaternion {q:?}");

        // At rest: the velocity changes by less than 1 mm/s over the 10 ms step.
        let a = &obs[layout.trunk_acceleration()];
        assert!(a.iter().all(|v| v.abs() < 0.1), "acceleration {a:?} m/s²");

        // Rows 36–38 are the trunk frame's position the engine reports, to the bit, at the
        // standing height (within 1 cm: engines settle a few mm apart).
        let t = env.trunk().pose.translation.vector;
        let c = position(&layout, obs);
        assert_eq!([c.x, c.y, c.z], [t.x, t.y, t.z]);
        assert!((c.z - model.standing_height()).abs() < 0.01, "trunk at {} m", c.z);
        assert!(c.x.abs() < 0.01 && c.y.abs() < 0.01, "drifted to ({}, {})", c.x, c.y);

        // Joint rows are the engine's joint angles, near the standing pose and still.
        assert_eq!(&obs[layout.joint_angles()], env.joint_angles());
        for (q, q0) in obs[layout.joint_angles()].iter().zip(model.standing_pose()) {
            assert!((q - q0).abs() < 0.06, "joint at {q}, standing {q0}");
        }
        assert!(obs[layout.joint_speeds()].iter().all(|v| v.abs() < 0.05));

        // The f32 observation is the f64 one rounded.
        let f32s: Vec<f32> = obs.iter().map(|v| *v as f32).collect();
        assert_eq!(env.observation_f32(), f32s.as_slice());
    }

    #[test]
    fn acceleration_is_the_trunk_velocity_change_over_the_env_step() {
        let mut env = env::<Engine>(&[]);
        reset(&mut env, 0);
        let layout = env.observation_layout().clone();
        let mut trot = Trot::new(env.model(), TrotParams::default()).unwrap_or_else(|e| panic!("{e}"));
        let mut action = vec![0.0; 12];
        let mut largest: f64 = 0.0;
        for _ in 0..150 {
            let v0 = env.trunk().linvel;
            trot.act(&env.policy_input(), &mut action);
            let record = step(&mut env, &action);
            let v1 = env.trunk().linvel;
            let expected = trunk_acceleration(&v0, &v1, env.env_dt()).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(&record.obs[layout.trunk_acceleration()], expected.as_slice());
            largest = largest.max(expected.norm());
        }
        assert!(largest > 1.0, "a trot accelerates the trunk (largest {largest} m/s²)");
    }
}
