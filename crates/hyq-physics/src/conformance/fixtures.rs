//! Shared fixtures of the conformance suite, also used by the backends' own tests and benches:
//! building worlds, a seeded random stream, reading a backend's state, stepping it, and
//! recording trajectories bit for bit. Every helper panics with the backend's name on failure
//! (they are for tests and benches, where a failure is the report).

use std::path::Path;
use std::sync::Arc;

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::actuator::{Actuator, PdScratch, pd_substep};
use crate::backend::{Backend, PhysicsParams, RobotState};
use crate::bundled;
use crate::model::RobotModel;
use crate::profile::Profile;

/// The robot a conformance test runs on: its model, and the URDF text and profile it was
/// built from (the tests that check the model against the URDF read them independently).
#[derive(Debug, Clone)]
pub struct Robot {
    /// The model every backend builds.
    pub model: Arc<RobotModel>,
    /// The URDF text the model was built from.
    pub urdf: String,
    /// The profile the model was built from.
    pub profile: Profile,
}

impl Robot {
    /// A bundled robot ([`bundled::NAMES`]); panics on an unknown name (a test's mistake).
    pub fn bundled(name: &str) -> Self {
        let sources =
            bundled::sources(name).unwrap_or_else(|| panic!("no bundled robot named {name:?}"));
        let model = bundled::by_name(name).unwrap_or_else(|| panic!("{name} is bundled"));
        let profile = Profile::from_toml_str(sources.profile, name)
            .unwrap_or_else(|e| panic!("bundled profile of {name}: {e}"));
        Self {
            model,
            urdf: sources.urdf.to_owned(),
            profile,
        }
    }

    /// The robot of a profile file (its URDF path is relative to the profile); panics if it
    /// cannot be loaded, with the loader's error.
    pub fn from_profile(path: impl AsRef<Path>) -> Self {
        let path = path.as_ref();
        let read = |p: &Path| {
            std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
        };
        let profile = Profile::from_toml_str(&read(path), &path.display().to_string())
            .unwrap_or_else(|e| panic!("{e}"));
        let urdf = read(
            &path
                .parent()
                .unwrap_or_else(|| Path::new("."))
                .join(&profile.urdf),
        );
        let model = RobotModel::load(path).unwrap_or_else(|e| panic!("{e}"));
        Self {
            model: Arc::new(model),
            urdf,
            profile,
        }
    }
}

/// `robot` on backend `B` with `params` and `options`.
pub fn build<B: Backend>(robot: &Robot, params: &PhysicsParams, options: &B::Options) -> B {
    B::build(Arc::clone(&robot.model), params, options).unwrap_or_else(|e| {
        panic!(
            "{} backend failed to build {}: {e}",
            B::NAME,
            robot.model.name()
        )
    })
}

/// [`build`] with the default physics parameters.
pub fn build_default<B: Backend>(robot: &Robot, options: &B::Options) -> B {
    build(robot, &PhysicsParams::default(), options)
}

/// The default physics parameters without gravity.
pub fn zero_gravity() -> PhysicsParams {
    PhysicsParams {
        gravity: [0.0; 3],
        ..PhysicsParams::default()
    }
}

/// A seeded random stream (ChaCha8, portable): every run, machine and backend sees the same
/// numbers for the same seed.
pub struct Rng(ChaCha8Rng);

impl Rng {
    /// The stream for `seed` (any value).
    pub fn new(seed: u64) -> Self {
        Self(ChaCha8Rng::seed_from_u64(seed))
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0.random::<f64>()
    }

    /// Uniform in [lo, hi) (`lo` itself when the interval is empty).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Joint angles uniformly inside the limits, `margin` (rad) away from them.
    pub fn joint_angles(&mut self, model: &RobotModel, margin: f64) -> Vec<f64> {
        let mut q = vec![0.0; model.num_joints()];
        self.fill_joint_angles(model, margin, &mut q);
        q
    }

    /// [`Rng::joint_angles`] into `out` (one value per joint), allocating nothing.
    pub fn fill_joint_angles(&mut self, model: &RobotModel, margin: f64, out: &mut [f64]) {
        for (o, j) in out.iter_mut().zip(model.joints()) {
            *o = self.range(j.lower + margin, j.upper - margin);
        }
    }

    /// A random orientation (roll and yaw within ±3 rad, pitch within ±1.4 rad).
    pub fn rotation(&mut self) -> UnitQuaternion<f64> {
        UnitQuaternion::from_euler_angles(
            self.range(-3.0, 3.0),
            self.range(-1.4, 1.4),
            self.range(-3.0, 3.0),
        )
    }

    /// A vector with each component uniform in ±`scale`.
    pub fn vector(&mut self, scale: f64) -> Vector3<f64> {
        Vector3::new(
            self.range(-scale, scale),
            self.range(-scale, scale),
            self.range(-scale, scale),
        )
    }
}

