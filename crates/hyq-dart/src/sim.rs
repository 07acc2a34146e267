//! A safe owner of one DART world: checks lengths on the Rust side and turns C++ exceptions into
//! [`DartError`]s.

use cxx::UniquePtr;

use crate::bridge::ffi;
use crate::error::DartError;

pub(crate) use ffi::{
    BaseState, BodyDesc, Inertial, JointKind, Pose, ShapeDesc, ShapeKind, WorldDesc,
};

impl Pose {
    /// The identity transform.
    pub(crate) const IDENTITY: Self = Self {
        translation: [0.0; 3],
        rotation: [1.0, 0.0, 0.0, 0.0],
    };
}

/// One DART world (robot + ground). `Send`, not `Sync`.
pub(crate) struct Sim {
    inner: UniquePtr<ffi::Sim>,
    num_joints: usize,
    num_bodies: usize,
    num_tracked: usize,
}

impl std::fmt::Debug for Sim {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Sim")
            .field("num_joints", &self.num_joints)
            .field("num_tracked", &self.num_tracked)
            .finish_non_exhaustive()
    }
}

impl Sim {
    /// Builds a world from the description, at the zero pose (root frame = world frame).
    pub(crate) fn new(
        bodies: &[BodyDesc],
        shapes: &[ShapeDesc],
        world: &WorldDesc,
    ) -> Result<Self, DartError> {
        let inner = ffi::new_sim(bodies, shapes, world)?;
        if inner.is_null() {
            return Err(DartError::NullWorld);
        }
        let num_joints = bodies
            .iter()
            .filter(|b| b.joint_kind == JointKind::Revolute)
            .count();
        Ok(Self {
            inner,
            num_joints,
            num_bodies: bodies.len(),
            num_tracked: world.num_tracked as usize,
        })
    }

    fn pin(&mut self) -> std::pin::Pin<&mut ffi::Sim> {
        // Invariant: `new` rejected a null pointer and nothing resets `inner` afterwards.
        #[allow(clippy::expect_used)]
        self.inner.as_mut().expect("Sim::inner is never null")
    }

    fn get(&self) -> &ffi::Sim {
        // Invariant: see `pin`.
        #[allow(clippy::expect_used)]
        self.inner.as_ref().expect("Sim::inner is never null")
    }

    /// Sets the root state and joint state; everything else as freshly built.
    pub(crate) fn set_state(
        &mut self,
        base: &BaseState,
        q: &[f64],
        qd: &[f64],
    ) -> Result<(), DartError> {
        self.pin().set_state(base, q, qd)?;
        Ok(())
    }

    /// Replaces the ground with a height field of `depth` rows of `width` heights (`heights`,
    /// row after row), `spacing` apart along the field's x and y, at `pose`; effective from the
    /// next [`Self::set_state`].
    pub(crate) fn set_ground_heights(
        &mut self,
        heights: &[f32],
        width: usize,
        depth: usize,
        spacing: [f64; 2],
        pose: &Pose,
    ) -> Result<(), DartError> {
        self.pin()
            .set_ground_heights(heights, width, depth, spacing, pose)?;
        Ok(())
    }

    /// Puts back the flat ground box; effective from the next [`Self::set_state`].
    pub(crate) fn set_ground_flat(&mut self) -> Result<(), DartError> {
        self.pin().set_ground_flat()?;
        Ok(())
    }

    /// Stores the joint torques applied during the next step only.
    pub(crate) fn set_joint_torques(&mut self, tau: &[f64]) -> Result<(), DartError> {
        self.pin().set_joint_torques(tau)?;
        Ok(())
    }

    /// One time step. `Ok(false)` when the state diverged: then only the joint readouts and
    /// [`Self::set_state`] may be called (anything that computes a transform would make DART
    /// abort the process).
    pub(crate) fn step(&mut self) -> Result<bool, DartError> {
        Ok(self.pin().step()?)
    }

    /// Joint positions; `out.len()` must equal [`Self::num_joints`].
    pub(crate) fn joint_positions(&self, out: &mut [f64]) {
        assert_eq!(out.len(), self.num_joints, "joint_positions: wrong length");
        self.get().joint_positions(out);
    }

    /// Joint velocities; `out.len()` must equal [`Self::num_joints`].
    pub(crate) fn joint_velocities(&self, out: &mut [f64]) {
        assert_eq!(out.len(), self.num_joints, "joint_velocities: wrong length");
        self.get().joint_velocities(out);
    }

