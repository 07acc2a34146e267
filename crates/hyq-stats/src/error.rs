//! What an estimate refuses: no values, a value that is not a finite number, a rate with more
//! successes than trials, and a ratio whose denominator's mean can be 0.

use thiserror::Error;

/// Why an estimate could not be made. Each message names what was wrong in one line.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum StatsError {
    /// An estimate of nothing.
    #[error("no values to estimate from")]
    Empty,
    /// A value that is NaN or infinite.
    #[error("value {index} is {value}, not a finite number")]
    NonFinite {
        /// Its position (0 for the first).
        index: usize,
        /// The value.
        value: f64,
    },
    /// A rate of no trials.
    #[error("a rate of 0 trials")]
    NoTrials,
    /// A rate with more successes than trials.
    #[error("{k} successes out of {n} trials: more successes than trials")]
    MoreSuccessesThanTrials {
        /// Successes.
        k: u64,
        /// Trials.
        n: u64,
    },
    /// Paired samples of different lengths.
    #[error("paired samples of different lengths ({numerator} and {denominator} values)")]
    Unpaired {
        /// The numerator's values.
        numerator: usize,
        /// The denominator's values.
        denominator: usize,
    },
    /// A ratio whose denominator's mean is 0 or whose resampled denominator means reach 0 or
    /// change sign: the ratio is unbounded.
    #[error(
        "the denominator's mean is {mean} and its resampled means reach 0 or change sign: the ratio is unbounded"
    )]
    DenominatorSpansZero {
        /// The denominator's sample mean.
        mean: f64,
    },
    /// A ratio too large for a finite number.
    #[error("the ratio of the means overflows ({numerator} / {denominator})")]
    Overflow {
        /// The numerator's mean.
        numerator: f64,
        /// The denominator's mean.
        denominator: f64,
    },
}
