//! The backend conformance suite: test bodies written once, generic over any [`Backend`].
//!
//! A backend crate runs all of them with one line in its `tests/conformance.rs`:
//!
//! ```text
//! hyq_physics::conformance_tests!(hyq_rapier::RapierBackend);
//! // or, with engine options:
//! hyq_physics::conformance_tests!(hyq_rapier::RapierBackend, hyq_rapier::RapierOptions::default());
//! ```
//!
//! and enables this module with `hyq-physics = { …, features = ["conformance"] }` in its
//! dev-dependencies. Every test uses the bundled robot ([`crate::bundled::hyq`]) and derives
//! its numbers from the model, the URDF text or physics, never from a particular engine: a
//! second engine passes the suite unchanged or has a real difference to explain.
//!
//! Each `pub fn` below states the invariant it checks. Tolerances are stated where they are
//! used, with the reason for their size.

use std::collections::HashMap;
use std::sync::Arc;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use crate::actuator::{Actuator, PdScratch, pd_substep};
use crate::backend::{Backend, PhysicsParams, RobotState, TrunkState};
use crate::bundled;
use crate::error::PhysicsError;
use crate::model::RobotModel;
use crate::profile::Profile;

/// Instantiates every conformance test for a backend type, as `#[test]` functions in the
/// calling module; the second form passes engine options (an expression, evaluated per test).
#[macro_export]
macro_rules! conformance_tests {
    ($backend:ty) => {
        $crate::conformance_tests!($backend, <$backend as $crate::Backend>::Options::default());
    };
    ($backend:ty, $options:expr) => {
        $crate::conformance_tests!(@each $backend, $options,
            total_mass_matches_urdf,
            forward_kinematics_matches_independent_urdf_computation,
            set_state_round_trips,
            free_fall_matches_ballistic_until_contact,
            stands_in_nominal_pose_for_10_s,
            limp_robot_collapses_onto_its_trunk,
            joint_limits_hold_under_full_torque,
            lifted_foot_reports_no_contact,
            same_inputs_give_bitwise_identical_trajectories,
            reset_restores_trajectory_bitwise,
            internal_torques_conserve_momentum,
            trunk_velocity_is_the_frame_origin_velocity,
            joint_velocities_match_finite_differences,
            state_read_back_continues_the_trajectory,
            velocity_limit_bounds_joint_speed,
            joint_damping_is_applied,
            invalid_params_are_rejected,
            wrong_length_inputs_are_errors,
            non_finite_inputs_are_rejected,
            divergence_is_reported_and_recoverable,
        );
    };
    (@each $backend:ty, $options:expr, $($name:ident),* $(,)?) => {
        $(
            #[test]
            fn $name() {
                let options = $options;
                $crate::conformance::$name::<$backend>(&options);
            }
        )*
    };
}

// ----------------------------------------------------------------------------------------------
// Helpers.

fn build<B: Backend>(params: &PhysicsParams, options: &B::Options) -> B {
    B::build(bundled::hyq(), params, options)
        .unwrap_or_else(|e| panic!("{} backend failed to build: {e}", B::NAME))
}

fn build_default<B: Backend>(options: &B::Options) -> B {
    build(&PhysicsParams::default(), options)
}

fn zero_gravity() -> PhysicsParams {
    PhysicsParams {
        gravity: [0.0; 3],
        ..PhysicsParams::default()
    }
}

/// A small deterministic generator (xorshift64*), so the suite needs no random crate and every
/// run sees the same numbers.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Self(seed.max(1))
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Joint angles uniformly inside the limits, `margin` (rad) away from them.
    fn joint_angles(&mut self, model: &RobotModel, margin: f64) -> Vec<f64> {
        model
            .joints()
            .iter()
            .map(|j| self.range(j.lower + margin, j.upper - margin))
            .collect()
    }

    fn rotation(&mut self) -> UnitQuaternion<f64> {
        UnitQuaternion::from_euler_angles(
            self.range(-3.0, 3.0),
            self.range(-1.4, 1.4),
            self.range(-3.0, 3.0),
        )
    }

    fn vector(&mut self, scale: f64) -> Vector3<f64> {
        Vector3::new(
            self.range(-scale, scale),
            self.range(-scale, scale),
            self.range(-scale, scale),
        )
    }
}

fn read_q<B: Backend>(b: &B) -> Vec<f64> {
    let mut q = vec![0.0; b.model().num_joints()];
    b.joint_positions(&mut q);
    q
}

fn read_qd<B: Backend>(b: &B) -> Vec<f64> {
    let mut qd = vec![0.0; b.model().num_joints()];
    b.joint_velocities(&mut qd);
    qd
}

fn read_contacts<B: Backend>(b: &B) -> Vec<bool> {
    let mut c = vec![false; b.model().tracked().len()];
    b.contacts(&mut c);
    c
}

/// Body poses recomputed by the shared forward kinematics from the backend's trunk pose and
/// joint angles.
fn fk_poses<B: Backend>(b: &B) -> Vec<Isometry3<f64>> {
    let model = b.model();
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    model
        .link_poses(&b.trunk().pose, &read_q(b), &mut poses)
        .expect("forward kinematics of the backend's own state");
    poses
}

/// Body poses as the engine holds them.
fn engine_poses<B: Backend>(b: &B) -> Vec<Isometry3<f64>> {
    let mut poses = vec![Isometry3::identity(); b.model().num_links()];
    b.link_poses(&mut poses);
    poses
}

/// The lowest point of each tracked body (its clearance above the ground), from the backend's
/// state through the shared forward kinematics.
fn clearances<B: Backend>(b: &B) -> Vec<f64> {
    let poses = fk_poses(b);
    (0..b.model().tracked().len())
        .map(|t| b.model().tracked_lowest_z(t, &poses))
        .collect()
}

fn set<B: Backend>(b: &mut B, state: &RobotState) {
    b.set_state(state)
        .unwrap_or_else(|e| panic!("{} rejected a valid state: {e}", B::NAME));
}

fn step_pd<B: Backend>(b: &mut B, act: &Actuator, targets: &[f64], scratch: &mut PdScratch) {
    pd_substep(b, act, targets, scratch)
        .unwrap_or_else(|e| panic!("{} failed a PD sub-step: {e}", B::NAME));
}

fn step_zero<B: Backend>(b: &mut B) {
    let zeros = vec![0.0; b.model().num_joints()];
    b.set_joint_torques(&zeros).expect("zero torques are valid");
    b.step()
        .unwrap_or_else(|e| panic!("{} failed a step: {e}", B::NAME));
}

