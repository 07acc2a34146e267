//! Spec §5.1 (Orientation penalty): the rewards of a step are multiplied by
//! m_yaw = 1 if |yaw| ≤ yaw_limit (2.5°), else max(0, cos yaw), and by m_pitch likewise with
//! the pitch; yaw and pitch are the intrinsic Z-Y-X angles of the trunk quaternion (spec §1).
//!
//! Invariant, on every backend: HyQ spawned standing yawed by ±10° gets m_yaw = cos 10° on its
//! first step (cos of the yaw it reports, to the bit; within 1e-4 of cos 10°, since the trunk
//! turns by less than 0.1° in 10 ms) and m_pitch = 1, and the reward is the rewards times the
//! multipliers; a yaw within the limit costs nothing; a trunk pitched nose-down by 10° gets
//! m_pitch = cos 10° and m_yaw = 1.

use hyq_env::ResetOptions;
use hyq_physics::na::UnitQuaternion;
use spec_tests::{env, reset, stand_action, step};

spec_tests::for_each_backend! {
    #[test]
    fn a_spawn_yawed_10_degrees_multiplies_the_reward_by_cos_10_degrees() {
        for yaw_deg in ["10", "-10"] {
            let mut env = env::<Engine>(&[("reset.yaw_deg", yaw_deg), ("task.norm_rew_scaling", "10")]);
            reset(&mut env, 0);
            let yaw0: f64 = yaw_deg.parse::<f64>().unwrap_or_else(|e| panic!("{e}")).to_radians();
            assert!((env.info().yaw - yaw0).abs() < 1e-6, "spawned at yaw {}", env.info().yaw);
            let action = stand_action(&env);
            let r = step(&mut env, &action);
            let t = &r.terms.values;
            assert!((r.yaw - yaw0).abs() < 0.1f64.to_radians(), "yaw {} after one step", r.yaw);
            assert_eq!(t.m_yaw, r.yaw.cos());
            assert!((t.m_yaw - 10f64.to_radians().cos()).abs() < 1e-4, "m_yaw {}", t.m_yaw);
            assert!(r.pitch.abs() < 2.5f64.to_radians());
            assert_eq!(t.m_pitch, 1.0);
            assert!(t.r_n != 0.0 && t.r_e != 0.0, "the step moved the trunk: {t:?}");
            assert_eq!(r.reward, (t.r_b + t.r_n + t.r_e + t.r_reach) * t.m_yaw * t.m_pitch);
        }
    }

    #[test]
    fn a_yaw_within_the_limit_costs_nothing_and_past_it_costs_its_cosine() {
        for (yaw_deg, penalised) in [("2", false), ("-2", false), ("4", true)] {
            let mut env = env::<Engine>(&[("reset.yaw_deg", yaw_deg)]);
            reset(&mut env, 0);
            let action = stand_action(&env);
            let r = step(&mut env, &action);
            if penalised {
                assert_eq!(r.terms.values.m_yaw, r.yaw.cos());
                assert!(r.terms.values.m_yaw < 1.0);
            } else {
                assert_eq!(r.terms.values.m_yaw, 1.0, "yaw {} within 2.5 degrees", r.yaw.to_degrees());
            }
        }
    }

    #[test]
    fn a_trunk_pitched_10_degrees_multiplies_the_reward_by_cos_10_degrees() {
        let mut env = env::<Engine>(&[("task.norm_rew_scaling", "10")]);
        let model = env.model().clone();
        let mut state = model.spawn_state();
        // Nose down by 10°, raised 15 cm so that no foot starts in the ground.
        let pitch0 = 10f64.to_radians();
        state.trunk.pose.rotation = UnitQuaternion::from_euler_angles(0.0, pitch0, 0.0);
        state.trunk.pose.translation.z += 0.15;
        env.reset(Some(0), &ResetOptions { state: Some(state), goal: None })
            .unwrap_or_else(|e| panic!("{e}"));
        assert!((env.info().pitch - pitch0).abs() < 1e-9);
        let action = stand_action(&env);
        let r = step(&mut env, &action);
        let t = &r.terms.values;
        assert!((r.pitch - pitch0).abs() < 0.5f64.to_radians(), "pitch {} after one step", r.pitch);
        assert_eq!(t.m_pitch, r.pitch.cos());
        assert!((t.m_pitch - pitch0.cos()).abs() < 2e-3, "m_pitch {}", t.m_pitch);
        assert_eq!(t.m_yaw, 1.0);
        assert_eq!(r.reward, (t.r_b + t.r_n + t.r_e + t.r_reach) * t.m_yaw * t.m_pitch);
    }
}