    /// Root body pose and velocity, world frame.
    pub(crate) fn base_state(&self) -> BaseState {
        self.get().base_state()
    }

    /// World pose of every body frame, 7 values per body (x, y, z, qw, qx, qy, qz);
    /// `out.len()` must be 7 × the number of bodies.
    pub(crate) fn body_poses(&self, out: &mut [f64]) {
        assert_eq!(out.len(), 7 * self.num_bodies, "body_poses: wrong length");
        self.get().body_poses(out);
    }

    /// Total mass of the robot as DART holds it (kg).
    pub(crate) fn total_mass(&self) -> f64 {
        self.get().total_mass()
    }

    /// Sets the friction coefficient of every shape, the ground's included.
    pub(crate) fn set_friction(&mut self, friction: f64) -> Result<(), DartError> {
        self.pin().set_friction(friction)?;
        Ok(())
    }

    /// Sets the restitution coefficient of every shape, the ground's included.
    pub(crate) fn set_restitution(&mut self, restitution: f64) -> Result<(), DartError> {
        self.pin().set_restitution(restitution)?;
        Ok(())
    }

    /// Sets body `body`'s mass properties (description frame).
    pub(crate) fn set_inertial(
        &mut self,
        body: usize,
        inertial: &Inertial,
    ) -> Result<(), DartError> {
        self.pin().set_inertial(body, inertial)?;
        Ok(())
    }

    /// Body `body`'s mass properties as DART holds them; `body` must be a body index.
    pub(crate) fn inertial(&self, body: usize) -> Inertial {
        assert!(body < self.num_bodies, "inertial: body {body} out of range");
        self.get().inertial(body)
    }

    /// Sets actuated joint `joint`'s viscous damping.
    pub(crate) fn set_joint_damping(
        &mut self,
        joint: usize,
        damping: f64,
    ) -> Result<(), DartError> {
        self.pin().set_joint_damping(joint, damping)?;
        Ok(())
    }

    /// Adds `dv` (world frame) to the root's linear velocity now.
    pub(crate) fn add_base_velocity(&mut self, dv: [f64; 3]) -> Result<(), DartError> {
        self.pin().add_base_velocity(&dv)?;
        Ok(())
    }

    /// Contact flag per tracked link; `out.len()` must equal the description's `num_tracked`.
    pub(crate) fn contacts(&self, out: &mut [bool]) {
        assert_eq!(out.len(), self.num_tracked, "contacts: wrong length");
        self.get().contacts(out);
    }

    /// Touching or penetrating contact points in the last step.
    pub(crate) fn num_contacts(&self) -> usize {
        self.get().num_contacts()
    }

    /// Simulated time since the last `set_state` (s).
    pub(crate) fn time(&self) -> f64 {
        self.get().time()
    }
}

#[cfg(test)]
mod tests {
    //! Behaviour of the bridge on small hand-made worlds: shapes rest where geometry says,
    //! contacts are reported only on touch, limits hold, errors name the culprit, resets are
    //! bitwise.
    #![allow(clippy::unwrap_used)]

    use hyq_physics::na::{Quaternion, UnitQuaternion, Vector3};

    use super::*;

    fn world(num_tracked: u32) -> WorldDesc {
        WorldDesc {
            dt: 0.001,
            gravity: [0.0, 0.0, -9.81],
            friction: 1.0,
            restitution: 0.0,
            world_friction_axes: false,
            ground_height: 0.0,
            ground_half_extent: 50.0,
            num_tracked,
        }
    }

    fn root(mass: f64) -> BodyDesc {
        BodyDesc {
            name: "root".into(),
            parent: -1,
            joint_kind: JointKind::Free,
            joint_name: "root_joint".into(),
            joint_index: 0,
            joint_origin: Pose::IDENTITY,
            axis: [0.0; 3],
            lower: 0.0,
            upper: 0.0,
            damping: 0.0,
            mass,
            com: [0.0; 3],
            inertia: [0.1, 0.1, 0.1, 0.0, 0.0, 0.0],
        }
    }

    fn shape(kind: ShapeKind, size: [f64; 3], pose: Pose, tracked: i32) -> ShapeDesc {
        ShapeDesc {
            body: 0,
            kind,
            size,
            pose,
            tracked,
        }
    }