fn steps_for(params: &PhysicsParams, seconds: f64) -> usize {
    (seconds / params.dt).round() as usize
}

/// A state in the air: standing pose, trunk `height` above the ground, at rest.
fn standing_at(model: &RobotModel, height: f64) -> RobotState {
    let mut s = model.spawn_state();
    s.trunk.pose.translation.z = height;
    s
}

/// Appends the bits of everything a backend reports to `out`.
fn record<B: Backend>(b: &B, out: &mut Vec<u64>) {
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
fn random_pd_trajectory<B: Backend>(b: &mut B, seed: u64, steps: usize) -> Vec<u64> {
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

fn first_difference(a: &[u64], b: &[u64]) -> Option<usize> {
    if a.len() != b.len() {
        return Some(a.len().min(b.len()));
    }
    a.iter().zip(b).position(|(x, y)| x != y)
}

// ----------------------------------------------------------------------------------------------
// An independent reading of the URDF: figures parsed here and composed by hand, sharing no code
// with `RobotModel`'s loader or forward kinematics.

type Mat4 = [[f64; 4]; 4];

fn mat_mul(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut c = [[0.0; 4]; 4];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

/// `T = [Rz(yaw) Ry(pitch) Rx(roll) | xyz]`, written out from the URDF specification.
fn urdf_transform(xyz: [f64; 3], rpy: [f64; 3]) -> Mat4 {
    let (sr, cr) = rpy[0].sin_cos();
    let (sp, cp) = rpy[1].sin_cos();
    let (sy, cy) = rpy[2].sin_cos();
    [
        [
            cy * cp,
            cy * sp * sr - sy * cr,
            cy * sp * cr + sy * sr,
            xyz[0],
        ],
        [
            sy * cp,
            sy * sp * sr + cy * cr,
            sy * sp * cr - cy * sr,
            xyz[1],
        ],
        [-sp, cp * sr, cp * cr, xyz[2]],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// Rotation by `angle` about a unit `axis` (Rodrigues' formula).
fn axis_angle(axis: [f64; 3], angle: f64) -> Mat4 {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let [x, y, z] = [axis[0] / n, axis[1] / n, axis[2] / n];
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0.0],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0.0],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

fn isometry_to_mat(p: &Isometry3<f64>) -> Mat4 {
    let m = p.to_homogeneous();
    let mut out = [[0.0; 4]; 4];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = m[(i, j)];
        }
    }
    out
}

/// World position of each foot's collision-shape centre, from the URDF text, the profile and a
/// state, by walking each foot's chain up to the root and composing transforms by hand.
fn independent_foot_centres(state: &RobotState) -> Vec<[f64; 3]> {
    let robot = urdf_rs::read_from_string(bundled::HYQ_URDF).expect("bundled URDF parses");
    let profile = Profile::from_toml_str(bundled::HYQ_PROFILE, "bundled").expect("profile");
    let angle_of: HashMap<&str, f64> = profile
        .joints
        .iter()
        .zip(&state.q)
        .map(|(j, &q)| (j.urdf.as_str(), q))
        .collect();
    let joint_to_child: HashMap<&str, &urdf_rs::Joint> = robot
        .joints
        .iter()
        .map(|j| (j.child.link.as_str(), j))
        .collect();
    let root = isometry_to_mat(&state.trunk.pose);
    profile
        .feet
        .iter()
        .map(|foot| {
            let link = robot
                .links
                .iter()
                .find(|l| l.name == foot.link)
                .expect("foot link in the URDF");
            let collision = link
                .collision
                .iter()
                .find(|c| {
                    foot.collision
                        .as_ref()
                        .is_none_or(|n| c.name.as_ref() == Some(n))
                })
                .expect("foot collision in the URDF");
            // Chain of transforms from the foot link up to the root.
            let mut chain: Vec<Mat4> = Vec::new();
            let mut current = foot.link.as_str();
            while let Some(joint) = joint_to_child.get(current) {
                let mut t = urdf_transform(joint.origin.xyz.0, joint.origin.rpy.0);
                if joint.joint_type != urdf_rs::JointType::Fixed {
                    let q = angle_of[joint.name.as_str()];
                    t = mat_mul(&t, &axis_angle(joint.axis.xyz.0, q));
                }
                chain.push(t);
                current = joint.parent.link.as_str();
            }
            let mut world = root;
            for t in chain.iter().rev() {
                world = mat_mul(&world, t);
            }
            let c = collision.origin.xyz.0;
            std::array::from_fn(|i| {
                world[i][0] * c[0] + world[i][1] * c[1] + world[i][2] * c[2] + world[i][3]
            })
        })
        .collect()
}

fn foot_centres_from(model: &RobotModel, poses: &[Isometry3<f64>]) -> Vec<[f64; 3]> {
    model.tracked()[..model.num_feet()]
        .iter()
        .map(|t| {
            let link = &model.links()[t.link];
            let c = poses[t.link] * link.collisions[t.shapes[0]].origin;
            c.translation.vector.into()
        })
        .collect()
}

fn max_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
        })
        .fold(0.0, f64::max)
}

// ----------------------------------------------------------------------------------------------
// The tests.

/// The robot's mass is the sum of every URDF link's mass (read independently from the URDF
/// text), in the model and in the engine.
pub fn total_mass_matches_urdf<B: Backend>(options: &B::Options) {
    let robot = urdf_rs::read_from_string(bundled::HYQ_URDF).expect("bundled URDF parses");
    let urdf_mass: f64 = robot.links.iter().map(|l| l.inertial.mass.value).sum();
    let b: B = build_default(options);
    let model = b.model();
    assert!(
        (model.total_mass() - urdf_mass).abs() < 1e-9,
        "model mass {} kg, URDF {urdf_mass} kg",
        model.total_mass()
    );
    // Engines may store masses in f32: a relative 1e-6 is far below any physical effect.
    assert!(
        (b.total_mass() - urdf_mass).abs() < 1e-6 * urdf_mass,
        "{} holds {} kg, URDF {urdf_mass} kg",
        B::NAME,
        b.total_mass()
    );
}

