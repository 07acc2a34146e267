//! Spec §1 (Figure 2, "HyQ Rotation", lost from the printed text) as ruled in spec §1:
//! roll, pitch and yaw are the intrinsic Z-Y-X Tait–Bryan angles of the trunk quaternion, in the
//! world frame with x forward, y left and z up:
//!
//! R(q) = R_z(yaw) · R_y(pitch) · R_x(roll),
//!
//! so for a unit quaternion q = (w, x, y, z)
//!
//! - roll  = atan2(2(w·x + y·z), 1 − 2(x² + y²))            ∈ [−π, π]
//! - pitch = asin(2(w·y − z·x))                              ∈ [−π/2, π/2]
//! - yaw   = atan2(2(w·z + x·y), 1 − 2(y² + z²))            ∈ [−π, π]
//!
//! With the right-hand rule this makes positive yaw a turn to the left, positive pitch nose
//! down and positive roll the right side down. The desired yaw and pitch are 0 (§5.1).
//!
//! Near pitch = ±90° (gimbal lock) roll and yaw are not unique: only yaw − roll (at +90°) or
//! yaw + roll (at −90°) is. There both `atan2` arguments shrink to |cos pitch| and rounding makes
//! the angles noisy, so when |cos pitch| < [`GIMBAL_COS_THRESHOLD`] the function puts the whole
//! heading into yaw (roll = 0, yaw = 2·atan2(z, w) wrapped into [−π, π]). Either way the three
//! angles recompose to the input rotation to within about 2·10⁻⁸ rad.

use nalgebra::UnitQuaternion;
use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, PI};

/// Below this |cos pitch| the rotation is treated as gimbal-locked (roll set to 0).
///
/// At |cos pitch| = δ the generic formulas lose about 2⁻⁵³/δ rad to rounding and the locked
/// formula is off by about δ rad; 10⁻⁸ balances the two near √2⁻⁵³.
pub const GIMBAL_COS_THRESHOLD: f64 = 1e-8;

/// Roll, pitch and yaw of the trunk in radians (intrinsic Z-Y-X, x forward, y left, z up).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RollPitchYaw {
    /// Rotation about x (forward), radians, in [−π, π]; positive lowers the right side.
    pub roll: f64,
    /// Rotation about y (left), radians, in [−π/2, π/2]; positive lowers the nose.
    pub pitch: f64,
    /// Rotation about z (up), radians, in [−π, π]; positive turns left.
    pub yaw: f64,
}

/// Roll, pitch and yaw of `orientation` (spec §1: intrinsic Z-Y-X, x forward, y left, z up).
///
/// `q` and `−q` give the same angles. See the module docs for the gimbal-lock convention.
pub fn roll_pitch_yaw(orientation: &UnitQuaternion<f64>) -> RollPitchYaw {
    let (w, x, y, z) = (orientation.w, orientation.i, orientation.j, orientation.k);

    let sin_pitch = (2.0 * (w * y - z * x)).clamp(-1.0, 1.0);
    // asin loses precision near ±1; this half-angle form keeps it (both roots are of
    // non-negative numbers because of the clamp above).
    let pitch = 2.0 * f64::atan2((1.0 + sin_pitch).sqrt(), (1.0 - sin_pitch).sqrt()) - FRAC_PI_2;

    let yaw_sin = 2.0 * (w * z + x * y);
    let yaw_cos = 1.0 - 2.0 * (y * y + z * z);
    if yaw_sin.hypot(yaw_cos) < GIMBAL_COS_THRESHOLD {
        return RollPitchYaw {
            roll: 0.0,
            pitch,
            yaw: wrap_to_pi(2.0 * f64::atan2(z, w)),
        };
    }
    let roll = f64::atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y));
    let yaw = f64::atan2(yaw_sin, yaw_cos);
    RollPitchYaw { roll, pitch, yaw }
}

