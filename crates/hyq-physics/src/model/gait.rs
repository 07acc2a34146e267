//! The profile's `[gait]` table resolved against the model's joints: the facts a scripted gait
//! needs about a robot (which joints swing each leg, when, and how far), so that no gait code
//! knows a robot's joint names or leg count.

use std::collections::HashSet;

use super::Joint;
use super::profile_values::bounded;
use crate::bounds;
use crate::error::ModelError;
use crate::profile::{GaitEntry, Profile};

/// A scripted gait's description of the robot, checked against its joints.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Gait {
    /// Gait frequency (Hz): one full cycle of every leg.
    pub frequency_hz: f64,
    /// Hip swing amplitude (rad) about the standing angle.
    pub hip_amplitude: f64,
    /// Extra knee flexion (rad) at the middle of a leg's swing.
    pub knee_lift: f64,
    /// Time (s) over which the amplitudes ramp up from standing.
    pub ramp_s: f64,
    /// The legs, in profile order.
    pub legs: Vec<GaitLeg>,
}

/// One leg of a [`Gait`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct GaitLeg {
    /// Index (profile order) of the joint that swings the leg fore and aft.
    pub hip: usize,
    /// Index (profile order) of the joint that bends the knee.
    pub knee: usize,
    /// The leg's phase as a fraction of a cycle, in [0, 1).
    pub phase: f64,
}

impl Gait {
    /// Resolves `entry`'s joint names against `joints` (profile order) and checks its values.
    pub(super) fn resolve(
        entry: &GaitEntry,
        profile: &Profile,
        joints: &[Joint],
    ) -> Result<Self, ModelError> {
        let invalid = |field: String, reason: String| ModelError::InvalidProfile { field, reason };
        let frequency_hz = bounded(
            &bounds::GAIT_FREQUENCY,
            "gait.frequency_hz",
            entry.frequency_hz,
        )?;
        let hip_amplitude = bounded(
            &bounds::GAIT_HIP_AMPLITUDE,
            "gait.hip_amplitude",
            entry.hip_amplitude,
        )?;
        let knee_lift = bounded(&bounds::GAIT_KNEE_LIFT, "gait.knee_lift", entry.knee_lift)?;
        let ramp_s = bounded(&bounds::GAIT_RAMP, "gait.ramp_s", entry.ramp_s)?;
        if entry.legs.is_empty() {
            return Err(invalid("gait.legs".into(), "lists no leg".into()));
        }
        let names: Vec<&str> = profile.joints.iter().map(|j| j.name.as_str()).collect();
        let mut used: HashSet<usize> = HashSet::new();
        let mut legs = Vec::with_capacity(entry.legs.len());
        for (li, leg) in entry.legs.iter().enumerate() {
            let mut joint = |key: &str, name: &str| -> Result<usize, ModelError> {
                let field = format!("gait.legs[{li}].{key}");
                let Some(j) = joints.iter().position(|j| j.name == name) else {
                    return Err(invalid(
                        field,
                        format!(
                            "no joint named {name:?} in the profile's joints (one of {})",
                            names.join(", ")
                        ),
                    ));
                };
                if !used.insert(j) {
                    return Err(invalid(
                        field,
                        format!("joint {name:?} is already driven by another leg or role"),
                    ));
                }
                Ok(j)
            };
            let hip = joint("hip", &leg.hip)?;
            let knee = joint("knee", &leg.knee)?;
            bounded(
                &bounds::GAIT_PHASE,
                format!("gait.legs[{li}].phase"),
                leg.phase,
            )?;
            legs.push(GaitLeg {
                hip,
                knee,
                phase: leg.phase,
            });
        }
        Ok(Self {
            frequency_hz,
            hip_amplitude,
            knee_lift,
            ramp_s,
            legs,
        })
    }
}