/// Foot positions agree three ways for random configurations (trunk anywhere, any
/// orientation, joints anywhere in their limits): composed by hand from the URDF text, from
/// the model's forward kinematics, and from the engine's own body poses.
pub fn forward_kinematics_matches_independent_urdf_computation<B: Backend>(options: &B::Options) {
    let mut b: B = build(&zero_gravity(), options);
    let model = Arc::clone(b.model());
    let mut rng = Rng::new(7);
    for _ in 0..8 {
        let state = RobotState {
            trunk: TrunkState::at_rest(Isometry3::from_parts(
                Translation3::from(rng.vector(2.0) + Vector3::new(0.0, 0.0, 4.0)),
                rng.rotation(),
            )),
            q: rng.joint_angles(&model, 0.0),
            qd: vec![0.0; model.num_joints()],
        };
        let expected = independent_foot_centres(&state);

        let mut poses = vec![Isometry3::identity(); model.num_links()];
        model
            .link_poses(&state.trunk.pose, &state.q, &mut poses)
            .expect("forward kinematics");
        let from_model = foot_centres_from(&model, &poses);
        // Both in f64 from the same figures: only rounding differs.
        let err = max_distance(&expected, &from_model);
        assert!(err < 1e-9, "model forward kinematics off by {err} m");

        set(&mut b, &state);
        let from_engine = foot_centres_from(&model, &engine_poses(&b));
        // Engines may compute in f32 (about 1e-7 relative per operation, over a four-joint
        // chain a few metres from the origin): 1e-5 m is ample and far below any geometry error.
        let err = max_distance(&expected, &from_engine);
        assert!(
            err < 1e-5,
            "{} body poses put the feet {err} m off",
            B::NAME
        );
        let from_engine_fk = foot_centres_from(&model, &fk_poses(&b));
        let err = max_distance(&expected, &from_engine_fk);
        assert!(
            err < 1e-5,
            "{} trunk pose and joint angles put the feet {err} m off",
            B::NAME
        );
    }
}

/// A state set is the state read back (within f32 rounding), and contacts read false until
/// the first step.
pub fn set_state_round_trips<B: Backend>(options: &B::Options) {
    let mut b: B = build_default(options);
    let model = Arc::clone(b.model());
    let mut rng = Rng::new(11);
    for _ in 0..8 {
        let state = RobotState {
            trunk: TrunkState {
                pose: Isometry3::from_parts(
                    Translation3::from(rng.vector(2.0) + Vector3::new(0.0, 0.0, 3.0)),
                    rng.rotation(),
                ),
                linvel: rng.vector(2.0),
                angvel: rng.vector(3.0),
            },
            q: rng.joint_angles(&model, 0.0),
            qd: (0..model.num_joints())
                .map(|_| rng.range(-5.0, 5.0))
                .collect(),
        };
        set(&mut b, &state);
        let back = b.state();
        let t = &back.trunk;
        let close = |a: f64, e: f64, tol: f64, what: &str| {
            assert!((a - e).abs() <= tol, "{what}: set {e}, read {a}");
        };
        for i in 0..3 {
            close(
                t.pose.translation.vector[i],
                state.trunk.pose.translation.vector[i],
                1e-5,
                "trunk position",
            );
            close(
                t.linvel[i],
                state.trunk.linvel[i],
                1e-4,
                "trunk linear velocity",
            );
            close(
                t.angvel[i],
                state.trunk.angvel[i],
                1e-4,
                "trunk angular velocity",
            );
        }
        let angle = t.pose.rotation.angle_to(&state.trunk.pose.rotation);
        assert!(angle < 1e-5, "trunk orientation off by {angle} rad");
        for (i, j) in model.joints().iter().enumerate() {
            close(back.q[i], state.q[i], 1e-5, &format!("angle of {}", j.name));
            close(
                back.qd[i],
                state.qd[i],
                1e-4,
                &format!("speed of {}", j.name),
            );
        }
        assert!(
            read_contacts(&b).iter().all(|c| !c),
            "contacts must read false before the first step"
        );
    }
}

/// Dropped level from rest with zero torques, the trunk follows z₀ − g t²/2 until a foot
/// touches (within the O(dt) term of a first-order integrator, g·dt·t/2), does not drift or
/// turn, and contact flags follow the true clearance: never set while a shape is more than
/// `contact_distance` + 0.5 mm above the ground before and after the step (no speculative
/// contacts), always set once a shape starts a step touching or penetrating it.
pub fn free_fall_matches_ballistic_until_contact<B: Backend>(options: &B::Options) {
    let params = PhysicsParams::default();
    let mut b: B = build(&params, options);
    let model = Arc::clone(b.model());
    let drop = 0.1;
    let start = standing_at(&model, model.spawn_height() + drop);
    set(&mut b, &start);
    let g = -params.gravity[2];
    let z0 = start.trunk.pose.translation.z;
    let clearance0 = clearances(&b);
    let foot_clearance0 = clearance0[..model.num_feet()]
        .iter()
        .fold(f64::INFINITY, |a, &c| a.min(c));
    let touch_time = (2.0 * foot_clearance0 / g).sqrt();
    let steps = steps_for(&params, touch_time + 0.05);
    let cd = params.contact_distance;
    let mut before = clearance0;
    let mut touched = vec![false; model.tracked().len()];
    let mut in_flight = true;
    for n in 1..=steps {
        step_zero(&mut b);
        let after = clearances(&b);
        let flags = read_contacts(&b);
        for (t, tracked) in model.tracked().iter().enumerate() {
            if before[t] > cd + 5e-4 && after[t] > cd + 5e-4 {
                assert!(
                    !flags[t],
                    "step {n}: {} reported in contact {:.2} mm above the ground",
                    tracked.name,
                    1e3 * after[t].min(before[t])
                );
            }
            if before[t] <= 0.0 {
                assert!(
                    flags[t],
                    "step {n}: {} started the step touching the ground ({:.3} mm) but no contact",
                    tracked.name,
                    1e3 * before[t]
                );
            }
            touched[t] |= flags[t];
        }
        in_flight &= !flags.iter().any(|&f| f);
        if in_flight {
            let t = n as f64 * params.dt;
            let trunk = b.trunk();
            let z = trunk.pose.translation.z;
            let expected = z0 - g * t * t / 2.0;
            let tol = g * params.dt * t / 2.0 + 1e-5;
            assert!(
                (z - expected).abs() <= tol,
                "t = {t} s: trunk z {z}, ballistic {expected} (tolerance {tol})"
            );
            let vz = trunk.linvel.z;
            assert!(
                (vz + g * t).abs() <= g * params.dt + 1e-5,
                "t = {t} s: trunk vz {vz}, ballistic {}",
                -g * t
            );
            let drift = (trunk.pose.translation.vector.xy()
                - start.trunk.pose.translation.vector.xy())
            .norm();
            assert!(drift < 1e-5, "t = {t} s: trunk drifted {drift} m sideways");
            let turn = trunk.pose.rotation.angle_to(&start.trunk.pose.rotation);
            assert!(turn < 1e-5, "t = {t} s: trunk turned {turn} rad");
        }
        before = after;
    }
    for (t, foot) in model.tracked()[..model.num_feet()].iter().enumerate() {
        assert!(
            touched[t],
            "foot {} never touched the ground after the drop",
            foot.name
        );
    }
}

