//! Phase 0 of building a model: the profile's own values, those that need no URDF.

use crate::error::ModelError;
use crate::profile::{ObservationBounds, Profile};

/// Checks the profile's own values (those that need no URDF).
pub(super) fn check_profile_values(profile: &Profile) -> Result<(), ModelError> {
    let invalid = |field: String, reason: String| ModelError::InvalidProfile { field, reason };
    if profile.joints.is_empty() {
        return Err(invalid("joints".into(), "lists no joint".into()));
    }
    if !(profile.spawn.height.is_finite() && profile.spawn.height > 0.0) {
        return Err(invalid(
            "spawn.height".into(),
            format!("{} m must be finite and positive", profile.spawn.height),
        ));
    }
    if let Some(h) = profile.spawn.standing_height
        && !(h.is_finite() && h > 0.0)
    {
        return Err(invalid(
            "spawn.standing_height".into(),
            format!("{h} m must be finite and positive"),
        ));
    }
    let gain = |field: String, v: f64| {
        if v.is_finite() && v >= 0.0 {
            Ok(())
        } else {
            Err(invalid(
                field,
                format!("{v} must be finite and non-negative"),
            ))
        }
    };
    gain("gains.kp".into(), profile.gains.kp)?;
    gain("gains.kd".into(), profile.gains.kd)?;
    for (i, j) in profile.joints.iter().enumerate() {
        if !j.standing.is_finite() {
            return Err(invalid(
                format!("joints[{i}].standing"),
                format!("{} is not finite", j.standing),
            ));
        }
        if let Some(kp) = j.kp {
            gain(format!("joints[{i}].kp"), kp)?;
        }
        if let Some(kd) = j.kd {
            gain(format!("joints[{i}].kd"), kd)?;
        }
    }
    Ok(())
}

/// Checks the profile's `[observation]` bounds (each finite with min < max) and returns them.
pub(super) fn check_observation_bounds(
    profile: &Profile,
) -> Result<Option<ObservationBounds>, ModelError> {
    let Some(bounds) = &profile.observation else {
        return Ok(None);
    };
    for (key, table) in [
        ("trunk_acceleration", &bounds.trunk_acceleration),
        ("trunk_position", &bounds.trunk_position),
    ] {
        for (axis, [min, max]) in table.iter().flatten().enumerate() {
            if !(min.is_finite() && max.is_finite() && min < max) {
                return Err(ModelError::InvalidProfile {
                    field: format!("observation.{key}[{axis}]"),
                    reason: format!("[{min}, {max}] must be finite with min < max"),
                });
            }
        }
    }
    Ok(Some(bounds.clone()))
}