    fn at(z: f64) -> BaseState {
        BaseState {
            position: [0.0, 0.0, z],
            orientation: [1.0, 0.0, 0.0, 0.0],
            ..BaseState::default()
        }
    }

    fn run(sim: &mut Sim, steps: usize) {
        for _ in 0..steps {
            assert!(sim.step().unwrap());
        }
    }

    /// Rotation of `angle` about the y axis, as (w, x, y, z).
    fn about_y(angle: f64) -> [f64; 4] {
        [(angle / 2.0).cos(), 0.0, (angle / 2.0).sin(), 0.0]
    }

    #[test]
    fn every_shape_kind_rests_on_the_ground_at_its_geometric_height() {
        // A capsule lying along x: its z axis rotated by 90° about y.
        let lying = Pose {
            translation: [0.0; 3],
            rotation: about_y(std::f64::consts::FRAC_PI_2),
        };
        let cases = [
            (
                shape(ShapeKind::Sphere, [0.05, 0.0, 0.0], Pose::IDENTITY, 0),
                0.05,
            ),
            (
                shape(ShapeKind::Box, [0.2, 0.1, 0.05], Pose::IDENTITY, 0),
                0.05,
            ),
            (shape(ShapeKind::Capsule, [0.04, 0.15, 0.0], lying, 0), 0.04),
            (
                shape(ShapeKind::Cylinder, [0.04, 0.15, 0.0], lying, 0),
                0.04,
            ),
        ];
        for (s, rest) in cases {
            let mut sim = Sim::new(&[root(2.0)], &[s], &world(1)).unwrap();
            sim.set_state(&at(rest + 0.02), &[], &[]).unwrap();
            let mut flags = [true];
            assert!(sim.step().unwrap());
            sim.contacts(&mut flags);
            assert!(
                !flags[0],
                "{:?} in contact while 2 cm above the ground",
                s.kind
            );
            run(&mut sim, 1500);
            sim.contacts(&mut flags);
            let z = sim.base_state().position[2];
            assert!(flags[0], "{:?} resting but no contact", s.kind);
            assert!(
                (z - rest).abs() < 2e-3,
                "{:?} rests at z = {z}, geometry says {rest}",
                s.kind
            );
        }
    }

    #[test]
    fn shapes_hovering_within_bullets_contact_margin_are_not_in_contact() {
        // Bullet keeps manifold points up to a few centimetres apart, and its plane shape
        // reported a box 14 mm above it as touching; against the ground box, only touching
        // counts, for every shape kind and orientation the robot uses.
        let tilted = Pose {
            translation: [0.0; 3],
            rotation: about_y(0.4),
        };
        let lying = Pose {
            translation: [0.0; 3],
            rotation: about_y(std::f64::consts::FRAC_PI_2),
        };
        let cases = [
            (ShapeKind::Sphere, [0.05, 0.0, 0.0], Pose::IDENTITY),
            (ShapeKind::Box, [0.2, 0.1, 0.05], Pose::IDENTITY),
            (ShapeKind::Box, [0.2, 0.1, 0.05], tilted),
            (ShapeKind::Capsule, [0.04, 0.15, 0.0], lying),
            (ShapeKind::Capsule, [0.04, 0.15, 0.0], tilted),
            (ShapeKind::Cylinder, [0.04, 0.15, 0.0], lying),
        ];
        let mut w = world(1);
        w.gravity = [0.0; 3];
        for (kind, size, pose) in cases {
            for gap in [0.003, 0.0005] {
                let s = shape(kind, size, pose, 0);
                let mut sim = Sim::new(&[root(1.0)], &[s], &w).unwrap();
                // Place the shape's lowest point `gap` above the ground.
                sim.set_state(&at(1.0), &[], &[]).unwrap();
                let lowest = lowest_point(kind, size, &pose) + 1.0;
                let z0 = 1.0 - lowest + gap;
                sim.set_state(&at(z0), &[], &[]).unwrap();
                run(&mut sim, 10);
                let mut flags = [true];
                sim.contacts(&mut flags);
                assert!(!flags[0], "{kind:?} {gap} m above the ground in contact");
                assert_eq!(sim.num_contacts(), 0, "{kind:?} {gap} m above the ground");
                let z = sim.base_state().position[2];
                assert!(
                    (z - z0).abs() < 1e-12,
                    "nothing pushed the {kind:?}: z = {z}, was {z0}"
                );
            }
        }
    }