/// Under the default PD gains with the standing pose as target, the robot stands for 10 s from
/// its spawn state: over the last 5 s the trunk height varies by at most 1 mm, every foot is in
/// contact at every step, and the trunk never touches the ground.
pub fn stands_in_nominal_pose_for_10_s<B: Backend>(options: &B::Options) {
    let params = PhysicsParams::default();
    let mut b: B = build(&params, options);
    let model = Arc::clone(b.model());
    set(&mut b, &model.spawn_state());
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let targets = model.standing_pose().to_vec();
    let steps = steps_for(&params, 10.0);
    let settle = steps / 2;
    let trunk_index = model.trunk_tracked_index();
    let (mut z_min, mut z_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for n in 1..=steps {
        step_pd(&mut b, &act, &targets, &mut scratch);
        let flags = read_contacts(&b);
        assert!(
            !flags[trunk_index],
            "t = {} s: trunk touched the ground",
            n as f64 * params.dt
        );
        if n > settle {
            let z = b.trunk().pose.translation.z;
            z_min = z_min.min(z);
            z_max = z_max.max(z);
            for (t, tracked) in model.tracked()[..model.num_feet()].iter().enumerate() {
                assert!(
                    flags[t],
                    "t = {} s: foot {} not in contact while standing",
                    n as f64 * params.dt,
                    tracked.name
                );
            }
        }
    }
    assert!(
        z_max - z_min <= 1e-3,
        "trunk height varied by {:.3} mm over the last 5 s ({z_min} .. {z_max})",
        1e3 * (z_max - z_min)
    );
    // Standing means the trunk stays up: well above half its spawn height.
    assert!(
        z_min > 0.5 * model.spawn_height(),
        "trunk sank to {z_min} m (spawn {} m)",
        model.spawn_height()
    );
    let (roll, pitch, _) = b.trunk().pose.rotation.euler_angles();
    assert!(
        roll.abs() < 0.05 && pitch.abs() < 0.05,
        "trunk not level: roll {roll}, pitch {pitch}"
    );
}

/// With zero joint torques the robot cannot hold itself up: from its spawn state it sinks to
/// less than half its spawn height within 1 s. Laid limp on its side just above the ground, its
/// trunk lands and is reported in contact within 0.5 s, and not before it is within
/// `contact_distance` + 1 mm of the ground.
///
/// (A limp robot left standing may come to rest on legs folded against their joint limits with
/// its trunk off the ground: HyQ does, its trunk 8 cm up; tipped sideways it ends 3 cm up.)
pub fn limp_robot_collapses_onto_its_trunk<B: Backend>(options: &B::Options) {
    let params = PhysicsParams::default();
    let mut b: B = build(&params, options);
    let model = Arc::clone(b.model());
    set(&mut b, &model.spawn_state());
    for _ in 0..steps_for(&params, 1.0) {
        step_zero(&mut b);
    }
    let z = b.trunk().pose.translation.z;
    assert!(
        z < 0.5 * model.spawn_height(),
        "a limp robot still holds its trunk at {z} m after 1 s (spawn {} m)",
        model.spawn_height()
    );

    // On its side (rolled a quarter turn), the lowest trunk point 2 cm above the ground.
    let trunk_index = model.trunk_tracked_index();
    let mut side = model.spawn_state();
    side.trunk.pose.rotation =
        UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 0.0);
    set(&mut b, &side);
    side.trunk.pose.translation.z -= clearances(&b)[trunk_index] - 0.02;
    set(&mut b, &side);
    let mut touched = false;
    for n in 1..=steps_for(&params, 0.5) {
        let before = clearances(&b)[trunk_index];
        step_zero(&mut b);
        let after = clearances(&b)[trunk_index];
        if read_contacts(&b)[trunk_index] {
            assert!(
                before.min(after) <= params.contact_distance + 1e-3,
                "trunk reported in contact at step {n} with {} m clearance",
                before.min(after)
            );
            touched = true;
            break;
        }
    }
    assert!(
        touched,
        "a limp robot on its side never put its trunk on the ground (clearance {} m)",
        clearances(&b)[trunk_index]
    );
}

/// Every joint driven into its limits at full torque (targets 0.5 rad past alternate limits,
/// stiff gains saturating at the effort limit) stays within 0.1 rad of its range, and no
/// joint comes apart: the engine's body poses stay within 1 mm of the forward kinematics of its
/// trunk pose and joint angles. First floating in zero gravity, where every joint must reach
/// each limit (within 0.1 rad by the end of each 0.5 s phase), then on the ground under the
/// robot's weight, where every joint must reach each limit at least once in 2 s.
pub fn joint_limits_hold_under_full_torque<B: Backend>(options: &B::Options) {
    let model = bundled::hyq();
    let n = model.num_joints();
    let act = Actuator::with_gains(&model, &vec![3000.0; n], &vec![30.0; n]).expect("gains");
    let mut worst_overshoot: f64 = 0.0;
    let mut worst_separation: f64 = 0.0;
    for (params, start, in_air) in [
        (zero_gravity(), standing_at(&model, 3.0), true),
        (PhysicsParams::default(), model.spawn_state(), false),
    ] {
        let mut b: B = build(&params, options);
        set(&mut b, &start);
        let mut scratch = PdScratch::new(n);
        let phase = steps_for(&params, 0.5);
        let mut saturated = vec![false; n];
        // Closest approach to each joint's [lower, upper] limit over the run.
        let mut closest = vec![[f64::INFINITY; 2]; n];
        for p in 0..4 {
            let upper = p % 2 == 0;
            let targets: Vec<f64> = model
                .joints()
                .iter()
                .map(|j| if upper { j.upper + 0.5 } else { j.lower - 0.5 })
                .collect();
            for _ in 0..phase {
                step_pd(&mut b, &act, &targets, &mut scratch);
                for (i, tau) in scratch.torques().iter().enumerate() {
                    saturated[i] |= tau.abs() >= model.joints()[i].effort;
                }
                let q = read_q(&b);
                for (i, j) in model.joints().iter().enumerate() {
                    let over = (j.lower - q[i]).max(q[i] - j.upper).max(0.0);
                    worst_overshoot = worst_overshoot.max(over);
                    assert!(
                        over <= 0.1,
                        "joint {} at {} rad, {over} rad past its range [{}, {}] (in the air: {in_air})",
                        j.name,
                        q[i],
                        j.lower,
                        j.upper
                    );
                    closest[i][0] = closest[i][0].min((q[i] - j.lower).abs());
                    closest[i][1] = closest[i][1].min((q[i] - j.upper).abs());
                }
                let fk = fk_poses(&b);
                let engine = engine_poses(&b);
                for (l, (a, e)) in fk.iter().zip(&engine).enumerate() {
                    let sep = (a.translation.vector - e.translation.vector).norm();
                    worst_separation = worst_separation.max(sep);
                    assert!(
                        sep <= 1e-3,
                        "body {} is {sep} m away from where its joints put it (in the air: {in_air})",
                        model.links()[l].name
                    );
                }
            }
            if in_air {
                let q = read_q(&b);
                for (i, j) in model.joints().iter().enumerate() {
                    let limit = if upper { j.upper } else { j.lower };
                    assert!(
                        (q[i] - limit).abs() <= 0.1,
                        "joint {} at {} rad did not reach its limit {limit} rad in the air",
                        j.name,
                        q[i]
                    );
                }
            }
        }
        for (i, j) in model.joints().iter().enumerate() {
            assert!(
                saturated[i],
                "joint {} never saturated: the test must drive every joint at full torque",
                j.name
            );
            assert!(
                closest[i][0] <= 0.1 && closest[i][1] <= 0.1,
                "joint {} came only within {:?} rad of its limits (in the air: {in_air})",
                j.name,
                closest[i]
            );
        }
    }
    // Both figures are part of the report of this test.
    println!(
        "{}: worst limit overshoot {worst_overshoot:.4} rad, worst joint separation {worst_separation:.2e} m",
        B::NAME
    );
}

