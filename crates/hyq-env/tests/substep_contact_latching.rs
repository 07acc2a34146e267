//! Invariant (spec §3, §6.3): a contact flag reads 1 when its body touched the ground in
//! any physics sub-step of the env step, not only the last; the trunk's latched flag is the fall
//! fact, so a trunk contact in a middle sub-step alone ends the episode with `fell` and its
//! penalty, and flags do not carry over to the next step.

mod common;

use common::{reset, scripted};
use hyq_env::Reason;

#[test]
fn a_trunk_contact_in_one_middle_substep_is_a_fall() {
    let mut env = scripted(&[("task.fall_penalty", "2.5")]);
    reset(&mut env, 0);
    let trunk = env.model().trunk_tracked_index();
    // Sub-steps are counted from the reset: step 2 runs sub-steps 11..=20; touch in 15 only.
    env.backend_mut().set_script(move |w| {
        w.contacts[trunk] = w.substep == 15;
        Ok(())
    });
    let layout = env.observation_layout().clone();
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.observation[layout.trunk_contact()], 0.0);
    assert!(!s.terminated);
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.observation[layout.trunk_contact()], 1.0);
    assert!(s.terminated && !s.truncated);
    assert!(s.info.reasons.contains(Reason::Fell));
    assert_eq!(s.info.reward.fall_penalty, 2.5);
    assert_eq!(env.backend().substeps(), 20);
}

#[test]
fn foot_flags_latch_over_the_substeps_and_reset_each_step() {
    let mut env = scripted(&[("control.sim_steps_per_env_step", "4")]);
    reset(&mut env, 0);
    env.backend_mut().options_mut().feet_touch = false;
    // Foot 1 touches only in the first sub-step of step 1; foot 3 only in the last sub-step of
    // step 2; nothing in step 3.
    env.backend_mut().set_script(|w| {
        w.contacts[1] = w.substep == 1;
        w.contacts[3] = w.substep == 8;
        Ok(())
    });
    let feet = env.observation_layout().foot_contacts();
    let mut flags = Vec::new();
    for _ in 0..3 {
        let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
        flags.push(s.observation[feet.clone()].to_vec());
    }
    assert_eq!(flags[0], [0.0, 1.0, 0.0, 0.0]);
    assert_eq!(flags[1], [0.0, 0.0, 0.0, 1.0]);
    assert_eq!(flags[2], [0.0, 0.0, 0.0, 0.0]);
}

#[test]
fn standing_feet_read_one_and_no_fall_without_trunk_contact() {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    let layout = env.observation_layout().clone();
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(&s.observation[layout.foot_contacts()], &[1.0; 4]);
    assert_eq!(s.observation[layout.trunk_contact()], 0.0);
    assert!(!s.info.reasons.contains(Reason::Fell));
}
