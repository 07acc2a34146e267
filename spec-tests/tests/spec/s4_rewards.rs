//! Spec §4 (Reward), eqs. (1)–(5), and §5:
//!
//! r = (r_b + r_n + r_e + r_reach) · m_yaw · m_pitch − joint_penalty − fall_penalty, with
//! r_b = k_base (D^{t−1} − D^t), r_n = k_norm (D^{t−1} − D^t) / K, r_e = R_e(D_n^t) − R_e(D_n^{t−1})
//! and R_e the continuous curve: (e^{k(1−D_n)} − 1)/k on [0, 1], 5 (1 − D_n) on (1, 9],
//! −40 + 0.5 (9 − D_n) beyond; D^t = ‖G − C^t‖, K = ‖G − C^0‖, D_n = D / K.
//!
//! Invariant, on every backend, over a trot with every reward term on: each step's recorded
//! reward and terms (as read back from the JSONL record) are, to the bit, hyq-spec's composition
//! evaluated on the recorded positions, orientation, joint angles and trunk flag (C^{t−1} from
//! the previous record, C^0 from the record's `initial_position`, which is the reset
//! observation's position); they also match the formulas above written out independently here
//! (to 1e-12); and over the episode Σ r_n = k_norm (1 − D_n^T), Σ r_e = R_e(D_n^T) and
//! Σ r_b = k_base (D^0 − D^T) (telescoping, to summation rounding).

use hyq_env::{Reason, Trot, TrotParams};
use hyq_physics::na::Point3;
use hyq_spec::{EpisodeRules, StepSnapshot, Termination};
use spec_tests::{env, orientation, position, reset, run_policy};

/// R_e as spec §4.3 rules it, written out independently of hyq-spec.
fn cumulative_exponential(d_n: f64, k: f64) -> f64 {
    if d_n <= 1.0 {
        ((k * (1.0 - d_n)).exp() - 1.0) / k
    } else if d_n <= 9.0 {
        5.0 * (1.0 - d_n)
    } else {
        -40.0 + 0.5 * (9.0 - d_n)
    }
}

fn close(what: &str, got: f64, want: f64, tol: f64) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: {got} vs {want} (tolerance {tol})"
    );
}

spec_tests::for_each_backend! {
    #[test]
    fn trot_rewards_are_the_spec_composition_of_the_recorded_positions() {
        const K_BASE: f64 = 2.0;
        const K_NORM: f64 = 10.0;
        const K_EXP: f64 = 5.0;
        let mut env = env::<Engine>(&[
            ("task.base_rew_scaling", "2"),
            ("task.norm_rew_scaling", "10"),
            ("task.exp_rew_scaling", "5"),
            ("task.max_time_steps", "300"),
        ]);
        reset(&mut env, 0);
        let task = env.config().task;
        let layout = env.observation_layout().clone();
        let ranges = env.robot().joint_ranges().to_vec();
        let c0 = Point3::from(env.info().initial_position);
        let goal = Point3::from(env.info().goal);
        // C^0 is the reset observation's position, so a record holds all a recomputation needs.
        assert_eq!(position(&layout, env.observation()), c0);

        let mut trot = Trot::new(env.model(), TrotParams::default()).unwrap_or_else(|e| panic!("{e}"));
        let records = run_policy(&mut env, &mut trot, 300);
        assert_eq!(records.len(), 300, "the trot walks 3 s without an episode end");

        let rules = EpisodeRules::new(&task, c0, goal).unwrap_or_else(|e| panic!("{e}"));
        let k = (goal - c0).norm();
        let mut previous = c0;
        let (mut sum_b, mut sum_n, mut sum_e, mut ret) = (0.0, 0.0, 0.0, 0.0);
        for r in &records {
            assert_eq!(Point3::from(r.initial_position), c0);
            assert_eq!(Point3::from(r.goal), goal);
            let c = position(&layout, &r.obs);
            let outcome = rules
                .evaluate_step(&StepSnapshot {
                    step: r.t,
                    previous_position: previous,
                    position: c,
                    orientation: orientation(&layout, &r.obs),
                    joint_angles: &r.obs[layout.joint_angles()],
                    joint_ranges: &ranges,
                    trunk_contact: r.obs[layout.trunk_contact()] == 1.0,
                })
                .unwrap_or_else(|e| panic!("{e}"));
            let b = outcome.reward;
            let t = &r.terms.values;
            assert_eq!(
                [t.r_b, t.r_n, t.r_e, t.r_reach, t.m_yaw, t.m_pitch, t.joint_penalty, t.fall_penalty, r.reward],
                [b.r_b, b.r_n, b.r_e, b.r_reach, b.m_yaw, b.m_pitch, b.joint_penalty, b.fall_penalty, b.total],
                "step {}",
                r.t
            );
            assert_eq!(r.terms.get("m_height"), None, "the height penalty is off by default");
            assert_eq!(r.reward, (t.r_b + t.r_n + t.r_e + t.r_reach) * t.m_yaw * t.m_pitch - t.joint_penalty - t.fall_penalty);
            assert_eq!(r.distance_to_goal, outcome.distance);
            assert_eq!(Some(r.d_n), outcome.normalised_distance);
            assert_eq!((r.yaw, r.pitch), (outcome.attitude.yaw, outcome.attitude.pitch));
            let spec_reasons: Vec<Reason> = outcome.terminations.iter().map(Reason::from).collect();
            assert_eq!(r.reasons, spec_reasons);
            assert_eq!(outcome.terminations.contains(Termination::Timeout), r.t == 300);

            // The formulas, written out here.
            let (d_prev, d) = ((goal - previous).norm(), (goal - c).norm());
            close("r_b", t.r_b, K_BASE * (d_prev - d), 1e-12);
            close("r_n", t.r_n, K_NORM * (d_prev - d) / k, 1e-12);
            close(
                "r_e",
                t.r_e,
                cumulative_exponential(d / k, K_EXP) - cumulative_exponential(d_prev / k, K_EXP),
                1e-12,
            );
            sum_b += t.r_b;
            sum_n += t.r_n;
            sum_e += t.r_e;
            ret += r.reward;
            previous = c;
        }
        let last = records.last().unwrap_or_else(|| unreachable!("300 records"));
        let d_end = last.distance_to_goal;
        assert!(d_end < k - 0.3, "the trot got closer to the goal: {k} m -> {d_end} m");
        close("Σ r_b", sum_b, K_BASE * (k - d_end), 1e-10);
        close("Σ r_n", sum_n, K_NORM * (1.0 - d_end / k), 1e-10);
        close("Σ r_e", sum_e, cumulative_exponential(d_end / k, K_EXP), 1e-10);
        assert!(ret > 0.0, "walking towards the goal earns a positive return ({ret})");
    }
}