/// A foot held 5 mm above the ground, while the other feet stand on it, is not in contact
/// (an engine's speculative contact at that distance does not count); the feet on the ground
/// are.
pub fn lifted_foot_reports_no_contact<B: Backend>(options: &B::Options) {
    let params = PhysicsParams::default();
    let mut b: B = build(&params, options);
    let model = Arc::clone(b.model());
    let lifted = 0;
    let foot = &model.tracked()[lifted];
    // The last joint on the lifted foot's chain (e.g. the knee) raises it.
    let joint = model.links()[foot.link]
        .parent_joint
        .expect("a foot hangs from a joint");
    let mut state = model.spawn_state();
    // Height of the lifted foot above the lowest of the other feet, minus the 5 mm wanted.
    let lift = 5e-3;
    let heights = |s: &RobotState| -> Vec<f64> {
        let mut poses = vec![Isometry3::identity(); model.num_links()];
        model
            .link_poses(&s.trunk.pose, &s.q, &mut poses)
            .expect("forward kinematics");
        (0..model.num_feet())
            .map(|t| model.tracked_lowest_z(t, &poses))
            .collect()
    };
    let others = |h: &[f64]| {
        h.iter()
            .enumerate()
            .filter(|&(t, _)| t != lifted)
            .fold(f64::INFINITY, |a, (_, &z)| a.min(z))
    };
    let goal = |s: &RobotState| {
        let h = heights(s);
        h[lifted] - others(&h) - lift
    };
    // Secant search on that joint's angle.
    let (mut a, mut b_angle) = (state.q[joint], state.q[joint] + 0.01);
    let mut fa = goal(&state);
    for _ in 0..50 {
        state.q[joint] = b_angle;
        let fb = goal(&state);
        if fb.abs() < 1e-9 {
            break;
        }
        let next = b_angle - fb * (b_angle - a) / (fb - fa);
        (a, fa, b_angle) = (b_angle, fb, next);
    }
    let j = &model.joints()[joint];
    assert!(
        (j.lower..=j.upper).contains(&state.q[joint]),
        "lifting the foot needs {} = {} rad, outside its limits",
        j.name,
        state.q[joint]
    );
    // Put the standing feet exactly on the ground.
    state.trunk.pose.translation.z -= others(&heights(&state));
    let foot_height = heights(&state)[lifted];
    assert!(
        (foot_height - lift).abs() < 1e-6,
        "foot placed at {foot_height} m"
    );
    set(&mut b, &state);
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let targets = state.q.clone();
    // 10 ms: the robot settles by well under the 4 mm left above the contact distance.
    for n in 1..=10 {
        step_pd(&mut b, &act, &targets, &mut scratch);
        let flags = read_contacts(&b);
        assert!(
            !flags[lifted],
            "step {n}: foot {} reported in contact {:.2} mm above the ground",
            foot.name,
            1e3 * clearances(&b)[lifted]
        );
        for t in (0..model.num_feet()).filter(|&t| t != lifted) {
            assert!(
                flags[t],
                "step {n}: foot {} on the ground not in contact",
                model.tracked()[t].name
            );
        }
    }
}

/// Two worlds built alike and driven alike produce bitwise-identical trajectories (joint
/// state, trunk state and contacts at every step).
pub fn same_inputs_give_bitwise_identical_trajectories<B: Backend>(options: &B::Options) {
    let mut first: B = build_default(options);
    let mut second: B = build_default(options);
    let a = random_pd_trajectory(&mut first, 3, 400);
    let b = random_pd_trajectory(&mut second, 3, 400);
    assert_eq!(first_difference(&a, &b), None, "trajectories differ");
}

/// `set_state` forgets everything: after running on (contacts, warm starts, pending torques),
/// setting a state again and repeating the inputs repeats the trajectory bitwise, as does a
/// freshly built world; a world as built equals one set to the spawn state.
pub fn reset_restores_trajectory_bitwise<B: Backend>(options: &B::Options) {
    let model = bundled::hyq();
    let mut rng = Rng::new(5);
    let mut moving = model.spawn_state();
    moving.trunk.linvel = Vector3::new(0.3, -0.1, 0.0);
    moving.trunk.angvel = Vector3::new(0.0, 0.2, 0.1);
    moving.qd = (0..model.num_joints())
        .map(|_| rng.range(-1.0, 1.0))
        .collect();
    for start in [model.spawn_state(), moving] {
        let mut b: B = build_default(options);
        set(&mut b, &start);
        let first = random_pd_trajectory(&mut b, 9, 300);
        // Run on elsewhere, and leave a torque pending that the reset must discard.
        let _ = random_pd_trajectory(&mut b, 10, 200);
        b.set_joint_torques(&vec![50.0; model.num_joints()])
            .expect("torques");
        set(&mut b, &start);
        let again = random_pd_trajectory(&mut b, 9, 300);
        assert_eq!(
            first_difference(&first, &again),
            None,
            "trajectory after set_state differs"
        );
        let mut fresh: B = build_default(options);
        set(&mut fresh, &start);
        let fresh_run = random_pd_trajectory(&mut fresh, 9, 300);
        assert_eq!(
            first_difference(&first, &fresh_run),
            None,
            "trajectory of a fresh world differs"
        );
    }
    let mut built: B = build_default(options);
    let mut spawned: B = build_default(options);
    set(&mut spawned, &model.spawn_state());
    assert_eq!(
        first_difference(
            &random_pd_trajectory(&mut built, 4, 200),
            &random_pd_trajectory(&mut spawned, 4, 200)
        ),
        None,
        "a world as built differs from one set to the spawn state"
    );
}

