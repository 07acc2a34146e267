//! The intervals do what an interval must: a 95 % interval covers the true value of a known
//! distribution about 95 % of the time, its half-width shrinks as 1/√n, every finite input gives
//! finite output with `lo ≤ mean ≤ hi`, the same seed gives the same interval bit for bit, and
//! empty or non-finite input is refused with an error naming it.

use hyq_stats::{
    Pairing, StatsError, mean_ci, mean_ci_with, ratio_of_means, ratio_of_means_with, wilson,
};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `n` draws of N(mu, sigma²) (Box–Muller) from a stream seeded with `seed`.
fn normal(seed: u64, n: usize, mu: f64, sigma: f64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut uniform = move || ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64);
    (0..n)
        .map(|_| {
            let (u, v) = (uniform(), uniform());
            mu + sigma * (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        })
        .collect()
}

/// Bernoulli(p) successes in `n` trials from a stream seeded with `seed`.
fn successes(seed: u64, n: u64, p: f64) -> u64 {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .filter(|_| ((rng.next_u64() >> 11) as f64) < p * (1u64 << 53) as f64)
        .count() as u64
}

#[test]
fn the_bootstrap_interval_covers_a_normal_mean_about_95_percent_of_the_time() {
    // 400 samples of 50 draws of N(3, 2²); the percentile bootstrap at n = 50 covers about
    // 94 % (it is a little narrow for small n). Binomial sd of the share over 400 samples: 1.1 %.
    let trials = 400;
    let covered = (0..trials)
        .filter(|&t| {
            let x = normal(1000 + t, 50, 3.0, 2.0);
            let e = mean_ci_with(&x, t, 2000).unwrap_or_else(|e| panic!("{e}"));
            e.contains(3.0)
        })
        .count();
    let share = covered as f64 / trials as f64;
    assert!((0.905..=0.985).contains(&share), "covered {share}");
}

#[test]
fn the_wilson_interval_covers_a_rate_about_95_percent_of_the_time() {
    // 2000 runs of 40 Bernoulli(0.3) trials. Wilson's coverage oscillates with n and p around
    // 95 % (Brown, Cai & DasGupta 2001, fig. 4); the binomial sum at n = 40, p = 0.3 gives
    // 94.4 %. Sd of the share over 2000 runs: 0.5 %.
    let runs = 2000;
    let covered = (0..runs)
        .filter(|&s| {
            let k = successes(s, 40, 0.3);
            let r = wilson(k, 40).unwrap_or_else(|e| panic!("{e}"));
            r.ci95[0] <= 0.3 && 0.3 <= r.ci95[1]
        })
        .count();
    let share = covered as f64 / runs as f64;
    assert!((0.925..=0.965).contains(&share), "covered {share}");
}

#[test]
fn the_half_width_shrinks_as_one_over_root_n() {
    // Averaged over 60 samples of N(0, 1) at n = 25, 100, 400: each fourfold n halves it.
    let mean_half_width = |n: usize| {
        (0..60)
            .map(|s| {
                let x = normal(7 + s, n, 0.0, 1.0);
                mean_ci_with(&x, s, 2000)
                    .unwrap_or_else(|e| panic!("{e}"))
                    .half_width()
            })
            .sum::<f64>()
            / 60.0
    };
    let h = [
        mean_half_width(25),
        mean_half_width(100),
        mean_half_width(400),
    ];
    for w in h.windows(2) {
        let ratio = w[0] / w[1];
        assert!((1.85..=2.15).contains(&ratio), "half-widths {h:?}");
    }
    // And it is near the normal theory's 1.96/√n (the percentile form is a little narrower).
    let expected = 1.96 / 20.0;
    assert!(
        (h[2] / expected - 1.0).abs() < 0.06,
        "{} vs {expected}",
        h[2]
    );
}

#[test]
fn the_same_values_and_seed_give_the_same_interval_bit_for_bit() {
    let x = normal(3, 37, 1.0, 0.5);
    let y = normal(4, 37, 2.0, 0.5);
    let a = mean_ci(&x, 11).unwrap_or_else(|e| panic!("{e}"));
    let b = mean_ci(&x, 11).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a.ci95.map(f64::to_bits), b.ci95.map(f64::to_bits));
    let c = mean_ci(&x, 12).unwrap_or_else(|e| panic!("{e}"));
    assert_ne!(a.ci95, c.ci95, "another seed resamples differently");
    let r = ratio_of_means(&y, &x, Pairing::Paired, 5).unwrap_or_else(|e| panic!("{e}"));
    let s = ratio_of_means(&y, &x, Pairing::Paired, 5).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.ci95.map(f64::to_bits), s.ci95.map(f64::to_bits));
}

#[test]
fn a_ratio_of_clearly_different_means_excludes_one_and_of_equal_ones_does_not() {
    let a = normal(21, 40, 4.0, 1.0);
    let b = normal(22, 40, 2.0, 1.0);
    let r = ratio_of_means(&a, &b, Pairing::Independent, 0).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.excludes_one && r.ci95[0] > 1.0, "{r:?}");
    assert!(r.ci95[0] <= r.mean && r.mean <= r.ci95[1]);
    let same = ratio_of_means(&a, &a, Pairing::Paired, 0).unwrap_or_else(|e| panic!("{e}"));
    // Paired resampling of a sample with itself: every resampled ratio is exactly 1.
    assert_eq!(
        (same.mean, same.ci95, same.excludes_one),
        (1.0, [1.0, 1.0], false)
    );
}

