//! Spec §5.2 (Height Penalty): "TBD" in the original, an opt-in multiplier here,
//! off by default. When `height_penalty` is set in [`crate::TaskConfig`], with z the trunk
//! centre's height (world z of C^t) and the parameters of [`HeightPenalty`],
//!
//! m_height = 1 if |z − z_0| ≤ tolerance, else e^{−λ·|z − z_0|},
//!
//! which is the form the system the spec describes used (z_0 = 0.62 m, tolerance 0.1 m, λ = 2
//! for HyQ). It multiplies the rewards with m_yaw and m_pitch. Like those, it jumps at the edge of
//! its free band (to e^{−λ·tolerance}, ≈ 0.82 with those values); it is never above 1 or below 0.
//! When unset, m_height = 1 and the total is bit-identical to the rule without it.

use crate::config::HeightPenalty;

/// m_height for trunk height `z` (metres), or 1 when `penalty` is `None`.
pub fn height_multiplier(z: f64, penalty: Option<&HeightPenalty>) -> f64 {
    let Some(p) = penalty else { return 1.0 };
    let off_nominal = (z - p.nominal_height_m).abs();
    if off_nominal <= p.tolerance_m {
        1.0
    } else {
        (-p.rate_per_m * off_nominal).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const HYQ: HeightPenalty = HeightPenalty {
        nominal_height_m: 0.62,
        tolerance_m: 0.1,
        rate_per_m: 2.0,
    };

    #[test]
    fn off_is_exactly_one() {
        assert_eq!(height_multiplier(-3.0, None), 1.0);
        assert_eq!(height_multiplier(0.0, None), 1.0);
    }

    #[test]
    fn free_band_then_exponential_decay() {
        assert_eq!(height_multiplier(0.62, Some(&HYQ)), 1.0);
        assert_eq!(height_multiplier(0.70, Some(&HYQ)), 1.0);
        assert_eq!(
            height_multiplier(0.30, Some(&HYQ)),
            (-2.0f64 * (0.62f64 - 0.30).abs()).exp()
        );
        assert_eq!(
            height_multiplier(1.00, Some(&HYQ)),
            (-2.0f64 * (1.00f64 - 0.62).abs()).exp()
        );
    }

    proptest! {
        #[test]
        fn within_unit_interval_and_one_inside_the_band(
            z in prop_oneof![0.50f64..0.74, -1.0f64..3.0],
        ) {
            let m = height_multiplier(z, Some(&HYQ));
            prop_assert!((0.0..=1.0).contains(&m));
            if (z - 0.62f64).abs() <= 0.1 {
                prop_assert_eq!(m, 1.0);
            } else {
                prop_assert!(m < 1.0);
                prop_assert_eq!(m, (-2.0 * (z - 0.62f64).abs()).exp());
            }
        }
    }
}