/// In zero gravity, away from the ground, internal joint torques cannot move the centre of
/// mass: it keeps its initial velocity (straight line) while the robot tumbles and flails for
/// 1 s. This catches a floating root whose velocity is integrated at the wrong point.
pub fn internal_torques_conserve_momentum<B: Backend>(options: &B::Options) {
    let params = zero_gravity();
    let mut b: B = build(&params, options);
    let model = Arc::clone(b.model());
    let mut start = standing_at(&model, 3.0);
    start.trunk.linvel = Vector3::new(1.0, -0.3, 0.5);
    start.trunk.angvel = Vector3::new(0.5, -0.8, 4.0);
    set(&mut b, &start);
    let com = |b: &B| model.centre_of_mass(&fk_poses(b));
    let c0 = com(&b);
    step_zero(&mut b);
    let c1 = com(&b);
    let v = (c1 - c0) / params.dt;
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let mut rng = Rng::new(17);
    let mut targets = model.standing_pose().to_vec();
    let mut worst: f64 = 0.0;
    for n in 2..=steps_for(&params, 1.0) {
        if n % 50 == 0 {
            targets = rng.joint_angles(&model, 0.1);
        }
        step_pd(&mut b, &act, &targets, &mut scratch);
        let t = (n - 1) as f64 * params.dt;
        let err = (com(&b) - (c1 + v * t)).norm();
        worst = worst.max(err);
    }
    // A first-order integrator at 1 kHz drifts by millimetres in this violent second (rapier:
    // 0.7 mm at 4 solver iterations, 6 mm at 1); a root integrated at its frame origin
    // instead of its centre of mass is off by decimetres (0.3 m).
    println!(
        "{}: centre of mass left its straight line by {worst:.2e} m in 1 s",
        B::NAME
    );
    assert!(
        worst < 1e-2,
        "centre of mass left its straight line by {worst} m"
    );
    assert!(
        read_contacts(&b).iter().all(|c| !c),
        "the robot must stay clear of the ground in this test"
    );
}

/// How far a finite difference over one step may be from the mean of the velocities reported
/// before and after it: an integrator with internal substeps moves by the mean of its substep
/// velocities, which lies between the two (monotonic change within the step) up to this slack;
/// the constant covers f32 rounding of the positions (a few 1e-7 over 1e-3 s).
fn fd_slack(v0: f64, v1: f64) -> f64 {
    0.75 * (v1 - v0).abs() + 3e-3
}

/// The reported trunk velocity is that of the trunk frame's origin and the angular velocity is
/// the world-frame one: finite differences of the trunk pose over each step agree with the
/// velocities reported before and after it, while the robot tumbles freely in zero gravity
/// (where the origin's and the centre of mass's velocities differ by ω × r ≈ 0.2 m/s).
pub fn trunk_velocity_is_the_frame_origin_velocity<B: Backend>(options: &B::Options) {
    let params = zero_gravity();
    let mut b: B = build(&params, options);
    let model = Arc::clone(b.model());
    let mut start = standing_at(&model, 3.0);
    start.trunk.linvel = Vector3::new(0.2, 0.1, -0.1);
    start.trunk.angvel = Vector3::new(1.0, -2.0, 3.0);
    set(&mut b, &start);
    for n in 0..300 {
        let before = b.trunk();
        step_zero(&mut b);
        let after = b.trunk();
        let fd_v = (after.pose.translation.vector - before.pose.translation.vector) / params.dt;
        let fd_w = (after.pose.rotation * before.pose.rotation.inverse()).scaled_axis() / params.dt;
        for k in 0..3 {
            let (v0, v1) = (before.linvel[k], after.linvel[k]);
            assert!(
                (fd_v[k] - 0.5 * (v0 + v1)).abs() <= fd_slack(v0, v1),
                "step {n}: trunk velocity[{k}] {v0} -> {v1}, finite difference {}",
                fd_v[k]
            );
            let (w0, w1) = (before.angvel[k], after.angvel[k]);
            assert!(
                (fd_w[k] - 0.5 * (w0 + w1)).abs() <= fd_slack(w0, w1),
                "step {n}: trunk angular velocity[{k}] {w0} -> {w1}, finite difference {}",
                fd_w[k]
            );
        }
    }
}

/// Reported joint speeds are the time derivative of the reported angles (units, sign): they
/// agree with finite differences over each step (see the trunk test for the criterion) while
/// the legs flail in zero gravity, away from the ground and the joint limits. (Contacts and
/// limit stops change velocities within a step non-monotonically, so they are left out.)
pub fn joint_velocities_match_finite_differences<B: Backend>(options: &B::Options) {
    let params = zero_gravity();
    let mut b: B = build(&params, options);
    let model = Arc::clone(b.model());
    set(&mut b, &standing_at(&model, 3.0));
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    let mut rng = Rng::new(29);
    let mut targets = model.standing_pose().to_vec();
    for n in 0..500 {
        if n % 50 == 0 {
            targets = rng.joint_angles(&model, 0.4);
        }
        let (q0, v0) = (read_q(&b), read_qd(&b));
        step_pd(&mut b, &act, &targets, &mut scratch);
        let (q1, v1) = (read_q(&b), read_qd(&b));
        for (i, j) in model.joints().iter().enumerate() {
            let fd = (q1[i] - q0[i]) / params.dt;
            assert!(
                (fd - 0.5 * (v0[i] + v1[i])).abs() <= fd_slack(v0[i], v1[i]),
                "step {n}: joint {} speed {} -> {}, finite difference {fd}",
                j.name,
                v0[i],
                v1[i]
            );
        }
    }
}

