//! The velocity task's observation rows: what both anchors give the policy beyond the spec's §3
//! rows (which already hold the joint angles and speeds, the contacts, the trunk's attitude,
//! acceleration and position). In SI units, unscaled and unclipped (legged_gym multiplies some
//! rows by fixed factors; Playground does not; a policy normalises its inputs itself).
//!
//! | rows | value | unit | bounds |
//! |---|---|---|---|
//! | `base_lin_vel_x`, `_y`, `_z` | Rᵀ v: the trunk frame origin's velocity in the trunk's frame | m/s | ±5 |
//! | `base_ang_vel_x`, `_y`, `_z` | Rᵀ ω: the trunk's angular velocity in its frame | rad/s | ±10 |
//! | `projected_gravity_x`, `_y`, `_z` | Rᵀ (0, 0, −1): gravity's direction in the trunk's frame | 1 | ±1 |
//! | `command_lin_vel_x`, `command_lin_vel_y`, `command_ang_vel_yaw` | the command (`[command]`) | m/s, rad/s | its configured range |
//! | `<joint>_offset` | q − q₀: the joint angle from the standing pose | rad | the joint's range minus q₀ |
//! | `<joint>_last_action` | the previous step's action (0 after reset) | the action's | the action space's |

use nalgebra::{UnitQuaternion, Vector3};

/// The bound of the body-frame linear velocity rows (m/s).
pub const LIN_VEL_BOUND: f64 = 5.0;
/// The bound of the body-frame angular velocity rows (rad/s).
pub const ANG_VEL_BOUND: f64 = 10.0;
/// The rows of the task's group before the per-joint rows: velocities, gravity, command.
pub const HEAD_ROWS: usize = 12;

/// A joint as the rows need it: name, limits, standing angle (rad) and action bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct JointRows<'a> {
    /// The joint's name.
    pub name: &'a str,
    /// Its range (rad).
    pub range: [f64; 2],
    /// Its standing angle q₀ (rad).
    pub standing: f64,
    /// Its action's bounds.
    pub action: [f64; 2],
}

/// The group's rows (name, min, max) for `joints` and the command `ranges` (observation order:
/// v_x, v_y, ω_z).
pub fn rows(joints: &[JointRows<'_>], ranges: [[f64; 2]; 3]) -> Vec<(String, f64, f64)> {
    let axes = ["x", "y", "z"];
    let mut out = Vec::with_capacity(HEAD_ROWS + 2 * joints.len());
    out.extend(axes.map(|a| (format!("base_lin_vel_{a}"), -LIN_VEL_BOUND, LIN_VEL_BOUND)));
    out.extend(axes.map(|a| (format!("base_ang_vel_{a}"), -ANG_VEL_BOUND, ANG_VEL_BOUND)));
    out.extend(axes.map(|a| (format!("projected_gravity_{a}"), -1.0, 1.0)));
    let names = [
        "command_lin_vel_x",
        "command_lin_vel_y",
        "command_ang_vel_yaw",
    ];
    out.extend(
        names
            .iter()
            .zip(ranges)
            .map(|(n, [lo, hi])| (n.to_string(), lo, hi)),
    );
    out.extend(joints.iter().map(|j| {
        (
            format!("{}_offset", j.name),
            j.range[0] - j.standing,
            j.range[1] - j.standing,
        )
    }));
    out.extend(
        joints
            .iter()
            .map(|j| (format!("{}_last_action", j.name), j.action[0], j.action[1])),
    );
    out
}

/// `v` (world frame) in the frame of `rotation`: Rᵀ v.
pub fn in_body_frame(rotation: &UnitQuaternion<f64>, v: &Vector3<f64>) -> [f64; 3] {
    (rotation.inverse() * v).into()
}

/// Gravity's direction in the frame of `rotation`: Rᵀ (0, 0, −1).
pub fn projected_gravity(rotation: &UnitQuaternion<f64>) -> [f64; 3] {
    in_body_frame(rotation, &Vector3::new(0.0, 0.0, -1.0))
}

/// What the group's rows hold on one step.
#[derive(Clone, Copy, Debug)]
pub struct GroupValues<'a> {
    /// Rᵀ v (m/s).
    pub lin_vel: [f64; 3],
    /// Rᵀ ω (rad/s).
    pub ang_vel: [f64; 3],
    /// Rᵀ (0, 0, −1).
    pub gravity: [f64; 3],
    /// The command, observation order.
    pub command: [f64; 3],
    /// q (rad).
    pub joint_angles: &'a [f64],
    /// q₀ (rad).
    pub standing: &'a [f64],
    /// The previous action.
    pub last_action: &'a [f64],
}

/// Writes the group's rows into `out` (exactly [`HEAD_ROWS`] + 2 × joints long). Allocates
/// nothing.
///
/// # Panics
/// If `out` has another length (a broken promise of the caller's layout).
pub fn write(v: &GroupValues<'_>, out: &mut [f64]) {
    let n = v.joint_angles.len();
    assert_eq!(out.len(), HEAD_ROWS + 2 * n, "the velocity group's width");
    let (head, joints) = out.split_at_mut(HEAD_ROWS);
    for (i, src) in [v.lin_vel, v.ang_vel, v.gravity, v.command]
        .iter()
        .enumerate()
    {
        head[3 * i..3 * i + 3].copy_from_slice(src);
    }
    let (offsets, actions) = joints.split_at_mut(n);
    for ((o, q), q0) in offsets.iter_mut().zip(v.joint_angles).zip(v.standing) {
        *o = q - q0;
    }
    actions.copy_from_slice(v.last_action);
}
