//! Spec §6.4 (Timeout): the episode times out when t ≥ t_max
//! (`max_time_steps`), t the env steps since reset (1 after the first), so t_max = 1 ends it
//! after its first step and "there will be no second step". In Gymnasium terms timeout is
//! `truncated` and the other conditions `terminated` (which wins when both hold); a step after
//! the end, without reset, is an error.
//!
//! Invariant: on every backend, t_max = 1 truncates after exactly one step and t_max = N after
//! exactly N, reasons = [timeout], no reward or penalty for it; the next step is an error that
//! changes nothing; after a reset the episode runs again. On the scripted backend (where the
//! coincidence can be staged), a fall on the timeout step is terminated, not truncated, with
//! both reasons.

use hyq_env::testing::ScriptedBackend;
use hyq_env::{EnvError, Reason, ResetOptions};
use spec_tests::{env, reset, stand_action, step};

spec_tests::for_each_backend! {
    #[test]
    fn max_time_steps_n_truncates_after_exactly_n_steps() {
        for n in [1u64, 7] {
            let mut env = env::<Engine>(&[("task.max_time_steps", &n.to_string())]);
            reset(&mut env, 0);
            let action = stand_action(&env);
            for t in 1..=n {
                let r = step(&mut env, &action);
                assert_eq!(r.t, t);
                assert!(!r.terminated, "t_max {n}, t {t}");
                assert_eq!(r.truncated, t == n, "t_max {n}, t {t}");
                if t == n {
                    assert_eq!(r.reasons, [Reason::Timeout]);
                    assert_eq!((r.terms.values.joint_penalty, r.terms.values.fall_penalty, r.terms.values.r_reach), (0.0, 0.0, 0.0));
                } else {
                    assert!(r.reasons.is_empty());
                }
            }
            let obs = env.observation().to_vec();
            match env.step(&action) {
                Err(EnvError::EpisodeOver { t, reasons, .. }) => {
                    assert_eq!(t, n);
                    assert!(reasons.contains(Reason::Timeout));
                }
                other => panic!("a step after the end must be an error, got {other:?}"),
            }
            assert_eq!(env.observation(), obs.as_slice(), "the refused step changed nothing");
            env.reset(None, &ResetOptions::default()).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(step(&mut env, &action).t, 1);
        }
    }
}

#[test]
fn a_fall_on_the_timeout_step_is_terminated_not_truncated_scripted() {
    let mut env =
        env::<ScriptedBackend>(&[("task.max_time_steps", "3"), ("task.fall_penalty", "1")]);
    reset(&mut env, 0);
    let trunk = env.model().trunk_tracked_index();
    // Sub-steps 21–30 are step 3, the timeout step.
    env.backend_mut().set_script(move |w| {
        w.contacts[trunk] = w.substep == 25;
        Ok(())
    });
    let zero = [0.0; 12];
    for _ in 0..2 {
        assert!(step(&mut env, &zero).reasons.is_empty());
    }
    let r = step(&mut env, &zero);
    assert_eq!(r.reasons, [Reason::Fell, Reason::Timeout]);
    assert!(r.terminated && !r.truncated);
    assert_eq!(r.terms.values.fall_penalty, 1.0);
}