/// The backend's joint angles (rad, profile order).
pub fn read_q<B: Backend>(b: &B) -> Vec<f64> {
    let mut q = vec![0.0; b.model().num_joints()];
    b.joint_positions(&mut q);
    q
}

/// The backend's joint speeds (rad/s, profile order).
pub fn read_qd<B: Backend>(b: &B) -> Vec<f64> {
    let mut qd = vec![0.0; b.model().num_joints()];
    b.joint_velocities(&mut qd);
    qd
}

/// The backend's contact flags (tracked order: feet, then the trunk).
pub fn read_contacts<B: Backend>(b: &B) -> Vec<bool> {
    let mut c = vec![false; b.model().tracked().len()];
    b.contacts(&mut c);
    c
}

/// Body poses recomputed by the shared forward kinematics from the backend's trunk pose and
/// joint angles.
pub fn fk_poses<B: Backend>(b: &B) -> Vec<Isometry3<f64>> {
    let model = b.model();
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    model
        .link_poses(&b.trunk().pose, &read_q(b), &mut poses)
        .expect("forward kinematics of the backend's own state");
    poses
}

/// Body poses as the engine holds them.
pub fn engine_poses<B: Backend>(b: &B) -> Vec<Isometry3<f64>> {
    let mut poses = vec![Isometry3::identity(); b.model().num_links()];
    b.link_poses(&mut poses);
    poses
}

/// The lowest point of each tracked body (its clearance above the ground), from the backend's
/// state through the shared forward kinematics.
pub fn clearances<B: Backend>(b: &B) -> Vec<f64> {
    let poses = fk_poses(b);
    (0..b.model().tracked().len())
        .map(|t| b.model().tracked_lowest_z(t, &poses))
        .collect()
}

/// Sets a state the backend must accept.
pub fn set<B: Backend>(b: &mut B, state: &RobotState) {
    b.set_state(state)
        .unwrap_or_else(|e| panic!("{} rejected a valid state: {e}", B::NAME));
}

/// One PD sub-step towards `targets` through the shared actuator.
pub fn step_pd<B: Backend>(b: &mut B, act: &Actuator, targets: &[f64], scratch: &mut PdScratch) {
    pd_substep(b, act, targets, scratch)
        .unwrap_or_else(|e| panic!("{} failed a PD sub-step: {e}", B::NAME));
}

/// One sub-step with zero joint torques.
pub fn step_zero<B: Backend>(b: &mut B) {
    let zeros = vec![0.0; b.model().num_joints()];
    b.set_joint_torques(&zeros).expect("zero torques are valid");
    b.step()
        .unwrap_or_else(|e| panic!("{} failed a step: {e}", B::NAME));
}

/// The number of sub-steps in `seconds`.
pub fn steps_for(params: &PhysicsParams, seconds: f64) -> usize {
    (seconds / params.dt).round() as usize
}

/// A state in the air: standing pose, trunk `height` above the ground, at rest.
pub fn standing_at(model: &RobotModel, height: f64) -> RobotState {
    let mut s = model.spawn_state();
    s.trunk.pose.translation.z = height;
    s
}

/// Appends the bits of everything a backend reports to `out`.
pub fn record<B: Backend>(b: &B, out: &mut Vec<u64>) {
    let t = b.trunk();
    let q = t.pose.rotation.quaternion();
    out.extend(
        [
            t.pose.translation.x,
            t.pose.translation.y,
            t.pose.translation.z,
            q.w,
            q.i,
            q.j,
            q.k,
            t.linvel.x,
            t.linvel.y,
            t.linvel.z,
            t.angvel.x,
            t.angvel.y,
            t.angvel.z,
        ]
        .iter()
        .map(|v| v.to_bits()),
    );
    out.extend(read_q(b).iter().map(|v| v.to_bits()));
    out.extend(read_qd(b).iter().map(|v| v.to_bits()));
    out.extend(read_contacts(b).iter().map(|&c| u64::from(c)));
}

/// A PD run with targets drawn inside the limits, redrawn every 10 sub-steps, recorded bitwise.
pub fn random_pd_trajectory<B: Backend>(b: &mut B, seed: u64, steps: usize) -> Vec<u64> {
    let model = Arc::clone(b.model());
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let mut rng = Rng::new(seed);
    let mut targets = model.standing_pose().to_vec();
    let mut out = Vec::new();
    for i in 0..steps {
        if i % 10 == 0 {
            targets = rng.joint_angles(&model, 0.05);
        }
        step_pd(b, &act, &targets, &mut scratch);
        record(b, &mut out);
    }
    out
}

/// Index of the first value where two traces differ (or where one ends early).
pub fn first_difference(a: &[u64], b: &[u64]) -> Option<usize> {
    if a.len() != b.len() {
        return Some(a.len().min(b.len()));
    }
    a.iter().zip(b).position(|(x, y)| x != y)
}
