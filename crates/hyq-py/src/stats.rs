//! hyq-stats' interval estimates for Python (`hyq.stats`), so that the training scripts judge
//! their evaluations with the very code `hyq compare --policy` uses rather than a second
//! implementation: a mean with its seeded percentile-bootstrap 95 % interval, a rate with its
//! Wilson 95 % interval, and a ratio of means with its bootstrap interval. Each returns the
//! numbers of hyq-stats' estimate; `hyq/stats.py` shapes them as `{"mean", "ci95", ...}`.
//! hyq-stats' refusals (no values, a value that is not a finite number, k > n, a denominator
//! whose mean can be 0) arrive as `ValueError` with its one-line message.

use std::panic::{UnwindSafe, catch_unwind};

use hyq_stats::{Pairing, StatsError};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// Runs `f`: a refusal is a `ValueError` with hyq-stats' message; a panic (no known input
/// causes one) a `RuntimeError` rather than PyO3's `PanicException`, which `except Exception`
/// does not catch.
fn estimate<T>(f: impl FnOnce() -> Result<T, StatsError> + UnwindSafe) -> PyResult<T> {
    match catch_unwind(f) {
        Ok(result) => result.map_err(|e| PyValueError::new_err(e.to_string())),
        Err(_) => Err(PyRuntimeError::new_err(
            "hyq.stats: internal error (a panic in hyq-stats); please report it",
        )),
    }
}

/// `(mean, lo, hi)`: the mean of `values` with its 95 % percentile-bootstrap interval from
/// hyq-stats' 10,000 resamples seeded with `seed`.
#[pyfunction]
pub fn stats_mean_ci(values: Vec<f64>, seed: u64) -> PyResult<(f64, f64, f64)> {
    let e = estimate(|| hyq_stats::mean_ci(&values, seed))?;
    Ok((e.mean, e.ci95[0], e.ci95[1]))
}

/// `(rate, lo, hi)`: k of n with its Wilson 95 % interval.
#[pyfunction]
pub fn stats_wilson(k: u64, n: u64) -> PyResult<(f64, f64, f64)> {
    let r = estimate(|| hyq_stats::wilson(k, n))?;
    Ok((r.mean, r.ci95[0], r.ci95[1]))
}

/// `(ratio, lo, hi, excludes_one)`: the mean of `numerator` over that of `denominator` with its
/// bootstrap 95 % interval, the samples resampled as pairs when `paired`.
#[pyfunction]
pub fn stats_ratio_of_means(
    numerator: Vec<f64>,
    denominator: Vec<f64>,
    paired: bool,
    seed: u64,
) -> PyResult<(f64, f64, f64, bool)> {
    let pairing = if paired {
        Pairing::Paired
    } else {
        Pairing::Independent
    };
    let r = estimate(|| hyq_stats::ratio_of_means(&numerator, &denominator, pairing, seed))?;
    Ok((r.mean, r.ci95[0], r.ci95[1], r.excludes_one))
}

/// Adds the functions to the extension module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(stats_mean_ci, m)?)?;
    m.add_function(wrap_pyfunction!(stats_wilson, m)?)?;
    m.add_function(wrap_pyfunction!(stats_ratio_of_means, m)?)?;
    m.add("STATS_RESAMPLES", hyq_stats::RESAMPLES)?;
    Ok(())
}
