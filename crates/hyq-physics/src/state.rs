//! The plain data that crosses the physics seam: the engine-independent settings
//! ([`PhysicsParams`]) and the robot's state ([`RobotState`], [`TrunkState`]), with the spawn
//! state a model starts from ([`RobotModel::spawn_state`]).
//!
//! They sit apart from the trait ([`crate::Backend`]) so that the model, the per-episode
//! dynamics and the terrain can use them without importing the seam: this module depends on
//! the model, and nothing it depends on depends on it.

use nalgebra::{Isometry3, Vector3};
use serde::{Deserialize, Serialize};

use crate::bounds::short;
use crate::error::PhysicsError;
use crate::model::RobotModel;

/// Engine-independent physics settings (`[physics]` in an environment's TOML).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PhysicsParams {
    /// Length of one physics sub-step (s) (default: 0.001).
    pub dt: f64,
    /// Gravity in the world frame (m/s²) (default: [0, 0, -9.81]).
    pub gravity: [f64; 3],
    /// Coulomb friction coefficient between any robot shape and the ground (default: 1.0, the
    /// upstream foot `lateral_friction` and Gazebo `mu`). Contacts are inelastic.
    pub ground_friction: f64,
    /// A tracked shape within this distance (m) of the ground, or penetrating it, counts as
    /// touching it even when it carries no load (default: 0.001).
    pub contact_distance: f64,
}

impl Default for PhysicsParams {
    fn default() -> Self {
        Self {
            dt: 0.001,
            gravity: [0.0, 0.0, -9.81],
            ground_friction: 1.0,
            contact_distance: 0.001,
        }
    }
}

impl PhysicsParams {
    /// Checks every field; the error names the first invalid one.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        let bad = |field: &'static str, value: String, reason: &'static str| {
            Err(PhysicsError::InvalidParam {
                field,
                value,
                reason,
            })
        };
        if !(self.dt.is_finite() && self.dt > 0.0 && self.dt <= 0.1) {
            return bad("dt", short(self.dt), "must be in (0, 0.1] s");
        }
        if !self.gravity.iter().all(|g| g.is_finite()) {
            return bad("gravity", format!("{:?}", self.gravity), "must be finite");
        }
        if !(self.ground_friction.is_finite() && self.ground_friction >= 0.0) {
            return bad(
                "ground_friction",
                short(self.ground_friction),
                "must be finite and non-negative",
            );
        }
        if !(self.contact_distance.is_finite() && self.contact_distance >= 0.0) {
            return bad(
                "contact_distance",
                short(self.contact_distance),
                "must be finite and non-negative (m)",
            );
        }
        Ok(())
    }
}

/// Pose and velocity of the trunk, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrunkState {
    /// Pose of the trunk's URDF link frame (not its centre of mass).
    pub pose: Isometry3<f64>,
    /// Linear velocity of the trunk frame's origin (m/s).
    pub linvel: Vector3<f64>,
    /// Angular velocity (rad/s).
    pub angvel: Vector3<f64>,
}

impl TrunkState {
    /// The trunk at rest at `pose`.
    pub fn at_rest(pose: Isometry3<f64>) -> Self {
        Self {
            pose,
            linvel: Vector3::zeros(),
            angvel: Vector3::zeros(),
        }
    }
}

/// The full state of the robot: trunk pose and velocity plus joint angles and speeds.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotState {
    /// The trunk (the free-floating root).
    pub trunk: TrunkState,
    /// Joint angles (rad), profile order.
    pub q: Vec<f64>,
    /// Joint speeds (rad/s), profile order.
    pub qd: Vec<f64>,
}

impl RobotState {
    /// The first non-finite value, named, if any.
    pub fn first_non_finite(&self, model: &RobotModel) -> Option<(String, f64)> {
        let t = &self.trunk;
        let q = t.pose.rotation.quaternion();
        let named: [(&str, f64); 13] = [
            ("trunk position x", t.pose.translation.x),
            ("trunk position y", t.pose.translation.y),
            ("trunk position z", t.pose.translation.z),
            ("trunk orientation w", q.w),
            ("trunk orientation x", q.i),
            ("trunk orientation y", q.j),
            ("trunk orientation z", q.k),
            ("trunk linear velocity x", t.linvel.x),
            ("trunk linear velocity y", t.linvel.y),
            ("trunk linear velocity z", t.linvel.z),
            ("trunk angular velocity x", t.angvel.x),
            ("trunk angular velocity y", t.angvel.y),
            ("trunk angular velocity z", t.angvel.z),
        ];
        if let Some((name, v)) = named.iter().find(|(_, v)| !v.is_finite()) {
            return Some(((*name).to_owned(), *v));
        }
        let joint_name = |i: usize| model.joints().get(i).map_or("?", |j| j.name.as_str());
        if let Some((i, v)) = self.q.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Some((format!("angle of joint {}", joint_name(i)), *v));
        }
        if let Some((i, v)) = self.qd.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Some((format!("speed of joint {}", joint_name(i)), *v));
        }
        None
    }

    /// Checks lengths, finiteness and that the orientation is a unit quaternion.
    pub fn validate(&self, model: &RobotModel) -> Result<(), PhysicsError> {
        let n = model.num_joints();
        for (what, got) in [
            ("joint angles", self.q.len()),
            ("joint speeds", self.qd.len()),
        ] {
            if got != n {
                return Err(PhysicsError::WrongLength {
                    what,
                    expected: n,
                    got,
                });
            }
        }
        if let Some((what, value)) = self.first_non_finite(model) {
            return Err(PhysicsError::NonFinite { what, value });
        }
        let norm = self.trunk.pose.rotation.quaternion().norm();
        if (norm - 1.0).abs() > 1e-6 {
            return Err(PhysicsError::InvalidState {
                what: "trunk orientation".into(),
                reason: format!("quaternion norm {norm} is not 1"),
            });
        }
        Ok(())
    }
}

impl RobotModel {
    /// The spawn state: trunk level at the spawn height above the world origin, joints at the
    /// standing pose, everything at rest.
    pub fn spawn_state(&self) -> RobotState {
        RobotState {
            trunk: TrunkState {
                pose: Isometry3::translation(0.0, 0.0, self.spawn_height()),
                linvel: Vector3::zeros(),
                angvel: Vector3::zeros(),
            },
            q: self.standing_pose().to_vec(),
            qd: vec![0.0; self.num_joints()],
        }
    }
}