/// `angle` (within [−2π, 2π]) moved by a whole turn into [−π, π].
fn wrap_to_pi(angle: f64) -> f64 {
    if angle > PI {
        angle - 2.0 * PI
    } else if angle < -PI {
        angle + 2.0 * PI
    } else {
        angle
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Quaternion, Vector3};
    use proptest::prelude::*;

    /// R_z(yaw) · R_y(pitch) · R_x(roll), built from axis rotations (not from nalgebra's Euler
    /// helper), as the independent oracle for the decomposition.
    fn compose(roll: f64, pitch: f64, yaw: f64) -> UnitQuaternion<f64> {
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw)
            * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), pitch)
            * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), roll)
    }

    /// Smallest difference between two angles, modulo a full turn.
    fn angle_diff(a: f64, b: f64) -> f64 {
        let d = (a - b).rem_euclid(2.0 * PI);
        d.min(2.0 * PI - d)
    }

    fn check_decomposition(roll: f64, pitch: f64, yaw: f64, tol: f64) {
        let q = compose(roll, pitch, yaw);
        for q in [q, UnitQuaternion::new_unchecked(-q.into_inner())] {
            let a = roll_pitch_yaw(&q);
            assert!(angle_diff(a.roll, roll) <= tol, "roll {} vs {roll}", a.roll);
            assert!(
                (a.pitch - pitch).abs() <= tol,
                "pitch {} vs {pitch}",
                a.pitch
            );
            assert!(angle_diff(a.yaw, yaw) <= tol, "yaw {} vs {yaw}", a.yaw);
        }
    }

    fn check_recomposes(q: &UnitQuaternion<f64>, tol: f64) {
        let a = roll_pitch_yaw(q);
        assert!((-PI..=PI).contains(&a.roll), "roll {}", a.roll);
        assert!(
            (-FRAC_PI_2..=FRAC_PI_2).contains(&a.pitch),
            "pitch {}",
            a.pitch
        );
        assert!((-PI..=PI).contains(&a.yaw), "yaw {}", a.yaw);
        let back = compose(a.roll, a.pitch, a.yaw);
        assert!(
            back.angle_to(q) <= tol,
            "recomposed {a:?} is {} rad off",
            back.angle_to(q)
        );
    }

    #[test]
    fn known_rotations() {
        let deg = f64::to_radians;
        let cases = [
            (UnitQuaternion::identity(), (0.0, 0.0, 0.0)),
            (
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), deg(90.0)),
                (0.0, 0.0, deg(90.0)),
            ),
            (
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), deg(-2.5)),
                (0.0, 0.0, deg(-2.5)),
            ),
            (
                UnitQuaternion::from_axis_angle(&Vector3::y_axis(), deg(30.0)),
                (0.0, deg(30.0), 0.0),
            ),
            (
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), deg(-45.0)),
                (deg(-45.0), 0.0, 0.0),
            ),
            (
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), deg(180.0)),
                (0.0, 0.0, PI),
            ),
        ];
        for (q, (roll, pitch, yaw)) in cases {
            let a = roll_pitch_yaw(&q);
            assert!(angle_diff(a.roll, roll) < 1e-12, "{q:?}: {a:?}");
            assert!((a.pitch - pitch).abs() < 1e-12, "{q:?}: {a:?}");
            assert!(angle_diff(a.yaw, yaw) < 1e-12, "{q:?}: {a:?}");
        }
    }

    #[test]
    fn signs_follow_x_forward_y_left_z_up() {
        // A positive yaw turns the forward axis towards +y (left).
        let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.3);
        assert!((q * Vector3::x()).y > 0.0 && roll_pitch_yaw(&q).yaw > 0.0);
        // A positive pitch turns the forward axis towards −z (nose down).
        let q = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 0.3);
        assert!((q * Vector3::x()).z < 0.0 && roll_pitch_yaw(&q).pitch > 0.0);
    }

    #[test]
    fn exact_gimbal_lock_keeps_the_heading_in_yaw() {
        for (pitch, roll, yaw) in [
            (FRAC_PI_2, 0.4, 1.0),
            (-FRAC_PI_2, 0.4, 1.0),
            (FRAC_PI_2, -3.0, 3.0),
        ] {
            let q = compose(roll, pitch, yaw);
            let a = roll_pitch_yaw(&q);
            assert_eq!(a.roll, 0.0);
            assert!((a.pitch.abs() - FRAC_PI_2).abs() < 1e-7, "{a:?}");
            check_recomposes(&q, 1e-7);
        }
    }

    #[test]
    fn non_unit_raw_quaternions_are_normalised_first() {
        let q = UnitQuaternion::from_quaternion(Quaternion::new(2.0, 0.0, 0.0, 2.0));
        assert!((roll_pitch_yaw(&q).yaw - FRAC_PI_2).abs() < 1e-12);
    }

    proptest! {
        #[test]
        fn decomposes_what_was_composed(
            roll in -3.1f64..3.1,
            pitch in -1.5f64..1.5,
            yaw in -3.1f64..3.1,
        ) {
            check_decomposition(roll, pitch, yaw, 1e-9);
        }

        #[test]
        fn decomposes_small_angles_near_the_limits(
            roll in -0.1f64..0.1,
            pitch in prop_oneof![-0.05f64..0.05, (2.4f64..2.6).prop_map(f64::to_radians), (-2.6f64..-2.4).prop_map(f64::to_radians)],
            yaw in prop_oneof![-0.05f64..0.05, (2.4f64..2.6).prop_map(f64::to_radians), (-2.6f64..-2.4).prop_map(f64::to_radians)],
        ) {
            check_decomposition(roll, pitch, yaw, 1e-12);
        }

        #[test]
        fn recomposes_in_the_gimbal_region(
            roll in -PI..PI,
            offset_exp in -15.0f64..-2.0,
            sign in prop_oneof![Just(1.0), Just(-1.0)],
            yaw in -PI..PI,
        ) {
            // Pitch within 10⁻¹⁵…10⁻² rad of ±90°.
            let pitch = sign * (FRAC_PI_2 - 10f64.powf(offset_exp));
            let q = compose(roll, pitch, yaw);
            // sin(pitch) carries a few ulps of the quaternion's rounding, and near ±90° an error
            // Δ in it moves pitch by about Δ / cos(pitch); outside the gimbal branch cos(pitch)
            // is at least GIMBAL_COS_THRESHOLD, so the bound is a few ε / threshold (2.2·10⁻⁸
            // per ε). 5·10⁻⁸ was met by most draws and missed by one at 6.7·10⁻⁸ (about 3 ε /
            // threshold); 16 ε / threshold leaves room for the few ulps without hiding a wrong
            // formula, which would be off by far more.
            let tol = 16.0 * f64::EPSILON / GIMBAL_COS_THRESHOLD;
            check_recomposes(&q, tol);
            let a = roll_pitch_yaw(&q);
            prop_assert!((a.pitch - pitch).abs() <= tol, "pitch {} vs {}", a.pitch, pitch);
        }
    }
}
