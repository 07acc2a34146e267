//! Helpers shared by this crate's integration tests (not a test of its own).

// Each test binary uses a different subset of these helpers.
#![allow(dead_code)]

use hyq_dart::{DartBackend, DartOptions};
use hyq_physics::conformance::fixtures::Rng;
use hyq_physics::{Actuator, Backend, PdScratch, PhysicsParams, bundled, pd_substep};

/// A DART world with the bundled HyQ at its spawn state.
pub fn hyq() -> DartBackend {
    DartBackend::build(
        bundled::hyq(),
        &PhysicsParams::default(),
        &DartOptions::default(),
    )
    .expect("the bundled HyQ builds on DART")
}

/// Runs `steps` PD sub-steps towards random joint targets (redrawn every 10 sub-steps, uniform
/// within the joint limits) and returns the bit patterns of everything the backend reports
/// after every sub-step: joint angles and speeds, trunk pose and velocities, contact flags.
pub fn random_trajectory(b: &mut DartBackend, seed: u64, steps: usize) -> Vec<u64> {
    random_trajectory_from(b, seed, 0, steps)
}

/// Sub-steps `skip .. skip + steps` of [`random_trajectory`]`(b, seed, skip + steps)`, for a
/// world that already ran the first `skip` of them.
pub fn random_trajectory_from(
    b: &mut DartBackend,
    seed: u64,
    skip: usize,
    steps: usize,
) -> Vec<u64> {
    let model = b.model().clone();
    let n = model.num_joints();
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(n);
    let mut rng = Rng::new(seed);
    let mut targets = model.standing_pose().to_vec();
    let mut contacts = vec![false; model.tracked().len()];
    let mut state = b.state();
    let mut out = Vec::with_capacity(steps * (2 * n + 13 + contacts.len()));
    for k in 0..skip + steps {
        if k.is_multiple_of(10) {
            rng.fill_joint_angles(&model, 0.0, &mut targets);
        }
        if k < skip {
            continue;
        }
        pd_substep(b, &act, &targets, &mut scratch).expect("a random-target step stays finite");
        b.read_state(&mut state);
        b.contacts(&mut contacts);
        let t = &state.trunk;
        out.extend(state.q.iter().chain(&state.qd).map(|v| v.to_bits()));
        out.extend(t.pose.translation.vector.iter().map(|v| v.to_bits()));
        out.extend(t.pose.rotation.coords.iter().map(|v| v.to_bits()));
        out.extend(t.linvel.iter().chain(t.angvel.iter()).map(|v| v.to_bits()));
        out.extend(contacts.iter().map(|&c| u64::from(c)));
    }
    out
}

pub use hyq_physics::conformance::fixtures::first_difference;
