//! Interval estimates for judging a policy from a handful of episodes: how sure a figure is,
//! not only what it is.
//!
//! - [`mean_ci`]: a mean with its 95 % percentile-bootstrap interval ([`RESAMPLES`] resamples,
//!   seeded: the same values and seed give the same interval bit for bit);
//! - [`wilson`]: a rate k of n with its Wilson 95 % interval;
//! - [`ratio_of_means`]: the ratio of two means with its bootstrap interval, and whether the
//!   interval excludes 1 (the two means differ at the 95 % level).
//!
//! Every estimate serialises as `{"mean": m, "ci95": [lo, hi]}` (a [`Rate`] adds `"k"` and
//! `"n"`, a [`Ratio`] `"excludes_one"`). Empty or non-finite input is refused with a
//! [`StatsError`] naming what was wrong; every finite input gives finite output.
//!
//! Pure: no I/O, no clock, no global state.

mod bootstrap;
mod error;
mod estimate;
mod wilson;

pub use bootstrap::{
    Pairing, RESAMPLES, mean_ci, mean_ci_with, ratio_of_means, ratio_of_means_with,
};
pub use error::StatsError;
pub use estimate::{Estimate, Rate, Ratio};
pub use wilson::{Z95, wilson};
