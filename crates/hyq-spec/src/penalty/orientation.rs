//! Spec §5.1 (Orientation Penalty): for the yaw angle α (§5.1.1) and the pitch
//! angle β (§5.1.2) of [`crate::attitude`], each with its limit (`yaw_limit_deg`,
//! `pitch_limit_deg`, "currently" 2.5°),
//!
//! m(angle) = 1 if |angle| ≤ limit, else max(0, cos angle),
//!
//! and the step's rewards are multiplied by m_yaw · m_pitch. The limit itself is inside the free
//! range ("after the angle exceeds the limit"). The clamp at 0 is the spec's "a multiplier
//! between 0 and 1", as cos is negative past 90°.

/// m(angle): 1 when |`angle`| ≤ `limit` (both in radians), else max(0, cos `angle`).
///
/// The result is in [0, 1] and even in `angle`. Compare in radians: convert the configuration's
/// degrees once with `f64::to_radians`.
pub fn orientation_multiplier(angle: f64, limit: f64) -> f64 {
    if angle.abs() <= limit {
        1.0
    } else {
        angle.cos().max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn free_range_then_cosine_then_zero() {
        let limit = 2.5f64.to_radians();
        assert_eq!(orientation_multiplier(0.0, limit), 1.0);
        assert_eq!(orientation_multiplier(-limit, limit), 1.0);
        assert_eq!(orientation_multiplier(0.5, limit), 0.5f64.cos());
        assert_eq!(orientation_multiplier(-0.5, limit), 0.5f64.cos());
        assert_eq!(orientation_multiplier(FRAC_PI_2 + 0.1, limit), 0.0);
        assert_eq!(orientation_multiplier(-PI, limit), 0.0);
    }
}
