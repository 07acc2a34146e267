//! The physics seam of the HyQ environment, free of any physics engine.
//!
//! - [`RobotModel`]: a robot built once from a URDF and a robot [`Profile`], shared by every
//!   backend (`Arc<RobotModel>`): bodies with mass properties and primitive collision shapes,
//!   actuated joints in the profile's order, tracked bodies (feet, then the trunk), standing
//!   pose, spawn height, default gains, and forward kinematics.
//! - [`Backend`]: the trait a simulator implements (rapier in `hyq-rapier`, DART in
//!   `hyq-dart`, MuJoCo in `hyq-mujoco`; hyq-engines names them): build, set a state, apply
//!   joint torques, advance one sub-step, read joint and trunk state and real ground contacts.
//! - [`actuator`]: the joint PD law with effort and velocity limits, evaluated every sub-step in
//!   shared code ([`pd_substep`]), so every backend is driven identically.
//! - [`state`]: the plain data that crosses the seam: the engine-independent
//!   [`PhysicsParams`] and the robot's [`RobotState`].
//! - [`dynamics`]: per-episode variations of the physics as plain data (ground friction,
//!   masses, damping, the actuator's gains, limits and delay) with the rules that keep every
//!   drawn world physical; backends take them through [`Backend::set_dynamics`] and push the
//!   trunk with [`Backend::push_trunk`]. The environment draws them (nothing here is random).
//! - [`terrain`]: the ground: flat, or a height field from one grid of heights (generated
//!   rough ground, slopes and stairs, or a user's `.npy` or PNG file), the surface every backend
//!   builds from it, and how far a shape is above it.
//! - [`bounds`]: the one table of bounds every number of a robot is checked against, so that
//!   everything derived from it stays finite (in f64 and in f32); [`input`]: the size-capped
//!   reader every loader of a user's file goes through, and the checks made before a parser
//!   runs (XML nesting depth).
//! - [`bundled`]: the URDF robots shipped in `assets/` (HyQ, the default, and ANYmal C), usable
//!   from any directory, and [`resolve_robot`], which turns a robot choice (a bundled name or a
//!   profile path) into a model. The front ends resolve through `hyq_formats::robots::resolve`,
//!   which adds the MJCF robots (the bundled Go1, profiles naming an `.xml` file) and falls back
//!   to this one.
//!
//! Nothing here knows HyQ or any physics engine: robot names and counts come from the profile.
//! Beside this crate, `hyq-formats` writes a loaded robot as MJCF or URDF, and
//! `hyq-conformance` holds the test kit every backend runs.

pub mod actuator;
pub mod backend;
pub mod bounds;
pub mod bundled;
pub mod dynamics;
pub mod error;
pub mod inertia;
pub mod input;
pub mod model;
pub mod profile;
pub mod state;
pub mod terrain;

pub use actuator::{Actuator, PdScratch, apply_pd, apply_pd_to_valid_targets, pd_substep};
pub use backend::{Backend, check_joint_values};
pub use bundled::resolve as resolve_robot;
pub use dynamics::{
    ActuatorScales, ContactDraw, DrawRangeFault, DrawRanges, DrawnQuantity, Dynamics, DynamicsDraw,
    TargetDelay, check_draw_ranges,
};
pub use error::{ModelError, PhysicsError, one_line, printable};
pub use inertia::MassProperties;
pub use model::{Collision, Joint, Link, RobotModel, Shape, TrackedBody};
pub use model::{Gait, GaitLeg};
pub use profile::Profile;
pub use state::{PhysicsParams, RobotState, TrunkState};

pub use terrain::{HeightGrid, Terrain, TerrainError};

/// The linear-algebra crate of this API (`nalgebra`), re-exported so that callers use the
/// same version.
pub use nalgebra as na;