    /// Lowest z of a shape whose body frame is at the origin (rotation about y only).
    fn lowest_point(kind: ShapeKind, size: [f64; 3], pose: &Pose) -> f64 {
        let (w, y) = (pose.rotation[0], pose.rotation[2]);
        let angle = 2.0 * y.atan2(w);
        let (sin, cos) = (angle.sin().abs(), angle.cos().abs());
        match kind {
            ShapeKind::Sphere => -size[0],
            ShapeKind::Box => -(size[0] * sin + size[2] * cos),
            ShapeKind::Capsule => -(size[1] * cos + size[0]),
            _ => -(size[1] * cos + size[0] * sin),
        }
    }

    #[test]
    fn contact_flags_map_shapes_to_their_tracked_link() {
        // Two spheres on one body, tracked as links 0 and 1; one untracked sphere. Tilted so
        // only the first touches.
        let s0 = shape(
            ShapeKind::Sphere,
            [0.05, 0.0, 0.0],
            Pose {
                translation: [0.0, 0.0, -0.1],
                rotation: [1.0, 0.0, 0.0, 0.0],
            },
            0,
        );
        let s1 = shape(
            ShapeKind::Sphere,
            [0.05, 0.0, 0.0],
            Pose {
                translation: [0.0, 0.0, 0.3],
                rotation: [1.0, 0.0, 0.0, 0.0],
            },
            1,
        );
        let untracked = shape(
            ShapeKind::Sphere,
            [0.05, 0.0, 0.0],
            Pose {
                translation: [0.2, 0.0, -0.1],
                rotation: [1.0, 0.0, 0.0, 0.0],
            },
            -1,
        );
        let mut w = world(2);
        w.gravity = [0.0; 3];
        let mut sim = Sim::new(&[root(1.0)], &[s0, s1, untracked], &w).unwrap();
        // Sphere 0 and the untracked sphere dip 1 mm into the ground.
        sim.set_state(&at(0.149), &[], &[]).unwrap();
        assert!(sim.step().unwrap());
        let mut flags = [false; 2];
        sim.contacts(&mut flags);
        assert_eq!(flags, [true, false]);
        assert!(sim.num_contacts() >= 2, "untracked sphere touches too");
    }

    /// A heavy base resting on the ground with a light arm on a revolute joint about y.
    fn arm(lower: f64, upper: f64) -> (Vec<BodyDesc>, Vec<ShapeDesc>) {
        let base = root(50.0);
        let arm = BodyDesc {
            name: "arm".into(),
            parent: 0,
            joint_kind: JointKind::Revolute,
            joint_name: "arm_joint".into(),
            joint_index: 0,
            joint_origin: Pose {
                translation: [0.0, 0.0, 0.3],
                rotation: [1.0, 0.0, 0.0, 0.0],
            },
            axis: [0.0, 1.0, 0.0],
            lower,
            upper,
            damping: 0.0,
            mass: 0.5,
            com: [0.2, 0.0, 0.0],
            inertia: [1e-4, 3e-3, 3e-3, 0.0, 0.0, 0.0],
        };
        let feet = shape(ShapeKind::Box, [0.3, 0.3, 0.05], Pose::IDENTITY, 0);
        (vec![base, arm], vec![feet])
    }

    #[test]
    fn position_limits_hold_and_velocity_limits_are_left_to_the_actuator() {
        let (bodies, shapes) = arm(-0.5, 0.5);
        let mut sim = Sim::new(&bodies, &shapes, &world(1)).unwrap();
        sim.set_state(&at(0.05), &[0.0], &[0.0]).unwrap();
        let (mut q, mut qd) = ([0.0], [0.0]);
        let (mut q_max, mut qd_max) = (f64::MIN, 0.0_f64);
        for _ in 0..1000 {
            sim.set_joint_torques(&[20.0]).unwrap();
            assert!(sim.step().unwrap());
            sim.joint_positions(&mut q);
            sim.joint_velocities(&mut qd);
            q_max = q_max.max(q[0]);
            qd_max = qd_max.max(qd[0].abs());
        }
        assert!(q_max <= 0.5 + 1e-6, "upper limit 0.5 exceeded: {q_max}");
        assert!(
            q[0] > 0.5 - 1e-3,
            "arm pushed to its limit rests there: {}",
            q[0]
        );
        // 20 N·m on ~0.023 kg·m² over 0.5 rad reaches ~30 rad/s: DART's own velocity limit is
        // off, so nothing clips it at the URDF's 12 rad/s.
        assert!(qd_max > 15.0, "peak joint speed {qd_max}");
    }

