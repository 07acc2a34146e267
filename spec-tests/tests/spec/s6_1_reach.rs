//! Spec §6.1 (Reach goal) and §4.4: the goal is reached when the
//! trunk centre lies in the cube of side ε_reach (`accepted_error`) centred on the goal,
//! |C_i − G_i| ≤ ε_reach / 2 on each of x, y, z; the episode ends (`reached`, terminated) and
//! r_reach = `reach_target_bonus_reward` is added on that step *before* the §5.1 multipliers.
//!
//! Invariant, on every backend: with ε_reach = 0.1 m and a goal 4 cm ahead and 4 cm to the side
//! of the spawn point (inside the cube although 5.7 cm away, farther than ε_reach / 2: a cube,
//! not a sphere), HyQ standing reaches it on its first step; the bonus is paid once, multiplied
//! by m_yaw = cos yaw < 1 (the spawn is yawed 10°), so the reward is (r_e + bonus) · m_yaw ·
//! m_pitch; a goal 6 cm ahead (outside the cube on x) is not reached while HyQ stands.

use hyq_env::{EnvError, Reason, ResetOptions};
use spec_tests::{env, stand_action, step};

spec_tests::for_each_backend! {
    #[test]
    fn a_goal_within_the_reach_cube_ends_with_reached_and_the_multiplied_bonus() {
        const BONUS: f64 = 10.0;
        let mut env = env::<Engine>(&[
            ("task.accepted_error", "0.1"),
            ("task.reach_target_bonus_reward", "10"),
            ("reset.yaw_deg", "10"),
        ]);
        let spawn = env.model().spawn_state().trunk.pose.translation.vector;
        let goal = [spawn.x + 0.04, spawn.y + 0.04, spawn.z];
        env.reset(Some(0), &ResetOptions { goal: Some(goal), state: None })
            .unwrap_or_else(|e| panic!("{e}"));
        let k = env.info().distance_to_goal;
        assert!(k > 0.05, "the goal is outside the ball of radius ε_reach / 2 ({k} m)");
        let action = stand_action(&env);
        let r = step(&mut env, &action);
        assert_eq!(r.t, 1);
        assert_eq!(r.reasons, [Reason::Reached]);
        assert!(r.terminated && !r.truncated);
        let t = &r.terms.values;
        assert_eq!(t.r_reach, BONUS);
        assert!(t.m_yaw < 0.99, "yawed 10°: m_yaw {}", t.m_yaw);
        assert_eq!(r.reward, (t.r_b + t.r_n + t.r_e + BONUS) * t.m_yaw * t.m_pitch);
        assert!(r.reward < t.r_e + BONUS, "the multiplier applies to the bonus too");
        assert!(matches!(env.step(&action), Err(EnvError::EpisodeOver { .. })));
    }

    #[test]
    fn a_goal_outside_the_reach_cube_is_not_reached() {
        let mut env = env::<Engine>(&[("task.accepted_error", "0.1"), ("task.reach_target_bonus_reward", "10")]);
        let spawn = env.model().spawn_state().trunk.pose.translation.vector;
        let goal = [spawn.x + 0.06, spawn.y, spawn.z];
        env.reset(Some(0), &ResetOptions { goal: Some(goal), state: None })
            .unwrap_or_else(|e| panic!("{e}"));
        let action = stand_action(&env);
        for _ in 0..50 {
            let r = step(&mut env, &action);
            assert!(r.reasons.is_empty(), "t = {}: {:?}", r.t, r.reasons);
            assert_eq!(r.terms.values.r_reach, 0.0);
        }
    }
}
