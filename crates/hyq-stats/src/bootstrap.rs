//! The percentile bootstrap (Efron & Tibshirani 1993, section 13.3), seeded: B resamples of the
//! episodes with replacement, the statistic of each, and the 2.5 % and 97.5 % quantiles of
//! those B values as the 95 % interval. The percentile form is rliable's default for its
//! interval estimates; it needs no distributional assumption and is exact for a constant
//! sample (its interval is the point).
//!
//! Resampling indices come from ChaCha8 seeded with the caller's seed (`seed_from_u64`), each
//! index the high half of a 64 × 64-bit product (bias below n/2⁶⁴), so the same values and seed
//! give the same interval bit for bit on every platform. Quantiles interpolate linearly between
//! order statistics (Hyndman & Fan's type 7, NumPy's default).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::error::StatsError;
use crate::estimate::{Estimate, Ratio};

/// Resamples per interval.
pub const RESAMPLES: usize = 10_000;

/// Whether a ratio's two samples are resampled together (episode k of both drawn as one, for
/// samples whose k-th values share a start, such as episodes run from the same seeds on two
/// engines) or each on its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pairing {
    /// One index per draw for both samples (they must be of the same length).
    Paired,
    /// Each sample resampled independently.
    Independent,
}

/// The mean of `values` with its percentile-bootstrap 95 % interval from [`RESAMPLES`]
/// resamples seeded with `seed`.
pub fn mean_ci(values: &[f64], seed: u64) -> Result<Estimate, StatsError> {
    mean_ci_with(values, seed, RESAMPLES)
}

/// As [`mean_ci`] with `resamples` resamples (at least 1).
pub fn mean_ci_with(values: &[f64], seed: u64, resamples: usize) -> Result<Estimate, StatsError> {
    let sample = Sample::new(values)?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut means: Vec<f64> = (0..resamples.max(1))
        .map(|_| sample.resampled_mean(&mut rng))
        .collect();
    let [lo, hi] = percentile_interval(&mut means);
    let mean = sample.mean();
    // Rounding of a near-constant sample can put the mean a hair outside the resampled means.
    Ok(Estimate {
        mean,
        ci95: [lo.min(mean), hi.max(mean)],
    })
}

/// The ratio of the means of `numerator` and `denominator` with its percentile-bootstrap 95 %
/// interval ([`RESAMPLES`] resamples seeded with `seed`). Refused when the denominator's mean or
/// any resampled denominator mean is 0 or of the other sign (the ratio is unbounded there).
pub fn ratio_of_means(
    numerator: &[f64],
    denominator: &[f64],
    pairing: Pairing,
    seed: u64,
) -> Result<Ratio, StatsError> {
    ratio_of_means_with(numerator, denominator, pairing, seed, RESAMPLES)
}

/// As [`ratio_of_means`] with `resamples` resamples (at least 1).
pub fn ratio_of_means_with(
    numerator: &[f64],
    denominator: &[f64],
    pairing: Pairing,
    seed: u64,
    resamples: usize,
) -> Result<Ratio, StatsError> {
    let (num, den) = (Sample::new(numerator)?, Sample::new(denominator)?);
    if pairing == Pairing::Paired && numerator.len() != denominator.len() {
        return Err(StatsError::Unpaired {
            numerator: numerator.len(),
            denominator: denominator.len(),
        });
    }
    let (m_num, m_den) = (num.mean(), den.mean());
    let spans_zero = StatsError::DenominatorSpansZero { mean: m_den };
    if m_den == 0.0 {
        return Err(spans_zero);
    }
    let mean = m_num / m_den;
    if !mean.is_finite() {
        return Err(StatsError::Overflow {
            numerator: m_num,
            denominator: m_den,
        });
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut ratios = Vec::with_capacity(resamples.max(1));
    for _ in 0..resamples.max(1) {
        let (a, b) = match pairing {
            Pairing::Paired => num.paired_means(&den, &mut rng),
            Pairing::Independent => (num.resampled_mean(&mut rng), den.resampled_mean(&mut rng)),
        };
        if b == 0.0 || b.signum() != m_den.signum() {
            return Err(spans_zero);
        }
        let r = a / b;
        if !r.is_finite() {
            return Err(StatsError::Overflow {
                numerator: a,
                denominator: b,
            });
        }
        ratios.push(r);
    }
    let [lo, hi] = percentile_interval(&mut ratios);
    let ci95 = [lo.min(mean), hi.max(mean)];
    Ok(Ratio {
        mean,
        ci95,
        excludes_one: !(ci95[0] <= 1.0 && 1.0 <= ci95[1]),
    })
}

/// Checked values, and whether their means are summed after dividing by n (when the plain sum
/// of their sizes overflows): every finite input gives a finite mean. Means are held within
/// the values' range, where rounding could put them a hair outside.
struct Sample<'a> {
    values: &'a [f64],
    divide_first: bool,
    range: [f64; 2],
}