#[test]
fn empty_and_non_finite_input_is_refused_with_what_was_wrong() {
    assert_eq!(mean_ci(&[], 0), Err(StatsError::Empty));
    let e = mean_ci(&[1.0, f64::NAN], 0).map_err(|e| e.to_string());
    assert_eq!(e, Err("value 1 is NaN, not a finite number".to_owned()));
    let e = mean_ci(&[f64::NEG_INFINITY], 0);
    assert_eq!(
        e,
        Err(StatsError::NonFinite {
            index: 0,
            value: f64::NEG_INFINITY
        })
    );
    assert_eq!(
        ratio_of_means(&[1.0], &[], Pairing::Independent, 0),
        Err(StatsError::Empty)
    );
    assert_eq!(
        ratio_of_means(&[f64::INFINITY], &[1.0], Pairing::Independent, 0),
        Err(StatsError::NonFinite {
            index: 0,
            value: f64::INFINITY
        })
    );
}

/// A finite f64 of any size, with the awkward ones (±0, the extremes, subnormals) often.
fn finite() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -1e3..1e3f64,
        1 => prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
        1 => prop::sample::select(vec![f64::MAX, f64::MIN, f64::MIN_POSITIVE, -0.0, 5e-324]),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn every_finite_sample_gives_a_finite_interval_around_its_mean(
        x in prop::collection::vec(finite(), 1..40),
        seed in any::<u64>(),
    ) {
        let e = mean_ci_with(&x, seed, 300).map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert!(e.mean.is_finite() && e.ci95[0].is_finite() && e.ci95[1].is_finite(), "{e:?}");
        prop_assert!(e.ci95[0] <= e.mean && e.mean <= e.ci95[1], "{e:?}");
        let (lo, hi) = x.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
        prop_assert!(lo <= e.ci95[0] && e.ci95[1] <= hi, "{e:?} outside [{lo}, {hi}]");
    }

    #[test]
    fn every_finite_ratio_is_finite_or_a_named_refusal(
        a in prop::collection::vec(finite(), 1..20),
        b in prop::collection::vec(finite(), 1..20),
        seed in any::<u64>(),
    ) {
        match ratio_of_means_with(&a, &b, Pairing::Independent, seed, 200) {
            Ok(r) => {
                prop_assert!(r.mean.is_finite() && r.ci95.iter().all(|v| v.is_finite()), "{r:?}");
                prop_assert!(r.ci95[0] <= r.mean && r.mean <= r.ci95[1], "{r:?}");
                prop_assert_eq!(r.excludes_one, !(r.ci95[0] <= 1.0 && 1.0 <= r.ci95[1]));
            }
            Err(StatsError::DenominatorSpansZero { .. } | StatsError::Overflow { .. }) => {}
            Err(e) => prop_assert!(false, "unexpected refusal: {e}"),
        }
    }

    #[test]
    fn a_sample_four_times_over_halves_the_half_width(
        seed in any::<u64>(),
        n in 30usize..80,
        mu in -1e3..1e3f64,
        sigma in 1e-3..1e3f64,
    ) {
        // The same empirical distribution at 4n: the resampled mean's spread is half.
        let x = normal(seed, n, mu, sigma);
        let x4: Vec<f64> = x.iter().chain(&x).chain(&x).chain(&x).copied().collect();
        let h1 = mean_ci_with(&x, seed, 4000).map_err(|e| TestCaseError::fail(e.to_string()))?.half_width();
        let h4 = mean_ci_with(&x4, seed, 4000).map_err(|e| TestCaseError::fail(e.to_string()))?.half_width();
        prop_assert!((1.75..=2.25).contains(&(h1 / h4)), "{h1} / {h4}");
    }

    #[test]
    fn wilson_is_inside_zero_one_around_the_rate_and_shrinks_as_one_over_root_n(
        n in 1u64..100_000,
        share in 0.0..=1.0f64,
    ) {
        let k = ((n as f64) * share).round() as u64;
        let r = wilson(k, n).map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert!(0.0 <= r.ci95[0] && r.ci95[0] <= r.mean && r.mean <= r.ci95[1] && r.ci95[1] <= 1.0, "{r:?}");
        prop_assert!(r.ci95[1] > r.ci95[0], "a Wilson interval is never a point: {r:?}");
        // Four times the trials at the same rate: narrower always, and half as wide once
        // n·p(1 − p) ≥ 10, where the normal approximation holds (the z²/n terms shrink a small
        // sample's interval by less: k = 1 of n = 2 only by 1.42×, k = 0 of 1 by 1.62×; over
        // every n < 3000 with n·p(1 − p) ≥ 10 the least ratio is 1.933, at k = 20 of 40).
        let r4 = wilson(4 * k, 4 * n).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let ratio = (r.ci95[1] - r.ci95[0]) / (r4.ci95[1] - r4.ci95[0]);
        prop_assert!(ratio >= 1.4, "{r:?} vs {r4:?}");
        if (k as f64) * ((n - k) as f64) / (n as f64) >= 10.0 {
            prop_assert!(ratio >= 1.93, "{r:?} vs {r4:?}");
        }
        if n >= 1000 && (0.1..=0.9).contains(&share) {
            prop_assert!(ratio <= 2.05, "{r:?} vs {r4:?}");
        }
    }
}
