//! The one `#[cxx::bridge]` of the project: the boundary between Rust and the C++ that owns a DART
//! world (`include/hyq_dart.h`, `src/hyq_dart.cc`).
//!
//! Only plain data crosses: the shared structs below, `f64`/`bool` slices and one opaque handle.
//! This file is kept small on purpose: editing it re-runs the build script, which recompiles all
//! C++ of the crate.

// cxx expands this module into `unsafe` FFI glue; the crate's lints deny `unsafe_code`
// everywhere else.
#[allow(unsafe_code)]
#[cxx::bridge(namespace = "hyq_dart")]
pub(crate) mod ffi {
    // ---------------------------------------------------------------------------------------
    // Shared structs: plain data, laid out identically on both sides.
    // ---------------------------------------------------------------------------------------

    /// How a body hangs from its parent.
    #[derive(Debug)]
    enum JointKind {
        /// Six-DOF floating joint to the world (only the root body).
        Free,
        /// One rotational DOF about `BodyDesc::axis`.
        Revolute,
        /// Rigidly welded to the parent.
        Fixed,
    }

    /// Collision primitive.
    #[derive(Debug)]
    enum ShapeKind {
        /// Box; `size` = half extents (m).
        Box,
        /// Sphere; `size[0]` = radius (m).
        Sphere,
        /// Capsule along the shape frame's z axis; `size[0]` = radius, `size[1]` = half the
        /// distance between the cap centres (m).
        Capsule,
        /// Cylinder along the shape frame's z axis; `size[0]` = radius, `size[1]` = half its
        /// length (m).
        Cylinder,
    }

    /// A rigid transform: translation (m) and unit quaternion (w, x, y, z).
    #[derive(Debug, Clone, Copy, PartialEq)]
    struct Pose {
        translation: [f64; 3],
        rotation: [f64; 4],
    }

    /// One rigid body and the joint that attaches it to its parent.
    #[derive(Debug, Clone)]
    struct BodyDesc {
        /// Body name, unique.
        name: String,
        /// Index of the parent body in the body list (lower than this body's index), or -1 for
        /// the root, which must be the first body and have a `Free` joint.
        parent: i32,
        joint_kind: JointKind,
        /// Joint name, unique.
        joint_name: String,
        /// Revolute only: the joint's slot in the actuated-joint order used by every slice
        /// (torques, positions, velocities); the slots of all revolute joints are 0..n.
        joint_index: u32,
        /// Joint frame (= this body's frame at zero joint angle) in the parent body's frame.
        joint_origin: Pose,
        /// Rotation axis in this body's frame, unit length (revolute only).
        axis: [f64; 3],
        /// Position limits (rad, revolute only), enforced as hard constraints.
        lower: f64,
        upper: f64,
        /// Viscous joint damping (N·m·s/rad, revolute only), handled by DART.
        damping: f64,
        /// Mass (kg), > 0.
        mass: f64,
        /// Centre of mass in this body's frame (m).
        com: [f64; 3],
        /// Inertia tensor about the centre of mass, in this body's axes (kg·m²):
        /// ixx, iyy, izz, ixy, ixz, iyz.
        inertia: [f64; 6],
    }

    /// One collision shape rigidly attached to a body.
    #[derive(Debug, Clone, Copy)]
    struct ShapeDesc {
        /// Index of the body in the body list.
        body: u32,
        kind: ShapeKind,
        size: [f64; 3],
        /// Shape frame in the body's frame.
        pose: Pose,
        /// Index of the tracked link whose contact flag this shape sets, or -1.
        tracked: i32,
    }

    /// World-wide settings.
    #[derive(Debug, Clone, Copy)]
    struct WorldDesc {
        /// Physics time step (s), > 0.
        dt: f64,
        /// Gravity (m/s²), world frame.
        gravity: [f64; 3],
        /// Coulomb friction coefficient of every shape, ground included (≥ 0).
        friction: f64,
        /// Restitution coefficient of every shape, ground included (in [0, 1]).
        restitution: f64,
        /// Every shape's first friction direction is the world's x axis, so each contact's
        /// friction pyramid lies along world x and y; false leaves DART's default (directions
        /// built from the contact normal).
        world_friction_axes: bool,
        /// The ground is a static box whose top face is the plane z = `ground_height`.
        ground_height: f64,
        /// Half the side of the ground box (m), > 0.
        ground_half_extent: f64,
        /// Number of tracked links (contact flags).
        num_tracked: u32,
    }

    /// Root body state, world frame: pose of the body frame, classical linear velocity of its
    /// origin and angular velocity.
    #[derive(Debug, Clone, Copy, PartialEq, Default)]
    struct BaseState {
        position: [f64; 3],
        /// Unit quaternion (w, x, y, z).
        orientation: [f64; 4],
        linear_velocity: [f64; 3],
        angular_velocity: [f64; 3],
    }

    /// A body's mass properties in its description frame.
    #[derive(Debug, Clone, Copy, PartialEq, Default)]
    struct Inertial {
        /// Mass (kg), > 0.
        mass: f64,
        /// Centre of mass in the body's frame (m).
        com: [f64; 3],
        /// Inertia tensor about the centre of mass, in the body's axes (kg·m²): ixx, iyy, izz,
        /// ixy, ixz, iyz.
        inertia: [f64; 6],
    }

