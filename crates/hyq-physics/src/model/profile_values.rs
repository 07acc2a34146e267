//! Phase 0 of building a model: the profile's own values, those that need no URDF, each
//! checked against its row of [`crate::bounds`].

use crate::bounds::{self, Bound, short};
use crate::error::ModelError;
use crate::profile::{ObservationBounds, Profile};

/// `value` checked against `bound`, as an error naming `field`.
pub(super) fn bounded(
    bound: &Bound,
    field: impl Into<String>,
    value: f64,
) -> Result<f64, ModelError> {
    bound
        .check(value)
        .map_err(|reason| ModelError::InvalidProfile {
            field: field.into(),
            reason,
        })
}

/// A profile name checked by [`bounds::check_name`], as an error naming `field`.
fn named(field: impl Into<String>, name: &str) -> Result<(), ModelError> {
    bounds::check_name(name)
        .map(|_| ())
        .map_err(|reason| ModelError::InvalidProfile {
            field: field.into(),
            reason: format!("name {reason}"),
        })
}

/// Checks the profile's own values (those that need no URDF): its names, heights, gains and
/// standing angles.
pub(super) fn check_profile_values(profile: &Profile) -> Result<(), ModelError> {
    named("name", &profile.name)?;
    if profile.joints.is_empty() {
        return Err(ModelError::InvalidProfile {
            field: "joints".into(),
            reason: "lists no joint".into(),
        });
    }
    bounded(&bounds::SPAWN_HEIGHT, "spawn.height", profile.spawn.height)?;
    if let Some(h) = profile.spawn.standing_height {
        bounded(&bounds::SPAWN_HEIGHT, "spawn.standing_height", h)?;
    }
    bounded(&bounds::GAIN_KP, "gains.kp", profile.gains.kp)?;
    bounded(&bounds::GAIN_KD, "gains.kd", profile.gains.kd)?;
    for (i, f) in profile.feet.iter().enumerate() {
        named(format!("feet[{i}].name"), &f.name)?;
    }
    for (i, j) in profile.joints.iter().enumerate() {
        named(format!("joints[{i}].name"), &j.name)?;
        bounded(
            &bounds::JOINT_ANGLE,
            format!("joints[{i}].standing"),
            j.standing,
        )?;
        if let Some(kp) = j.kp {
            bounded(&bounds::GAIN_KP, format!("joints[{i}].kp"), kp)?;
        }
        if let Some(kd) = j.kd {
            bounded(&bounds::GAIN_KD, format!("joints[{i}].kd"), kd)?;
        }
    }
    Ok(())
}

/// Checks the profile's `[observation]` bounds (each within [`bounds::OBSERVATION_BOUND`],
/// with min < max) and returns them.
pub(super) fn check_observation_bounds(
    profile: &Profile,
) -> Result<Option<ObservationBounds>, ModelError> {
    let Some(table) = &profile.observation else {
        return Ok(None);
    };
    for (key, rows) in [
        ("trunk_acceleration", &table.trunk_acceleration),
        ("trunk_position", &table.trunk_position),
    ] {
        for (axis, [min, max]) in rows.iter().flatten().enumerate() {
            let field = format!("observation.{key}[{axis}]");
            bounded(&bounds::OBSERVATION_BOUND, field.clone(), *min)?;
            bounded(&bounds::OBSERVATION_BOUND, field.clone(), *max)?;
            if min >= max {
                return Err(ModelError::InvalidProfile {
                    field,
                    reason: format!("[{}, {}] must have min < max", short(*min), short(*max)),
                });
            }
        }
    }
    Ok(Some(table.clone()))
}
