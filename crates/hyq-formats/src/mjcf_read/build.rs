//! An MJCF robot with a profile becomes a model: effort limits from the actuators, the
//! position servos' gains where the profile gives none per joint, armature after the build.

use hyq_physics::{ModelError, Profile, RobotModel};

use super::types::{ActuatorKind, MjcfRobot};

impl MjcfRobot {
    /// The model of this robot with `profile`, built as a URDF robot is (the profile's `urdf`
    /// path is not read).
    ///
    /// From the MJCF, beyond what a URDF gives: each joint's effort limit is its actuator's
    /// `forcerange` (a motor's: `gear` × its `ctrlrange`), else the joint's
    /// `actuatorfrcrange`; a `<position>` actuator's `kp` and `kv` (when positive) are the
    /// joint's gains unless the profile gives the joint its own; `armature` is kept. MJCF has
    /// no joint velocity limit: the profile must give each joint's `velocity`.
    pub fn model(&self, profile: &Profile) -> Result<RobotModel, ModelError> {
        let robot = self.urdf_description()?;
        let mut profile = profile.clone();
        for (i, entry) in profile.joints.iter_mut().enumerate() {
            if entry.velocity.is_none() {
                return Err(ModelError::InvalidProfile {
                    field: format!("joints[{i}].velocity"),
                    reason: "MJCF gives no joint velocity limit, so the profile must".to_owned(),
                });
            }
            let servo = self.actuators.iter().find_map(|a| match a.kind {
                ActuatorKind::Position { kp, kv } if a.joint == entry.urdf => Some((kp, kv)),
                _ => None,
            });
            if let Some((kp, kv)) = servo {
                entry.kp.get_or_insert(kp);
                if kv > 0.0 {
                    entry.kd.get_or_insert(kv);
                }
            }
        }
        let model = RobotModel::from_urdf_model(&robot, &profile)?;
        let armature: Vec<(usize, f64)> = model
            .joints()
            .iter()
            .enumerate()
            .filter_map(|(i, j)| self.armature.get(&j.urdf_name).map(|a| (i, *a)))
            .collect();
        model.with_joint_armature(&armature)
    }

    /// The URDF description the model is built from: [`MjcfRobot::robot`] with each joint's
    /// effort limit from the MJCF (see [`MjcfRobot::model`]).
    pub fn urdf_description(&self) -> Result<urdf_rs::Robot, ModelError> {
        let mut robot = self.robot.clone();
        for joint in robot.joints.iter_mut() {
            if let Some(effort) = self.effort(&joint.name)? {
                joint.limit.effort = effort;
            }
        }
        Ok(robot)
    }

    /// Joint `joint`'s effort limit (N·m) from the MJCF, if it gives one; an asymmetric range
    /// is refused (the model's limit is symmetric).
    fn effort(&self, joint: &str) -> Result<Option<f64>, ModelError> {
        let actuator = self.actuators.iter().find(|a| a.joint == joint);
        let (range, source) = match actuator {
            Some(a) if a.force_range.is_some() => (a.force_range, "its actuator's forcerange"),
            Some(a) => match (a.kind, a.ctrl_range) {
                (ActuatorKind::Motor { gear }, Some([lo, hi])) => {
                    (Some([gear * lo, gear * hi]), "its motor's gear × ctrlrange")
                }
                _ => (self.joint_force.get(joint).copied(), "its actuatorfrcrange"),
            },
            None => (self.joint_force.get(joint).copied(), "its actuatorfrcrange"),
        };
        let Some([lo, hi]) = range else {
            return Ok(None);
        };
        let (lo, hi) = (lo.min(hi), lo.max(hi));
        if (lo + hi).abs() > 1e-9 * hi.abs().max(1.0) {
            return Err(ModelError::InvalidJoint {
                joint: joint.to_owned(),
                reason: format!(
                    "{source} [{lo}, {hi}] is not symmetric about 0, and the effort limit here is"
                ),
            });
        }
        Ok(Some(hi))
    }
}
