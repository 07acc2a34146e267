//! Invariant: the ruled R_e (spec §4.3) is a continuous, decreasing curve with
//! R_e(1) = 0 and R_e(0) = (e^k − 1)/k:
//!
//! - 0 ≤ D_n ≤ 1: (e^{k(1−D_n)} − 1)/k;  1 < D_n ≤ 9: 5(1 − D_n);  D_n > 9: −40 + 0.5(9 − D_n);
//! - |R_e(a) − R_e(b)| ≤ max(e^k, 5)·|a − b| everywhere, across D_n = 1 and 9 included
//!   (Lipschitz, hence continuous: no jump to farm);
//! - a < b ⇒ R_e(a) ≥ R_e(b) (moving towards the goal never loses reward);
//! - r_e = R_e(D_n^t) − R_e(D_n^{t−1}).

mod common;

use common::d_n_near_boundaries;
use hyq_spec::reward::exponential::{cumulative_exponential_reward as r_e_cum, exponential_reward};
use proptest::prelude::*;

fn k_exp() -> impl Strategy<Value = f64> {
    prop_oneof![Just(5.0), 0.05f64..20.0]
}

/// R_e(D_n) equals the ruled piecewise formula, evaluated directly.
fn check_formula(d_n: f64, k: f64) {
    let expected = if d_n <= 1.0 {
        ((k * (1.0 - d_n)).exp() - 1.0) / k
    } else if d_n <= 9.0 {
        5.0 * (1.0 - d_n)
    } else {
        -40.0 + 0.5 * (9.0 - d_n)
    };
    let got = r_e_cum(d_n, k);
    let tol = 1e-12 * (1.0 + expected.abs());
    assert!(
        (got - expected).abs() <= tol,
        "R_e({d_n}; k = {k}) = {got}, formula {expected}"
    );
}

/// |R_e(a) − R_e(b)| ≤ L·|a − b| with L = max(e^k, 5) (plus rounding).
fn check_lipschitz(a: f64, b: f64, k: f64) {
    let lipschitz = k.exp().max(5.0);
    let gap = (r_e_cum(a, k) - r_e_cum(b, k)).abs();
    let bound = lipschitz * (a - b).abs() + 1e-12 * (1.0 + r_e_cum(a, k).abs());
    assert!(
        gap <= bound,
        "R_e jumps by {gap} between {a} and {b} (k = {k}), bound {bound}"
    );
}

/// a ≤ b ⇒ R_e(a) ≥ R_e(b).
fn check_decreasing(a: f64, b: f64, k: f64) {
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    assert!(
        r_e_cum(lo, k) >= r_e_cum(hi, k),
        "R_e({lo}) = {} < R_e({hi}) = {}",
        r_e_cum(lo, k),
        r_e_cum(hi, k)
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2048, ..ProptestConfig::default() })]

    #[test]
    fn follows_the_ruled_formula(d_n in d_n_near_boundaries(), k in k_exp()) {
        check_formula(d_n, k);
    }

    #[test]
    fn is_continuous_across_one_and_nine(
        at in prop_oneof![Just(1.0), Just(9.0)],
        left in 0.0f64..1e-3,
        right in 0.0f64..1e-3,
        k in k_exp(),
    ) {
        check_lipschitz(at - left, at + right, k);
        check_lipschitz(at, at + right, k);
        check_lipschitz(at - left, at, k);
    }

    #[test]
    fn is_lipschitz_everywhere(a in d_n_near_boundaries(), b in d_n_near_boundaries(), k in k_exp()) {
        check_lipschitz(a, b, k);
    }

    #[test]
    fn is_decreasing(a in d_n_near_boundaries(), b in d_n_near_boundaries(), k in k_exp()) {
        check_decreasing(a, b, k);
    }

    #[test]
    fn is_decreasing_between_neighbouring_floats(d_n in d_n_near_boundaries(), k in k_exp()) {
        check_decreasing(d_n, d_n.next_up(), k);
    }

    #[test]
    fn step_reward_is_the_change_of_the_cumulative(a in d_n_near_boundaries(), b in d_n_near_boundaries(), k in k_exp()) {
        prop_assert_eq!(exponential_reward(a, b, k), r_e_cum(b, k) - r_e_cum(a, k));
        // Moving closer (b < a) never costs reward.
        if b < a {
            prop_assert!(exponential_reward(a, b, k) >= 0.0);
        }
    }

    #[test]
    fn peak_is_e_to_the_k_minus_one_over_k(k in k_exp()) {
        let expected = (k.exp() - 1.0) / k;
        prop_assert!((r_e_cum(0.0, k) - expected).abs() <= 1e-12 * expected);
        prop_assert_eq!(r_e_cum(1.0, k), 0.0);
        prop_assert_eq!(r_e_cum(9.0, k), -40.0);
    }
}

#[test]
fn default_peak_is_about_29_48() {
    assert!((r_e_cum(0.0, 5.0) - 29.48).abs() < 0.005);
    assert!((r_e_cum(0.0, 5.0) - (5f64.exp() - 1.0) / 5.0).abs() < 1e-12);
}