/// The state read back is the state: a run that is stopped every 10 steps, read with
/// [`Backend::state`] and put back with [`Backend::set_state`] follows the uninterrupted run
/// (flailing in zero gravity, away from the ground and the joint limits). Stale or misplaced
/// velocities would make it veer off within a few round trips.
pub fn state_read_back_continues_the_trajectory<B: Backend>(options: &B::Options) {
    let params = zero_gravity();
    let model = bundled::hyq();
    let mut start = standing_at(&model, 3.0);
    start.trunk.linvel = Vector3::new(0.3, -0.2, 0.1);
    start.trunk.angvel = Vector3::new(0.5, 1.0, -1.5);
    let act = Actuator::new(&model);
    let run = |round_trip: bool| -> RobotState {
        let mut b: B = build(&params, options);
        set(&mut b, &start);
        let mut scratch = PdScratch::new(model.num_joints());
        let mut rng = Rng::new(31);
        let mut targets = model.standing_pose().to_vec();
        for n in 0..200 {
            if n % 20 == 0 {
                targets = rng.joint_angles(&model, 0.4);
            }
            if round_trip && n % 10 == 0 {
                let s = b.state();
                set(&mut b, &s);
            }
            step_pd(&mut b, &act, &targets, &mut scratch);
        }
        b.state()
    };
    let plain = run(false);
    let interrupted = run(true);
    let dq = plain
        .q
        .iter()
        .zip(&interrupted.q)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let dqd = plain
        .qd
        .iter()
        .zip(&interrupted.qd)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let dp =
        (plain.trunk.pose.translation.vector - interrupted.trunk.pose.translation.vector).norm();
    let dr = plain
        .trunk
        .pose
        .rotation
        .angle_to(&interrupted.trunk.pose.rotation);
    println!(
        "{}: after 20 round trips: joint angles {dq:.2e} rad, speeds {dqd:.2e} rad/s, trunk {dp:.2e} m, {dr:.2e} rad",
        B::NAME
    );
    // f32 rounding at each round trip, amplified by 0.2 s of flailing, stays below these; a
    // velocity stale by one solver substep is off by rad/s at once.
    assert!(dq < 1e-3, "joint angles differ by {dq} rad");
    assert!(dqd < 3e-2, "joint speeds differ by {dqd} rad/s");
    assert!(dp < 1e-4, "trunk position differs by {dp} m");
    assert!(dr < 1e-3, "trunk orientation differs by {dr} rad");
}

/// The actuator's velocity-limit rule keeps joint speeds near their URDF limits in the
/// learning workload (default gains, random targets redrawn every 10 sub-steps, on the ground,
/// reset when the trunk touches): the 99th percentile of |q̇| / limit stays at most 2 and the
/// peak at most 4.5. Without the rule the 99th percentile is at least 1.5 times higher, so the
/// bound is the rule's doing. (The rule cannot do more: joints whipped by their neighbours or
/// stopped by a limit exceed it with no motor torque at all; see `hyq_physics::actuator`.)
pub fn velocity_limit_bounds_joint_speed<B: Backend>(options: &B::Options) {
    let params = PhysicsParams::default();
    let model = bundled::hyq();
    let n = model.num_joints();
    let run = |limit: bool| -> (f64, f64) {
        let mut b: B = build(&params, options);
        let mut act = Actuator::new(&model);
        act.set_velocity_limit(limit);
        let mut scratch = PdScratch::new(n);
        let mut rng = Rng::new(37);
        let mut targets = model.standing_pose().to_vec();
        let mut ratios = Vec::new();
        let trunk = model.trunk_tracked_index();
        for i in 0..4000 {
            if i % 10 == 0 {
                targets = rng.joint_angles(&model, 0.0);
            }
            step_pd(&mut b, &act, &targets, &mut scratch);
            for (qd, j) in read_qd(&b).iter().zip(model.joints()) {
                ratios.push(qd.abs() / j.velocity);
            }
            if read_contacts(&b)[trunk] {
                set(&mut b, &model.spawn_state());
            }
        }
        ratios.sort_by(f64::total_cmp);
        let p99 = ratios[(ratios.len() - 1) * 99 / 100];
        (p99, ratios[ratios.len() - 1])
    };
    let (p99, peak) = run(true);
    let (p99_off, peak_off) = run(false);
    println!(
        "{}: |joint speed| / limit, 99th percentile and peak: {p99:.2}, {peak:.2} with the rule; {p99_off:.2}, {peak_off:.2} without",
        B::NAME
    );
    assert!(
        p99 <= 2.0,
        "99th percentile of |q̇| / limit is {p99} with the rule"
    );
    assert!(peak <= 4.5, "peak |q̇| / limit is {peak} with the rule");
    assert!(
        p99_off >= 1.5 * p99,
        "without the rule the 99th percentile is {p99_off}, with it {p99}: the rule does not matter?"
    );
}

/// The backend applies the model's passive joint damping: in zero gravity with no torque, the
/// joints carrying only a leaf body, set spinning at 1 rad/s, lose more than half their speed
/// within 0.5 s (the URDF damping against the leaf's inertia; without damping the speed would
/// barely change).
pub fn joint_damping_is_applied<B: Backend>(options: &B::Options) {
    let params = zero_gravity();
    let mut b: B = build(&params, options);
    let model = Arc::clone(b.model());
    let leaves: Vec<usize> = (0..model.num_joints())
        .filter(|&j| {
            let child = model.joints()[j].child;
            model.links().iter().all(|l| l.parent != Some(child)) && model.joints()[j].damping > 0.0
        })
        .collect();
    assert!(
        !leaves.is_empty(),
        "the robot needs a damped leaf joint for this test"
    );
    let mut start = standing_at(&model, 3.0);
    for &j in &leaves {
        let joint = &model.joints()[j];
        start.q[j] = 0.5 * (joint.lower + joint.upper);
        start.qd[j] = 1.0;
    }
    set(&mut b, &start);
    for _ in 0..steps_for(&params, 0.5) {
        step_zero(&mut b);
    }
    let qd = read_qd(&b);
    for &j in &leaves {
        assert!(
            qd[j].abs() < 0.5,
            "joint {} still turns at {} rad/s after 0.5 s (started at 1 rad/s)",
            model.joints()[j].name,
            qd[j]
        );
    }
}

