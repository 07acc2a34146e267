//! Shared fixtures of the conformance suite, also used by the backends' own tests and benches:
//! building worlds, a seeded random stream, reading a backend's state, stepping it, and
//! recording trajectories bit for bit. Every helper panics with the backend's name on failure
//! (they are for tests and benches, where a failure is the report).

use std::ops::Range;
use std::path::Path;
use std::sync::Arc;

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use hyq_physics::actuator::{Actuator, PdScratch, pd_substep};
use hyq_physics::bundled;
use hyq_physics::dynamics::{Dynamics, DynamicsDraw};
use hyq_physics::error::PhysicsError;
use hyq_physics::model::RobotModel;
use hyq_physics::profile::Profile;
use hyq_physics::{Backend, PhysicsParams, RobotState};

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

    /// The robot of URDF and profile text (`origin` names them in errors); panics if it cannot
    /// be loaded, with the loader's error.
    pub fn from_text(urdf: &str, profile: &str, origin: &str) -> Self {
        let profile =
            Profile::from_toml_str(profile, origin).unwrap_or_else(|e| panic!("{origin}: {e}"));
        let model = RobotModel::from_urdf_str(urdf, origin, &profile)
            .unwrap_or_else(|e| panic!("{origin}: {e}"));
        Self {
            model: Arc::new(model),
            urdf: urdf.to_owned(),
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

/// PD sub-steps the way the environment takes them (the shared actuator's torques, then one
/// step), towards the standing pose or towards random targets redrawn every 10 sub-steps (one
/// env step). Owns its actuator, scratch and targets, so a sub-step allocates nothing (the
/// backends' benchmarks time it).
pub struct PdDriver {
    model: Arc<RobotModel>,
    actuator: Actuator,
    scratch: PdScratch,
    targets: Vec<f64>,
    /// The stream and the margin (rad) inside the limits of random targets; `None` holds the
    /// standing pose.
    random: Option<(Rng, f64)>,
    /// Sub-steps taken or skipped so far.
    count: usize,
}

impl PdDriver {
    /// Holds `model`'s standing pose.
    pub fn standing(model: &Arc<RobotModel>) -> Self {
        Self {
            model: Arc::clone(model),
            actuator: Actuator::new(model),
            scratch: PdScratch::new(model.num_joints()),
            targets: model.standing_pose().to_vec(),
            random: None,
            count: 0,
        }
    }

    /// Targets drawn from [`Rng`]`::new(seed)`, uniformly inside the joint limits and `margin`
    /// (rad) away from them ([`Rng::fill_joint_angles`]), before the first sub-step and every
    /// 10 sub-steps after it.
    pub fn random(model: &Arc<RobotModel>, seed: u64, margin: f64) -> Self {
        Self {
            random: Some((Rng::new(seed), margin)),
            ..Self::standing(model)
        }
    }

    /// Advances the targets by `n` sub-steps without stepping anything: a driver that skipped
    /// `n` continues the run of one that took them, for a world that already ran them.
    pub fn skip(&mut self, n: usize) {
        for _ in 0..n {
            self.next_targets();
        }
    }

    /// One PD sub-step towards the current targets (redrawn first when due).
    pub fn substep<B: Backend>(&mut self, b: &mut B) -> Result<(), PhysicsError> {
        self.next_targets();
        pd_substep(b, &self.actuator, &self.targets, &mut self.scratch)
    }

    fn next_targets(&mut self) {
        if let Some((rng, margin)) = &mut self.random
            && self.count.is_multiple_of(10)
        {
            rng.fill_joint_angles(&self.model, *margin, &mut self.targets);
        }
        self.count += 1;
    }
}

/// The sub-step workloads of the backends' benchmarks (`benches/step.rs`), each on a world of
/// its own, the bundled robot at its spawn state: one call is one timed iteration, and
/// allocates nothing.
pub struct SubstepWorkloads<B: Backend> {
    standing_world: B,
    standing: PdDriver,
    random_world: B,
    random: PdDriver,
    reset_on_fall: bool,
    reset_world: B,
    spawn: RobotState,
    contacts: Vec<bool>,
    trunk: usize,
    /// Two varied dynamics ([`varied_dynamics`]) a randomised reset alternates between, and
    /// which one is next.
    varied: [Dynamics; 2],
    next_varied: usize,
}

impl<B: Backend> SubstepWorkloads<B> {
    /// The three worlds of `robot` on `B` with `options`; the standing one settles for 1 s
    /// first. With `reset_on_fall`, the random-target world is set back to the spawn state
    /// whenever the trunk touches the ground, as an episode would end.
    pub fn new(robot: &Robot, options: &B::Options, reset_on_fall: bool) -> Self {
        let model = &robot.model;
        let mut standing_world: B = build_default(robot, options);
        let mut standing = PdDriver::standing(model);
        for _ in 0..steps_for(&PhysicsParams::default(), 1.0) {
            standing
                .substep(&mut standing_world)
                .unwrap_or_else(|e| panic!("{} failed to stand: {e}", B::NAME));
        }
        Self {
            standing_world,
            standing,
            random_world: build_default(robot, options),
            random: PdDriver::random(model, 0, 0.0),
            reset_on_fall,
            reset_world: build_default(robot, options),
            spawn: model.spawn_state(),
            contacts: vec![false; model.tracked().len()],
            trunk: model.trunk_tracked_index(),
            varied: [
                varied_dynamics(model, 1, 0.6),
                varied_dynamics(model, 2, 0.9),
            ],
            next_varied: 0,
        }
    }

    /// One PD sub-step holding the standing pose, then the contact flags read.
    pub fn standing(&mut self) {
        self.standing
            .substep(&mut self.standing_world)
            .unwrap_or_else(|e| panic!("{} failed a standing sub-step: {e}", B::NAME));
        self.standing_world.contacts(&mut self.contacts);
    }

    /// One PD sub-step towards random targets anywhere inside the joint limits, redrawn every
    /// 10 sub-steps (feet landing and lifting, joints at their limits), then the contact flags
    /// read (and the reset, see [`SubstepWorkloads::new`]).
    pub fn random_targets(&mut self) {
        self.random
            .substep(&mut self.random_world)
            .unwrap_or_else(|e| panic!("{} failed a random-target sub-step: {e}", B::NAME));
        self.random_world.contacts(&mut self.contacts);
        if self.reset_on_fall && self.contacts[self.trunk] {
            set(&mut self.random_world, &self.spawn);
        }
    }

    /// `set_state` to the spawn state.
    pub fn set_state(&mut self) {
        set(&mut self.reset_world, &self.spawn);
    }

    /// A randomised episode's reset: `reset_with_dynamics` with other varied dynamics than
    /// last time (every body's mass, the trunk's centre of mass, damping, friction) and the
    /// spawn state, as an environment's reset makes it.
    pub fn randomized_reset(&mut self) {
        let d = &self.varied[self.next_varied];
        self.next_varied = 1 - self.next_varied;
        self.reset_world
            .reset_with_dynamics(d, &self.spawn)
            .unwrap_or_else(|e| panic!("{} refused varied dynamics: {e}", B::NAME));
    }
}

/// Dynamics varied in every way a randomised episode varies them, from [`Rng`]`::new(seed)`:
/// each body's mass (and tensor) scaled by U(0.8, 1.2), the trunk given U(−3, 5) kg at its
/// centre of mass, which moves by U(±0.05) m in x and y and 0.01 m up, every joint's damping
/// tripled, and the ground friction `friction`.
pub fn varied_dynamics(model: &RobotModel, seed: u64, friction: f64) -> Dynamics {
    let mut rng = Rng::new(seed);
    let mut d = DynamicsDraw::nominal(model, &PhysicsParams::default());
    d.ground_friction = friction;
    for s in &mut d.link_mass_scale {
        *s = rng.range(0.8, 1.2);
    }
    d.trunk_added_mass_kg = rng.range(-3.0, 5.0);
    d.trunk_com_offset_m = [rng.range(-0.05, 0.05), rng.range(-0.05, 0.05), 0.01];
    d.joint_damping_scale.fill(3.0);
    d.dynamics(model)
        .unwrap_or_else(|e| panic!("the varied dynamics are physical: {e}"))
}

/// Sub-steps `steps` (counted from 0) of a PD run towards random targets `margin` (rad) inside
/// the joint limits ([`PdDriver::random`]), each recorded bitwise after it is taken
/// ([`record`]). A range starting after 0 continues a run whose first sub-steps this world
/// already took: `random_pd_run(b, s, m, 0..n)` then `random_pd_run(b, s, m, n..n + k)` equals
/// `random_pd_run(b, s, m, 0..n + k)`.
pub fn random_pd_run<B: Backend>(
    b: &mut B,
    seed: u64,
    margin: f64,
    steps: Range<usize>,
) -> Vec<u64> {
    let mut driver = PdDriver::random(b.model(), seed, margin);
    driver.skip(steps.start);
    let mut out = Vec::new();
    for _ in steps {
        driver
            .substep(b)
            .unwrap_or_else(|e| panic!("{} failed a PD sub-step: {e}", B::NAME));
        record(b, &mut out);
    }
    out
}

/// A PD run with targets drawn 0.05 rad inside the limits, redrawn every 10 sub-steps,
/// recorded bitwise ([`random_pd_run`] from the first sub-step).
pub fn random_pd_trajectory<B: Backend>(b: &mut B, seed: u64, steps: usize) -> Vec<u64> {
    random_pd_run(b, seed, 0.05, 0..steps)
}

/// Index of the first value where two traces differ (or where one ends early).
pub fn first_difference(a: &[u64], b: &[u64]) -> Option<usize> {
    if a.len() != b.len() {
        return Some(a.len().min(b.len()));
    }
    a.iter().zip(b).position(|(x, y)| x != y)
}
