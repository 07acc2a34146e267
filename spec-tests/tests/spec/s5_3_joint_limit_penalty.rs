//! Spec §5.3 (Reach joint limits) and §6.2 (a **deviation**: the
//! printed test is false for every negative range): a joint is at its limit when
//! θ ≤ θ_min + ε_joint or θ ≥ θ_max − ε_joint; the episode then ends (`joint_limit`,
//! terminated) and `reach_bounds_penalty` is subtracted after the multipliers, on that step
//! only.
//!
//! Invariant, on every backend: HyQ standing with one joint's target at one of its limits (each
//! of the 12 joints, each limit) ends the episode within 1 s with `joint_limit` naming that
//! joint, terminated and not truncated; the penalty is subtracted on the last step and on no
//! other, so the episode's joint penalties sum to it once; the step after is an error.

use hyq_env::{EnvError, Reason};
use hyq_spec::LimitSide;
use spec_tests::{env, reset, run_action, stand_action};

spec_tests::for_each_backend! {
    #[test]
    fn a_joint_commanded_into_its_limit_ends_the_episode_with_the_penalty_once() {
        const PENALTY: f64 = 2.5;
        let mut env = env::<Engine>(&[("task.reach_bounds_penalty", "2.5")]);
        let eps = env.config().task.accepted_dist_to_bounds;
        let joints = env.model().joints().to_vec();
        for (j, joint) in joints.iter().enumerate() {
            for (side, normalized) in [(LimitSide::Lower, -1.0), (LimitSide::Upper, 1.0)] {
                reset(&mut env, 0);
                let mut action = stand_action(&env);
                action[j] = normalized;
                let records = run_action(&mut env, &action, 100);
                let what = format!("{} to its {side:?} limit", joint.name);
                let last = records.last().unwrap_or_else(|| unreachable!("one step at least"));
                assert_eq!(last.reasons, [Reason::JointLimit], "{what}: ended with {:?} at t = {}", last.reasons, last.t);
                assert!(last.terminated && !last.truncated, "{what}");
                let hit = env.info().joint_at_limit.unwrap_or_else(|| panic!("{what}: no joint named"));
                assert_eq!((hit.joint, hit.side), (j, side), "{what}");
                let angle = env.joint_angles()[j];
                match side {
                    LimitSide::Lower => assert!(angle <= joint.lower + eps, "{what}: {angle}"),
                    LimitSide::Upper => assert!(angle >= joint.upper - eps, "{what}: {angle}"),
                }
                let t = &last.terms.values;
                assert_eq!(t.joint_penalty, PENALTY, "{what}");
                assert_eq!(t.fall_penalty, 0.0, "{what}");
                assert_eq!(
                    last.reward,
                    (t.r_b + t.r_n + t.r_e + t.r_reach) * t.m_yaw * t.m_pitch - PENALTY,
                    "{what}"
                );
                for r in &records[..records.len() - 1] {
                    assert_eq!(r.terms.values.joint_penalty, 0.0, "{what}: penalised at t = {}", r.t);
                }
                let total: f64 = records.iter().map(|r| r.terms.values.joint_penalty).sum();
                assert_eq!(total, PENALTY, "{what}: penalised once");
                assert!(matches!(env.step(&action), Err(EnvError::EpisodeOver { .. })), "{what}");
            }
        }
    }
}