impl<'a> Sample<'a> {
    fn new(values: &'a [f64]) -> Result<Self, StatsError> {
        if values.is_empty() {
            return Err(StatsError::Empty);
        }
        if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(StatsError::NonFinite { index, value });
        }
        let divide_first = !values.iter().map(|v| v.abs()).sum::<f64>().is_finite();
        let range = values
            .iter()
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], &v| {
                [lo.min(v), hi.max(v)]
            });
        Ok(Self {
            values,
            divide_first,
            range,
        })
    }

    fn n(&self) -> f64 {
        self.values.len() as f64
    }

    fn mean(&self) -> f64 {
        self.mean_of(self.values.iter().copied())
    }

    fn mean_of(&self, values: impl Iterator<Item = f64>) -> f64 {
        let n = self.n();
        let mean = if self.divide_first {
            values.map(|v| v / n).sum()
        } else {
            values.sum::<f64>() / n
        };
        mean.clamp(self.range[0], self.range[1])
    }

    fn resampled_mean(&self, rng: &mut ChaCha8Rng) -> f64 {
        let len = self.values.len();
        self.mean_of((0..len).map(|_| self.values[index(rng, len)]))
    }

    /// Both samples' means over the same drawn indices (same lengths).
    fn paired_means(&self, other: &Sample<'_>, rng: &mut ChaCha8Rng) -> (f64, f64) {
        let len = self.values.len();
        let idx: Vec<usize> = (0..len).map(|_| index(rng, len)).collect();
        (
            self.mean_of(idx.iter().map(|&i| self.values[i])),
            other.mean_of(idx.iter().map(|&i| other.values[i])),
        )
    }
}

/// A uniform index below `len` (> 0): the high 64 bits of a 64 × 64-bit product.
fn index(rng: &mut ChaCha8Rng, len: usize) -> usize {
    ((u128::from(rng.next_u64()) * len as u128) >> 64) as usize
}

/// The 2.5 % and 97.5 % quantiles of `values` (not empty, all finite), sorted in place.
fn percentile_interval(values: &mut [f64]) -> [f64; 2] {
    values.sort_by(f64::total_cmp);
    [quantile(values, 0.025), quantile(values, 0.975)]
}

/// The `p` quantile of sorted `values` (type 7: linear between order statistics).
fn quantile(sorted: &[f64], p: f64) -> f64 {
    let h = (sorted.len() - 1) as f64 * p;
    let below = h.floor() as usize;
    let above = (below + 1).min(sorted.len() - 1);
    let (a, b) = (sorted[below], sorted[above]);
    let t = h - h.floor();
    // a + t(b − a), written to stay finite when b − a overflows, and held between a and b
    // where rounding would step outside (a = b included).
    let step = b - a;
    let q = if step.is_finite() {
        a + t * step
    } else {
        a * (1.0 - t) + b * t
    };
    q.clamp(a, b)
}

#[cfg(test)]
mod tests {
    use super::{Pairing, quantile, ratio_of_means_with};
    use crate::StatsError;

    #[test]
    fn quantiles_interpolate_between_order_statistics() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0];
        assert_eq!(quantile(&v, 0.0), 1.0);
        assert_eq!(quantile(&v, 1.0), 5.0);
        assert_eq!(quantile(&v, 0.5), 3.0);
        assert_eq!(quantile(&v, 0.125), 1.5);
        assert_eq!(quantile(&[7.0], 0.975), 7.0);
    }

    #[test]
    fn a_denominator_that_can_be_zero_is_refused() {
        let e = ratio_of_means_with(&[1.0, 2.0], &[-1.0, 1.5], Pairing::Paired, 0, 200);
        assert!(
            matches!(e, Err(StatsError::DenominatorSpansZero { .. })),
            "{e:?}"
        );
        let e = ratio_of_means_with(&[1.0], &[0.0], Pairing::Independent, 0, 200);
        assert_eq!(e, Err(StatsError::DenominatorSpansZero { mean: 0.0 }));
        let e = ratio_of_means_with(&[1.0, 2.0], &[1.0], Pairing::Paired, 0, 200);
        assert_eq!(
            e,
            Err(StatsError::Unpaired {
                numerator: 2,
                denominator: 1
            })
        );
    }
}
