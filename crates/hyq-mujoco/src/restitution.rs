//! `randomize.restitution` on MuJoCo: the damping ratio whose contact gives back e of an impact.
//!
//! MuJoCo's contact has no restitution coefficient. Along the contact normal it is a
//! spring-damper in constraint space: with the impedance d near its maximum, the constrained
//! acceleration is −d (b v + k r), a linear spring of natural frequency ω = √(d k) and damping
//! ratio ζ = d b / (2 ω) (for a positive `solref` (timeconst tc, dampratio z), ω = 1 / (tc z)
//! and ζ = z; MuJoCo's modelling guide, "Restitution", bounces a ball with a direct
//! `solref` (−stiffness, −damping) whose damping is 0). A bounce is the spring giving back what
//! the damper left of the impact, so e is a function of ζ alone.
//!
//! Which function: the contact can only push (its force is clamped at zero), so it lets go of
//! the body when the spring-damper's force k r + b v falls to zero, before the body is back at
//! the surface, and from then on the body flies free. For a body arriving at speed v₀ with
//! r(0) = 0, r(t) = (v₀ / ω_d) e^(−ζωt) sin(ω_d t) (ω_d = ω √(1 − ζ²)); the force is zero where
//! r̈ = 0, at ω_d t* = π − 2 asin ζ, and the speed there is v₀ e^(−ζ ω t*), so
//!
//! ```text
//! e(ζ) = exp(−2 ζ acos ζ / √(1 − ζ²))        (ζ < 1; e(1) = e⁻² ≈ 0.135)
//! e(ζ) = exp(−2 ζ acosh ζ / √(ζ² − 1))       (ζ > 1, the same function continued)
//! ```
//!
//! falling from 1 at ζ = 0 towards 0 as ζ grows. The often-quoted e = exp(−ζπ / √(1 − ζ²))
//! is the bilateral spring's, which also pulls the body back to the surface: it gives e = 0.55
//! where 0.5 was asked. [`damping_ratio_for_restitution`] inverts the unilateral e(ζ).
//!
//! Time is discrete: at the project's 1 ms step and stiffness (ω = 500 rad/s) a contact lasts
//! about six steps, so MuJoCo's bounce follows e(ζ) only roughly (the crate's
//! `tests/contact_audit.rs` measures how closely).

/// The smallest damping ratio a restitution maps to: a positive `solref` cannot hold a damping
/// ratio of 0 (its stiffness 1 / (tc z)² would be infinite), so e = 1 is taken as
/// e(0.001) = 0.997.
pub const MIN_DAMPING_RATIO: f64 = 1e-3;

/// The largest damping ratio a restitution maps to (e(20) ≈ 6e-4): a drawn e below that asks
/// for more damping than MuJoCo's step can hold at any stiffness it accepts.
pub const MAX_DAMPING_RATIO: f64 = 20.0;

/// The coefficient of restitution of a unilateral linear spring-damper contact with damping
/// ratio `zeta` (≥ 0): the speed at which it lets go of a body, over the speed the body
/// arrived at (module docs).
pub fn restitution_of_damping_ratio(zeta: f64) -> f64 {
    let exponent = if zeta < 1.0 - 1e-9 {
        if zeta == 0.0 {
            0.0
        } else {
            2.0 * zeta * zeta.acos() / (1.0 - zeta * zeta).sqrt()
        }
    } else if zeta > 1.0 + 1e-9 {
        2.0 * zeta * zeta.acosh() / (zeta * zeta - 1.0).sqrt()
    } else {
        // Both branches tend to 2 at ζ = 1 (acos ζ ≈ √(1 − ζ²) there).
        2.0
    };
    (-exponent).exp()
}

/// The damping ratio ζ whose contact has restitution `e` ([`restitution_of_damping_ratio`]
/// inverted), held to [[`MIN_DAMPING_RATIO`], [`MAX_DAMPING_RATIO`]].
///
/// # Panics
/// If `e` is not in [0, 1] (the drawn restitution is validated before it gets here).
pub fn damping_ratio_for_restitution(e: f64) -> f64 {
    assert!((0.0..=1.0).contains(&e), "restitution {e} is not in [0, 1]");
    if e >= restitution_of_damping_ratio(MIN_DAMPING_RATIO) {
        return MIN_DAMPING_RATIO;
    }
    if e <= restitution_of_damping_ratio(MAX_DAMPING_RATIO) {
        return MAX_DAMPING_RATIO;
    }
    // e(ζ) falls monotonically: bisect until the bracket is one ulp wide.
    let (mut lo, mut hi) = (MIN_DAMPING_RATIO, MAX_DAMPING_RATIO);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if restitution_of_damping_ratio(mid) > e {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The bilateral spring-damper's restitution exp(−ζπ / √(1 − ζ²)) (ζ < 1), the formula this
/// module does not use, for the tests that show why.
#[cfg(test)]
fn bilateral_restitution(zeta: f64) -> f64 {
    (-zeta * std::f64::consts::PI / (1.0 - zeta * zeta).sqrt()).exp()
}

#[cfg(test)]
mod tests {
    //! The unilateral restitution is continuous and falling, its inverse returns the asked
    //! restitution, and it differs from the bilateral formula as the module docs say.
    #![allow(clippy::unwrap_used)]

    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn restitution_falls_from_one_and_is_continuous_at_critical_damping() {
        assert_eq!(restitution_of_damping_ratio(0.0), 1.0);
        let mut last = 1.0;
        for i in 1..=4000 {
            let e = restitution_of_damping_ratio(i as f64 * 0.005);
            assert!(
                e < last && e > 0.0,
                "ζ = {}: {e} after {last}",
                i as f64 * 0.005
            );
            last = e;
        }
        let at_one = (-2.0f64).exp();
        for zeta in [1.0 - 1e-6, 1.0, 1.0 + 1e-6] {
            let e = restitution_of_damping_ratio(zeta);
            assert!((e - at_one).abs() < 1e-5, "ζ = {zeta}: {e}");
        }
    }

    #[test]
    fn the_inverse_returns_the_asked_restitution() {
        for i in 1..100 {
            let e = i as f64 / 100.0;
            let zeta = damping_ratio_for_restitution(e);
            let back = restitution_of_damping_ratio(zeta);
            assert!((back - e).abs() < 1e-12, "e = {e}: ζ = {zeta} gives {back}");
        }
        assert_eq!(damping_ratio_for_restitution(1.0), MIN_DAMPING_RATIO);
        assert_eq!(damping_ratio_for_restitution(0.0), MAX_DAMPING_RATIO);
    }

    #[test]
    fn a_contact_that_only_pushes_bounces_more_than_the_bilateral_formula_says() {
        // e = 0.5: the unilateral contact needs ζ ≈ 0.255, where the bilateral formula would
        // have given 0.44; the bilateral formula's ζ ≈ 0.215 bounces a unilateral contact at 0.55.
        let zeta = damping_ratio_for_restitution(0.5);
        assert!((zeta - 0.2553).abs() < 1e-4, "{zeta}");
        let bilateral = bilateral_restitution(zeta);
        assert!((bilateral - 0.437).abs() < 0.005, "{bilateral}");
        let bilateral_zeta = 0.5f64.ln().abs() / (PI * PI + 0.5f64.ln().powi(2)).sqrt();
        let unilateral = restitution_of_damping_ratio(bilateral_zeta);
        assert!((unilateral - 0.550).abs() < 0.005, "{unilateral}");
    }

    #[test]
    #[should_panic(expected = "not in [0, 1]")]
    fn a_restitution_outside_zero_to_one_is_a_bug() {
        damping_ratio_for_restitution(1.5);
    }
}
