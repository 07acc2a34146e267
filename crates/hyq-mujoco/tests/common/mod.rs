//! Helpers shared by this crate's integration tests (not a test of its own).

// Each test binary uses a different subset of these helpers.
#![allow(dead_code)]

use hyq_mujoco::{MujocoBackend, MujocoOptions};
use hyq_physics::{Actuator, Backend, PdScratch, PhysicsParams, bundled, pd_substep};

/// A small deterministic generator (xorshift64*), so that the tests need no dependency.
pub struct Rng(u64);

impl Rng {
    /// A generator for `seed` (any value, zero included).
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A MuJoCo world with the bundled HyQ at its spawn state.
pub fn hyq() -> MujocoBackend {
    MujocoBackend::build(
        bundled::hyq(),
        &PhysicsParams::default(),
        &MujocoOptions::default(),
    )
    .expect("the bundled HyQ builds on MuJoCo")
}

/// Runs `steps` PD sub-steps towards random joint targets (redrawn every 10 sub-steps, uniform
/// within the joint limits) and returns the bit patterns of everything the backend reports
/// after every sub-step: joint angles and speeds, trunk pose and velocities, contact flags.
pub fn random_trajectory(b: &mut MujocoBackend, seed: u64, steps: usize) -> Vec<u64> {
    random_trajectory_from(b, seed, 0, steps)
}

/// Sub-steps `skip .. skip + steps` of [`random_trajectory`]`(b, seed, skip + steps)`, for a
/// world that already ran the first `skip` of them.
pub fn random_trajectory_from(
    b: &mut MujocoBackend,
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
            for (t, j) in targets.iter_mut().zip(model.joints()) {
                *t = j.lower + rng.unit() * (j.upper - j.lower);
            }
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

/// Index of the first value where two traces differ (or where one ends early).
pub fn first_difference(a: &[u64], b: &[u64]) -> Option<usize> {
    a.iter()
        .zip(b)
        .position(|(x, y)| x != y)
        .or_else(|| (a.len() != b.len()).then(|| a.len().min(b.len())))
}
