//! The shapes every estimate is reported in, so that a script reads any figure the same way:
//! `{"mean": m, "ci95": [lo, hi]}`, a rate adding `"k"` and `"n"`, a ratio adding whether its
//! interval excludes 1.

use serde::Serialize;

/// A mean with its 95 % confidence interval (`lo ≤ mean ≤ hi`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Estimate {
    /// The sample mean.
    pub mean: f64,
    /// The interval's lower and upper ends.
    pub ci95: [f64; 2],
}

impl Estimate {
    /// Half the interval's width.
    pub fn half_width(&self) -> f64 {
        0.5 * (self.ci95[1] - self.ci95[0])
    }

    /// Whether `x` lies in the interval (ends included).
    pub fn contains(&self, x: f64) -> bool {
        self.ci95[0] <= x && x <= self.ci95[1]
    }
}

/// A rate (k of n) with its Wilson 95 % interval.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Rate {
    /// k / n.
    pub mean: f64,
    /// The Wilson interval's lower and upper ends, within [0, 1].
    pub ci95: [f64; 2],
    /// Successes.
    pub k: u64,
    /// Trials.
    pub n: u64,
}

/// The ratio of two means with its 95 % bootstrap interval.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Ratio {
    /// The numerator's mean over the denominator's.
    pub mean: f64,
    /// The interval's lower and upper ends.
    pub ci95: [f64; 2],
    /// Whether 1 lies outside the interval: the two means differ at the 95 % level.
    pub excludes_one: bool,
}