/// Invalid physics parameters are refused when the world is built, and the error names the
/// field.
pub fn invalid_params_are_rejected<B: Backend>(options: &B::Options) {
    let cases: [(&str, PhysicsParams); 5] = [
        (
            "dt",
            PhysicsParams {
                dt: 0.0,
                ..PhysicsParams::default()
            },
        ),
        (
            "dt",
            PhysicsParams {
                dt: f64::NAN,
                ..PhysicsParams::default()
            },
        ),
        (
            "gravity",
            PhysicsParams {
                gravity: [0.0, f64::INFINITY, -9.81],
                ..PhysicsParams::default()
            },
        ),
        (
            "ground_friction",
            PhysicsParams {
                ground_friction: -0.5,
                ..PhysicsParams::default()
            },
        ),
        (
            "contact_distance",
            PhysicsParams {
                contact_distance: -1e-3,
                ..PhysicsParams::default()
            },
        ),
    ];
    for (field, params) in cases {
        match B::build(bundled::hyq(), &params, options) {
            Err(PhysicsError::InvalidParam { field: f, .. }) => assert_eq!(f, field),
            Err(other) => panic!("{field}: expected InvalidParam, got {other}"),
            Ok(_) => panic!("{} accepted an invalid {field}", B::NAME),
        }
    }
}

/// Torques, targets and states of the wrong length are errors naming what was wrong, and
/// leave the world as it was.
pub fn wrong_length_inputs_are_errors<B: Backend>(options: &B::Options) {
    let mut b: B = build_default(options);
    let model = Arc::clone(b.model());
    let n = model.num_joints();
    let before = b.state();
    for len in [0, n - 1, n + 1] {
        match b.set_joint_torques(&vec![0.0; len]) {
            Err(PhysicsError::WrongLength { expected, got, .. }) => {
                assert_eq!((expected, got), (n, len));
            }
            other => panic!("torques of length {len}: expected WrongLength, got {other:?}"),
        }
        let mut s = model.spawn_state();
        s.q = vec![0.0; len];
        assert!(
            matches!(b.set_state(&s), Err(PhysicsError::WrongLength { .. })),
            "joint angles of length {len} accepted"
        );
        let mut s = model.spawn_state();
        s.qd = vec![0.0; len];
        assert!(
            matches!(b.set_state(&s), Err(PhysicsError::WrongLength { .. })),
            "joint speeds of length {len} accepted"
        );
        let act = Actuator::new(&model);
        let mut scratch = PdScratch::new(n);
        assert!(
            matches!(
                pd_substep(&mut b, &act, &vec![0.0; len], &mut scratch),
                Err(PhysicsError::WrongLength { .. })
            ),
            "targets of length {len} accepted"
        );
    }
    assert_eq!(b.state(), before, "a rejected input changed the world");
}

/// Non-finite states and torques, and orientations that are not unit quaternions, are
/// rejected with an error naming the value, and leave the world as it was.
pub fn non_finite_inputs_are_rejected<B: Backend>(options: &B::Options) {
    let mut b: B = build_default(options);
    let model = Arc::clone(b.model());
    let before = b.state();
    let spawn = model.spawn_state();
    let mut cases: Vec<(&str, RobotState)> = Vec::new();
    let mut s = spawn.clone();
    s.q[1] = f64::NAN;
    cases.push(("angle of joint", s));
    let mut s = spawn.clone();
    s.qd[0] = f64::INFINITY;
    cases.push(("speed of joint", s));
    let mut s = spawn.clone();
    s.trunk.pose.translation.z = f64::NAN;
    cases.push(("trunk position z", s));
    let mut s = spawn.clone();
    s.trunk.angvel.y = f64::NEG_INFINITY;
    cases.push(("trunk angular velocity y", s));
    for (what, state) in cases {
        match b.set_state(&state) {
            Err(PhysicsError::NonFinite { what: w, .. }) => {
                assert!(w.contains(what), "error names {w:?}, expected {what:?}");
            }
            other => panic!("{what}: expected NonFinite, got {other:?}"),
        }
    }
    let mut s = spawn.clone();
    s.trunk.pose.rotation =
        UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(2.0, 0.0, 0.0, 0.0));
    assert!(
        matches!(b.set_state(&s), Err(PhysicsError::InvalidState { .. })),
        "a non-unit quaternion was accepted"
    );
    let mut torques = vec![0.0; model.num_joints()];
    torques[2] = f64::NAN;
    match b.set_joint_torques(&torques) {
        Err(PhysicsError::NonFinite { what, .. }) => {
            assert!(
                what.contains(&model.joints()[2].name),
                "error names {what:?}"
            );
        }
        other => panic!("NaN torque: expected NonFinite, got {other:?}"),
    }
    let mut targets = model.standing_pose().to_vec();
    targets[0] = f64::NAN;
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    assert!(
        matches!(
            pd_substep(&mut b, &act, &targets, &mut scratch),
            Err(PhysicsError::NonFinite { .. })
        ),
        "a NaN target was accepted"
    );
    assert_eq!(b.state(), before, "a rejected input changed the world");
}

/// A step never returns `Ok` with a non-finite state: driven with absurd (finite) torques,
/// every `Ok` step leaves every read finite, a diverged step says so, and `set_state` brings
/// the world back.
pub fn divergence_is_reported_and_recoverable<B: Backend>(options: &B::Options) {
    let mut b: B = build_default(options);
    let model = Arc::clone(b.model());
    let huge = vec![1e300; model.num_joints()];
    let mut diverged = false;
    for _ in 0..20 {
        b.set_joint_torques(&huge)
            .expect("finite torques are valid input");
        match b.step() {
            Ok(()) => {
                let s = b.state();
                assert_eq!(
                    s.first_non_finite(&model),
                    None,
                    "step returned Ok with a non-finite state"
                );
                assert!(
                    s.trunk.pose.rotation.quaternion().norm().is_finite(),
                    "non-finite orientation after Ok"
                );
            }
            Err(PhysicsError::Diverged { .. }) => {
                diverged = true;
                break;
            }
            Err(other) => panic!("expected Diverged, got {other}"),
        }
    }
    set(&mut b, &model.spawn_state());
    step_zero(&mut b);
    let s = b.state();
    assert_eq!(
        s.first_non_finite(&model),
        None,
        "not recovered after set_state"
    );
    let z = s.trunk.pose.translation.z;
    assert!(
        (z - model.spawn_height()).abs() < 0.01,
        "after set_state (diverged before: {diverged}) the trunk is at {z} m"
    );
    // The world behaves as a fresh one again.
    let mut fresh: B = build_default(options);
    set(&mut b, &model.spawn_state());
    let again = random_pd_trajectory(&mut b, 13, 100);
    let reference = random_pd_trajectory(&mut fresh, 13, 100);
    assert_eq!(
        first_difference(&again, &reference),
        None,
        "a world reset after divergence differs from a fresh one"
    );
}