    #[test]
    fn base_state_round_trips_through_set_state() {
        let (bodies, shapes) = arm(-0.5, 0.5);
        let mut w = world(1);
        w.gravity = [0.0; 3];
        let mut sim = Sim::new(&bodies, &shapes, &w).unwrap();
        let half = 0.4_f64;
        let n = (1.0_f64 + 4.0 + 9.0).sqrt();
        let (s, c) = half.sin_cos();
        let base = BaseState {
            position: [1.0, -2.0, 3.0],
            orientation: [c, s / n, 2.0 * s / n, -3.0 * s / n],
            linear_velocity: [0.3, -0.2, 0.1],
            angular_velocity: [-1.0, 0.5, 2.0],
        };
        sim.set_state(&base, &[0.25], &[-1.5]).unwrap();
        let got = sim.base_state();
        for i in 0..3 {
            assert!((got.position[i] - base.position[i]).abs() < 1e-12);
            assert!((got.linear_velocity[i] - base.linear_velocity[i]).abs() < 1e-12);
            assert!((got.angular_velocity[i] - base.angular_velocity[i]).abs() < 1e-12);
        }
        for i in 0..4 {
            assert!((got.orientation[i] - base.orientation[i]).abs() < 1e-12);
        }
        let (mut q, mut qd) = ([0.0], [0.0]);
        sim.joint_positions(&mut q);
        sim.joint_velocities(&mut qd);
        assert_eq!((q[0], qd[0]), (0.25, -1.5));
        assert_eq!(sim.time(), 0.0);
    }

    fn trace(sim: &mut Sim, steps: usize) -> Vec<u64> {
        let mut out = Vec::new();
        let (mut q, mut qd) = ([0.0], [0.0]);
        for k in 0..steps {
            let tau = if (k / 50) % 2 == 0 { 15.0 } else { -15.0 };
            sim.set_joint_torques(&[tau]).unwrap();
            assert!(sim.step().unwrap());
            sim.joint_positions(&mut q);
            sim.joint_velocities(&mut qd);
            let b = sim.base_state();
            out.extend([q[0], qd[0]].iter().map(|v| v.to_bits()));
            out.extend(b.position.iter().chain(&b.orientation).map(|v| v.to_bits()));
            out.extend(b.linear_velocity.iter().map(|v| v.to_bits()));
        }
        out
    }

    #[test]
    fn set_state_after_a_contact_rich_run_replays_a_fresh_world_bitwise() {
        let (bodies, shapes) = arm(-1.0, 1.0);
        let start = at(0.06);
        let mut fresh = Sim::new(&bodies, &shapes, &world(1)).unwrap();
        fresh.set_state(&start, &[0.0], &[0.0]).unwrap();
        let reference = trace(&mut fresh, 600);

        let mut reused = Sim::new(&bodies, &shapes, &world(1)).unwrap();
        reused.set_state(&at(0.2), &[0.3], &[1.0]).unwrap();
        trace(&mut reused, 777);
        reused.set_state(&start, &[0.0], &[0.0]).unwrap();
        let replay = trace(&mut reused, 600);
        let first_difference = replay.iter().zip(&reference).position(|(a, b)| a != b);
        assert_eq!(
            first_difference, None,
            "replay diverged (index into the trace)"
        );
    }

    #[test]
    fn bad_descriptions_are_errors_that_name_the_culprit() {
        let mut zero_mass = root(1.0);
        zero_mass.mass = 0.0;
        let err = Sim::new(&[zero_mass], &[], &world(0))
            .unwrap_err()
            .to_string();
        assert!(err.contains("body 'root'") && err.contains("mass"), "{err}");

        let (mut bodies, shapes) = arm(0.5, -0.5);
        let err = Sim::new(&bodies, &shapes, &world(1))
            .unwrap_err()
            .to_string();
        assert!(err.contains("arm_joint") && err.contains("limits"), "{err}");

        bodies[1].lower = -0.5;
        bodies[1].upper = 0.5;
        bodies[1].joint_origin.rotation = [1.0, 1.0, 0.0, 0.0];
        let err = Sim::new(&bodies, &shapes, &world(1))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("arm_joint") && err.contains("unit length"),
            "{err}"
        );

