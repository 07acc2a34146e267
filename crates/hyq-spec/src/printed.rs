//! The spec's equations **as printed**, where the spec page rules otherwise. Nothing in the
//! environment uses these; they exist so that tests can show each ruling's reason
//! (`tests/ruling_reasons.rs`, and `docs/spec.md`).
//!
//! - §4.1, eq. (2): r_b^t = |C^t − C^{t−1}|, the distance travelled in any direction
//!   (ruled: k_base · (D^{t−1} − D^t), see [`crate::reward::base`]).
//! - §4.3, eq. (4): R_e = (1/k) e^{k(1−D_n)} on [0, 1], 5(1 − D_n) on (1, 9], 0.5(1 − D_n) past 9
//!   (ruled: the continuous curve of [`crate::reward::exponential`]).
//! - §6.2: limit reached unless θ_min < |θ − ε| < θ_max (ruled: θ ≤ θ_min + ε or
//!   θ ≥ θ_max − ε, see [`crate::termination::joint_limit`]).

use nalgebra::Point3;

/// Eq. (2) as printed: r_b^t = |C^t − C^{t−1}|, metres travelled, whatever the direction.
pub fn base_reward(previous_position: &Point3<f64>, position: &Point3<f64>) -> f64 {
    (position - previous_position).norm()
}

/// Eq. (4) as printed: (1/k) e^{k(1−D_n)} for 0 ≤ D_n ≤ 1, 5(1 − D_n) for 1 < D_n ≤ 9,
/// 0.5(1 − D_n) for D_n > 9.
pub fn cumulative_exponential_reward(d_n: f64, k_exp: f64) -> f64 {
    if d_n <= 1.0 {
        (k_exp * (1.0 - d_n)).exp() / k_exp
    } else if d_n <= 9.0 {
        5.0 * (1.0 - d_n)
    } else {
        0.5 * (1.0 - d_n)
    }
}

/// §6.2 as printed: the limit is **not** reached when θ_min < |θ − ε| < θ_max, and reached
/// otherwise.
pub fn joint_limit_reached(
    angle: f64,
    lower: f64,
    upper: f64,
    accepted_dist_to_bounds: f64,
) -> bool {
    let shifted = (angle - accepted_dist_to_bounds).abs();
    !(lower < shifted && shifted < upper)
}