    // ---------------------------------------------------------------------------------------
    // Rust items exposed to C++: none. C++ never calls back into Rust.
    // ---------------------------------------------------------------------------------------

    // ---------------------------------------------------------------------------------------
    // C++ items exposed to Rust: the opaque world handle and its methods. Every function that
    // can fail returns `Result` (a C++ exception becomes `Err`); the readouts cannot fail.
    // ---------------------------------------------------------------------------------------
    unsafe extern "C++" {
        include!("hyq-dart/include/hyq_dart.h");

        /// One DART world (robot + ground), owned through `UniquePtr`.
        type Sim;

        /// Builds a world from the description; `Err` names what DART or the description refused.
        fn new_sim(
            bodies: &[BodyDesc],
            shapes: &[ShapeDesc],
            world: &WorldDesc,
        ) -> Result<UniquePtr<Sim>>;

        /// Sets root state and actuated-joint positions/velocities (revolute joints in body order)
        /// and resets everything else to the freshly built state.
        fn set_state(self: Pin<&mut Sim>, base: &BaseState, q: &[f64], qd: &[f64]) -> Result<()>;
        /// Replaces the ground with one height field (DART's `HeightmapShapef`): `heights` is
        /// its matrix row after row, `depth` rows of `width` values, sample `spacing` (m) apart
        /// along the shape's x (within a row) and y (across rows), placed at `pose`. Takes effect
        /// from the next `set_state`.
        fn set_ground_heights(
            self: Pin<&mut Sim>,
            heights: &[f32],
            width: usize,
            depth: usize,
            spacing: [f64; 2],
            pose: &Pose,
        ) -> Result<()>;
        /// Puts back the flat ground box of the description. Takes effect from the next
        /// `set_state`.
        fn set_ground_flat(self: Pin<&mut Sim>) -> Result<()>;
        /// Stores the actuated-joint torques applied during the next step only.
        fn set_joint_torques(self: Pin<&mut Sim>, tau: &[f64]) -> Result<()>;
        /// Advances the world by one time step; `Ok(false)` when the state diverged (non-finite
        /// or absurdly large). A diverged world must not be read except for joint values, and
        /// must be given a new state before it is stepped again: DART aborts the process when
        /// it computes a transform from a non-finite state.
        fn step(self: Pin<&mut Sim>) -> Result<bool>;

        /// Actuated-joint positions (rad).
        fn joint_positions(self: &Sim, out: &mut [f64]);
        /// Actuated-joint velocities (rad/s).
        fn joint_velocities(self: &Sim, out: &mut [f64]);
        /// Root body state.
        fn base_state(self: &Sim) -> BaseState;
        /// World pose of every body frame, body-list order, 7 values each: x, y, z, then the
        /// quaternion w, x, y, z.
        fn body_poses(self: &Sim, out: &mut [f64]);
        /// Total mass of the robot's bodies (kg) as DART holds them.
        fn total_mass(self: &Sim) -> f64;
        /// Sets the friction coefficient of every shape, the ground's included (set_state must
        /// follow before a step, as for the three setters below).
        fn set_friction(self: Pin<&mut Sim>, friction: f64) -> Result<()>;
        /// Sets the restitution coefficient of every shape, the ground's included (DART takes
        /// the product of a contact's two).
        fn set_restitution(self: Pin<&mut Sim>, restitution: f64) -> Result<()>;
        /// Sets a body's mass properties (description frame); the root's frames follow its
        /// centre of mass.
        fn set_inertial(self: Pin<&mut Sim>, body: usize, inertial: &Inertial) -> Result<()>;
        /// A body's mass properties as DART holds them (description frame).
        fn inertial(self: &Sim, body: usize) -> Inertial;
        /// Sets an actuated joint's viscous damping (N·m·s/rad).
        fn set_joint_damping(self: Pin<&mut Sim>, joint: usize, damping: f64) -> Result<()>;
        /// Adds three values (world frame, m/s) to the root's linear velocity now.
        fn add_base_velocity(self: Pin<&mut Sim>, dv: &[f64]) -> Result<()>;
        /// Per tracked link: one of its shapes touched or penetrated the ground in the contacts
        /// of the last step.
        fn contacts(self: &Sim, out: &mut [bool]);
        /// Touching or penetrating contact points in the last step (Bullet also reports points
        /// up to about a millimetre apart; those are not counted).
        fn num_contacts(self: &Sim) -> usize;
        /// Simulated time since the last `set_state` (s).
        fn time(self: &Sim) -> f64;
    }
}

// SAFETY: a `Sim` owns its whole DART world (skeletons, shapes, solver, detector); no two `Sim`s
// share mutable state, and DART's process-wide settings (contact and joint-limit constraint
// parameters) are only read. Moving a `Sim` to another thread is therefore sound. It is not
// `Sync`: DART updates cached kinematics inside `const` getters, so two threads must never read
// the same `Sim` at once.
#[allow(unsafe_code)]
unsafe impl Send for ffi::Sim {}
