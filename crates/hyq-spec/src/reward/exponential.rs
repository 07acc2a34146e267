//! Spec §4.3, eqs. (4)–(5), as ruled (a **deviation**): the cumulative exponential
//! reward R_e is the continuous piecewise curve of the normalised distance D_n,
//!
//! - 0 ≤ D_n ≤ 1:  R_e(D_n) = (e^{k_exp(1 − D_n)} − 1) / k_exp
//! - 1 < D_n ≤ 9:  R_e(D_n) = 5 (1 − D_n)
//! - 9 < D_n:      R_e(D_n) = −40 + 0.5 (9 − D_n)
//!
//! and the per-step reward is its change, eq. (5): r_e^t = R_e(D_n^t) − R_e(D_n^{t−1}).
//!
//! R_e(1) = 0 (the start pays nothing, as the spec's text requires), R_e(0) = (e^{k_exp} − 1) /
//! k_exp (≈ 29.48 for the default k_exp = 5), and R_e is continuous at 1 and at 9 and decreasing,
//! so Σ r_e over an episode is R_e(D_n^T) whatever the path. The printed eq. (4) lacks the −1
//! and the −40 and jumps at D_n = 1 and D_n = 9 (kept in
//! [`crate::printed::cumulative_exponential_reward`] to show why). Unset `exp_rew_scaling`
//! turns r_e off.
//!
//! D_n is a ratio of distances, so it is never negative; for a negative argument the first
//! branch's formula is used as is.

/// The start of the linear region: R_e is the exponential branch up to here.
pub const LINEAR_FROM: f64 = 1.0;
/// The start of the gentle region: R_e is the steep linear branch up to here.
pub const GENTLE_FROM: f64 = 9.0;
/// R_e at [`GENTLE_FROM`]: 5 · (1 − 9).
const R_E_AT_GENTLE_FROM: f64 = -40.0;

/// R_e(D_n), the cumulative exponential reward at normalised distance `d_n` (k_exp > 0; the
/// configuration guarantees it).
pub fn cumulative_exponential_reward(d_n: f64, k_exp: f64) -> f64 {
    if d_n <= LINEAR_FROM {
        // exp_m1 keeps R_e(1) exactly 0 and stays accurate as D_n approaches 1.
        (k_exp * (1.0 - d_n)).exp_m1() / k_exp
    } else if d_n <= GENTLE_FROM {
        5.0 * (1.0 - d_n)
    } else {
        R_E_AT_GENTLE_FROM + 0.5 * (GENTLE_FROM - d_n)
    }
}

/// r_e = R_e(D_n^t) − R_e(D_n^{t−1}) for the normalised distances before (`d_n_prev`) and after
/// (`d_n`) the step.
pub fn exponential_reward(d_n_prev: f64, d_n: f64, k_exp: f64) -> f64 {
    cumulative_exponential_reward(d_n, k_exp) - cumulative_exponential_reward(d_n_prev, k_exp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anchor_values() {
        assert_eq!(cumulative_exponential_reward(1.0, 5.0), 0.0);
        assert!((cumulative_exponential_reward(0.0, 5.0) - 29.482_631_820_515_32).abs() < 1e-12);
        assert_eq!(cumulative_exponential_reward(9.0, 5.0), -40.0);
        assert_eq!(cumulative_exponential_reward(11.0, 5.0), -41.0);
        assert_eq!(cumulative_exponential_reward(3.0, 5.0), -10.0);
        assert_eq!(exponential_reward(1.0, 1.0, 5.0), 0.0);
    }
}
