//! What reading an MJCF robot gives: the robot as a URDF description (the form the model is
//! built from), what URDF cannot hold (armature), the actuators, the keyframes, and the notes
//! on what was skipped.

use std::collections::HashMap;

/// An MJCF robot, read and checked, ready to become a [`hyq_physics::RobotModel`] with a
/// profile ([`MjcfRobot::model`](crate::mjcf_read::MjcfRobot::model)).
#[derive(Debug, Clone)]
pub struct MjcfRobot {
    /// The `<mujoco model>` name, if given.
    pub name: Option<String>,
    /// The robot as a URDF description: a link per body (named as the body), a revolute
    /// joint per hinge (named as the joint), a fixed joint (`<body>_fixed`) per body without
    /// one, a named collision per colliding geom. The root body is the free trunk.
    pub robot: urdf_rs::Robot,
    /// The root body's name (the trunk).
    pub root: String,
    /// Hinge joints in file order (the order of `qpos` after the free joint's seven numbers).
    pub joints: Vec<String>,
    /// Joint armature (kg·m²) by joint name, where non-zero.
    pub armature: HashMap<String, f64>,
    /// A joint's `actuatorfrcrange` (N·m) by joint name: its effort limit when no actuator
    /// gives one.
    pub joint_force: HashMap<String, [f64; 2]>,
    /// The actuators, in file order.
    pub actuators: Vec<Actuator>,
    /// The keyframes, in file order.
    pub keyframes: Vec<Keyframe>,
    /// What was skipped or left to the project's own settings, one line each.
    pub notes: Vec<String>,
}

/// What an MJCF actuator drives and how.
#[derive(Debug, Clone, PartialEq)]
pub struct Actuator {
    /// The actuator's name (MuJoCo's, or `actuator<i>` when unnamed).
    pub name: String,
    /// The hinge joint it drives.
    pub joint: String,
    /// Position servo or plain motor.
    pub kind: ActuatorKind,
    /// Force (torque, N·m) range, when limited.
    pub force_range: Option<[f64; 2]>,
    /// Control range (rad for a position servo, the control's units for a motor), when limited
    /// (`inheritrange` resolved to the joint's range).
    pub ctrl_range: Option<[f64; 2]>,
}

/// The kind of an MJCF actuator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ActuatorKind {
    /// `<position>`: a PD servo on the joint angle.
    Position {
        /// Proportional gain (N·m/rad).
        kp: f64,
        /// Derivative gain (N·m·s/rad).
        kv: f64,
    },
    /// `<motor>`: torque = gear × control.
    Motor {
        /// The gear ratio.
        gear: f64,
    },
}

/// An MJCF `<key>`.
#[derive(Debug, Clone, PartialEq)]
pub struct Keyframe {
    /// Its name (`key<i>` when unnamed).
    pub name: String,
    /// Generalised positions: the free joint's position and quaternion (w x y z), then the
    /// hinges in [`MjcfRobot::joints`] order; empty if not given.
    pub qpos: Vec<f64>,
    /// Controls, one per actuator; empty if not given.
    pub ctrl: Vec<f64>,
}