        let (bodies, shapes) = arm(-0.5, 0.5);
        let err = Sim::new(&bodies, &shapes, &world(0))
            .unwrap_err()
            .to_string();
        assert!(err.contains("shape 0") && err.contains("tracked"), "{err}");

        let mut sim = Sim::new(&bodies, &shapes, &world(1)).unwrap();
        let err = sim.set_joint_torques(&[1.0, 2.0]).unwrap_err().to_string();
        assert!(err.contains("expected 1 torques, got 2"), "{err}");
        let err = sim
            .set_state(&at(f64::NAN), &[0.0], &[0.0])
            .unwrap_err()
            .to_string();
        assert!(err.contains("translation must be finite"), "{err}");
    }

    #[test]
    fn a_free_body_flies_its_centre_of_mass_straight_whatever_its_frame() {
        // DART integrates a free body at its body frame's origin; the bridge puts the root's
        // frame at its centre of mass, so a tumbling body's centre of mass keeps a straight
        // line (with the frame at the URDF origin, 6 cm off, it drifted 5.5e-5 m in 1 s).
        for com in [[0.0; 3], [0.056, 0.0215, 0.0036]] {
            let mut body = root(61.0);
            body.com = com;
            body.inertia = [1.5, 5.0, 5.5, 0.0, 0.0, 0.0];
            let mut w = world(0);
            w.gravity = [0.0; 3];
            let mut sim = Sim::new(&[body], &[], &w).unwrap();
            let start = BaseState {
                position: [0.0, 0.0, 3.0],
                orientation: [1.0, 0.0, 0.0, 0.0],
                linear_velocity: [1.0, -0.3, 0.5],
                angular_velocity: [0.5, -0.8, 4.0],
            };
            sim.set_state(&start, &[], &[]).unwrap();
            let centre = |sim: &Sim| {
                let mut p = [0.0; 7];
                sim.body_poses(&mut p);
                let q = UnitQuaternion::from_quaternion(Quaternion::new(p[3], p[4], p[5], p[6]));
                Vector3::new(p[0], p[1], p[2]) + q * Vector3::from(com)
            };
            let c0 = centre(&sim);
            let v = Vector3::from(start.linear_velocity)
                + Vector3::from(start.angular_velocity).cross(&Vector3::from(com));
            let mut worst: f64 = 0.0;
            for n in 1..=1000 {
                assert!(sim.step().unwrap());
                let expected = c0 + v * (f64::from(n) * w.dt);
                worst = worst.max((centre(&sim) - expected).norm());
            }
            assert!(
                worst < 1e-9,
                "com {com:?}: centre of mass drifted {worst} m"
            );
        }
    }

    #[test]
    fn friction_is_a_pyramid_along_the_world_axes() {
        // A box sliding on the ground (mu = 1) decelerates at mu g along x or y, as under a
        // Coulomb cone, but at sqrt(2) mu g along the diagonal: DART bounds the friction along
        // two tangent directions (world x and y on flat ground) separately.
        let decel = |dir: [f64; 2]| {
            let s = shape(ShapeKind::Box, [0.2, 0.2, 0.05], Pose::IDENTITY, 0);
            let mut sim = Sim::new(&[root(10.0)], &[s], &world(1)).unwrap();
            let mut start = at(0.05);
            start.linear_velocity = [dir[0], dir[1], 0.0];
            sim.set_state(&start, &[], &[]).unwrap();
            run(&mut sim, 20);
            let v0 = sim.base_state().linear_velocity;
            run(&mut sim, 50);
            let v1 = sim.base_state().linear_velocity;
            let speed = |v: [f64; 3]| v[0].hypot(v[1]);
            (speed(v0) - speed(v1)) / 0.05
        };
        let g = 9.81;
        let along_x = decel([1.0, 0.0]);
        let along_y = decel([0.0, 1.0]);
        let diagonal = decel([std::f64::consts::FRAC_1_SQRT_2; 2]);
        assert!((along_x / g - 1.0).abs() < 0.02, "x: {along_x} m/s²");
        assert!((along_y / g - 1.0).abs() < 0.02, "y: {along_y} m/s²");
        assert!(
            (diagonal / g - std::f64::consts::SQRT_2).abs() < 0.03,
            "diagonal: {diagonal} m/s²"
        );
    }
}
