//! The Wilson score interval for a rate (Wilson 1927; the interval rliable and Agresti & Coull
//! recommend over the normal one): with p̂ = k/n and z the standard normal's 97.5 % quantile,
//!
//! centre = (p̂ + z²/2n) / (1 + z²/n),  half-width = z·√(p̂(1 − p̂)/n + z²/4n²) / (1 + z²/n).
//!
//! Unlike p̂ ± z·√(p̂(1 − p̂)/n) it stays inside [0, 1] and is not empty at k = 0 or k = n.

use crate::error::StatsError;
use crate::estimate::Rate;

/// The standard normal's 97.5 % quantile.
pub const Z95: f64 = 1.959_963_984_540_054;

/// The rate k/n with its Wilson 95 % interval; refuses n = 0 and k > n.
pub fn wilson(k: u64, n: u64) -> Result<Rate, StatsError> {
    if n == 0 {
        return Err(StatsError::NoTrials);
    }
    if k > n {
        return Err(StatsError::MoreSuccessesThanTrials { k, n });
    }
    let nf = n as f64;
    let p = k as f64 / nf;
    let z2 = Z95 * Z95;
    let denominator = 1.0 + z2 / nf;
    let centre = (p + z2 / (2.0 * nf)) / denominator;
    let half = Z95 * (p * (1.0 - p) / nf + z2 / (4.0 * nf * nf)).sqrt() / denominator;
    // At k = 0 (k = n) the lower (upper) end is 0 (1) in exact arithmetic; rounding must not
    // put it a hair beside, nor leave p̂ outside.
    let lo = if k == 0 {
        0.0
    } else {
        (centre - half).clamp(0.0, p)
    };
    let hi = if k == n {
        1.0
    } else {
        (centre + half).clamp(p, 1.0)
    };
    Ok(Rate {
        mean: p,
        ci95: [lo, hi],
        k,
        n,
    })
}

#[cfg(test)]
mod tests {
    use super::wilson;
    use crate::StatsError;

    #[test]
    fn matches_published_values() {
        // Newcombe (1998), Table I: 81 of 263 → [0.2553, 0.3662]; 15 of 148 → [0.0624, 0.1605];
        // 0 of 20 → [0, 0.1611]; 1 of 29 → [0.0061, 0.1718].
        let cases = [
            (81, 263, [0.2553, 0.3662]),
            (15, 148, [0.0624, 0.1605]),
            (0, 20, [0.0, 0.1611]),
            (1, 29, [0.0061, 0.1718]),
        ];
        for (k, n, [lo, hi]) in cases {
            let r = wilson(k, n).unwrap_or_else(|e| panic!("{e}"));
            assert!((r.ci95[0] - lo).abs() < 5e-5, "{k}/{n}: {:?}", r.ci95);
            assert!((r.ci95[1] - hi).abs() < 5e-5, "{k}/{n}: {:?}", r.ci95);
            assert_eq!(r.mean, k as f64 / n as f64);
        }
    }

    #[test]
    fn refuses_no_trials_and_more_successes_than_trials() {
        assert_eq!(wilson(0, 0), Err(StatsError::NoTrials));
        assert_eq!(
            wilson(3, 2),
            Err(StatsError::MoreSuccessesThanTrials { k: 3, n: 2 })
        );
        assert_eq!(
            wilson(3, 2).map_err(|e| e.to_string()),
            Err("3 successes out of 2 trials: more successes than trials".to_owned())
        );
    }
}
