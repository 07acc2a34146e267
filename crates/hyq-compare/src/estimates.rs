//! A policy's figures with their uncertainty (hyq-stats): per engine the mean of each
//! episode figure with its 95 % bootstrap interval and the rate of each way an episode ends
//! with its Wilson 95 % interval; per pair of engines the ratio of their means with its
//! interval. The bootstrap is seeded with the run's seed, so the same inputs give the same
//! report byte for byte.
//!
//! In `report.json` every estimate reads the same way: `{"mean": m, "ci95": [lo, hi]}` (a rate
//! also `"k"` and `"n"`, a ratio also `"excludes_one"`). Where no interval exists (a figure that
//! is not a finite number, a ratio whose denominator's resampled means reach 0) the key is left
//! out and the Markdown shows a dash.

use hyq_env::Reason;
use hyq_stats::{Pairing, Rate, Ratio, mean_ci, ratio_of_means, wilson};
use serde::Serialize;

/// Mean with its 95 % interval, sample standard deviation, min and max of some episodes'
/// values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Stats {
    /// Mean.
    pub mean: f64,
    /// The mean's 95 % percentile-bootstrap interval (10,000 resamples); absent when a value
    /// is not a finite number.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ci95: Option<[f64; 2]>,
    /// Sample standard deviation (0 for one episode).
    pub sd: f64,
    /// Smallest.
    pub min: f64,
    /// Largest.
    pub max: f64,
}

impl Stats {
    /// The statistics of `values`, the interval's resampling seeded with `seed`.
    pub(crate) fn of(values: &[f64], seed: u64) -> Self {
        let n = values.len();
        if n == 0 {
            return Self::default();
        }
        let mean = values.iter().sum::<f64>() / n as f64;
        let sd = if n > 1 {
            (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
        } else {
            0.0
        };
        let (min, max) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        Self {
            mean,
            ci95: mean_ci(values, seed).ok().map(|e| e.ci95),
            sd,
            min,
            max,
        }
    }

    /// "7.440 [7.204, 7.676]" (`decimals` places), a dash for a missing interval.
    pub fn text(&self, decimals: usize) -> String {
        match self.ci95 {
            Some([lo, hi]) => format!(
                "{:.decimals$} [{lo:.decimals$}, {hi:.decimals$}]",
                self.mean
            ),
            None => format!("{:.decimals$} [—]", self.mean),
        }
    }
}

/// How often an engine's episodes ended for each reason, each with its Wilson 95 % interval
/// (an episode can end for several reasons at once, so the rates need not sum to 1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Rates {
    /// Reached the goal (§6.1).
    pub reached: Rate,
    /// Fell (§6.3).
    pub fell: Rate,
    /// A joint at its limit (§6.2).
    pub joint_limit: Rate,
    /// Ran out of time (§6.4).
    pub timeout: Rate,
    /// The simulation diverged.
    pub diverged: Rate,
}

impl Rates {
    /// The rates over episodes that ended for `ends`; `None` for no episodes.
    pub(crate) fn of<'a>(ends: impl Iterator<Item = &'a [Reason]> + Clone) -> Option<Self> {
        let n = ends.clone().count() as u64;
        let rate = |r: Reason| {
            let k = ends.clone().filter(|e| e.contains(&r)).count() as u64;
            wilson(k, n).ok()
        };
        Some(Self {
            reached: rate(Reason::Reached)?,
            fell: rate(Reason::Fell)?,
            joint_limit: rate(Reason::JointLimit)?,
            timeout: rate(Reason::Timeout)?,
            diverged: rate(Reason::Diverged)?,
        })
    }

    /// The rates with their names as the Markdown shows them.
    pub(crate) fn named(&self) -> [(&'static str, &Rate); 5] {
        [
            ("reached the goal (§6.1)", &self.reached),
            ("fell", &self.fell),
            ("joint limit", &self.joint_limit),
            ("timeout", &self.timeout),
            ("diverged", &self.diverged),
        ]
    }
}

/// "18 of 20 (90 %) [70 %, 97 %]": the count, the rate and its Wilson interval.
pub fn rate_text(r: &Rate) -> String {
    format!(
        "{} of {} ({:.0} %) [{:.0} %, {:.0} %]",
        r.k,
        r.n,
        100.0 * r.mean,
        100.0 * r.ci95[0],
        100.0 * r.ci95[1]
    )
}

/// One engine's episode figures, a column each (the same episodes in the same order).
pub(crate) struct Columns {
    pub(crate) travel_m: Vec<f64>,
    pub(crate) distance_walked_m: Vec<f64>,
    pub(crate) ret: Vec<f64>,
    pub(crate) steps: Vec<f64>,
}

/// The ratio of two engines' means (the second's over the first's) of each figure with its
/// 95 % bootstrap interval. Episode k on both engines started from the same reset (the
/// streams depend on the seed alone), so the two are resampled as pairs. A figure is absent
/// where the ratio is unbounded (the first engine's resampled means reach 0 or change sign).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct PairRatios {
    /// Trunk travel toward the goal.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub travel_m: Option<Ratio>,
    /// K − D^T.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distance_walked_m: Option<Ratio>,
    /// The return.
    #[serde(rename = "return", skip_serializing_if = "Option::is_none")]
    pub ret: Option<Ratio>,
    /// Episode length (steps).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steps: Option<Ratio>,
}

impl PairRatios {
    /// `b`'s means over `a`'s, resampled with `seed`.
    pub(crate) fn of(a: &Columns, b: &Columns, seed: u64) -> Self {
        let ratio = |x: &[f64], y: &[f64]| ratio_of_means(y, x, Pairing::Paired, seed).ok();
        Self {
            travel_m: ratio(&a.travel_m, &b.travel_m),
            distance_walked_m: ratio(&a.distance_walked_m, &b.distance_walked_m),
            ret: ratio(&a.ret, &b.ret),
            steps: ratio(&a.steps, &b.steps),
        }
    }
}

/// "0.720 [0.690, 0.751] ≠ 1" (the interval excludes 1), "1.012 [0.95, 1.08]", or a dash.
pub fn ratio_text(r: Option<&Ratio>) -> String {
    match r {
        Some(r) => format!(
            "{:.3} [{:.3}, {:.3}]{}",
            r.mean,
            r.ci95[0],
            r.ci95[1],
            if r.excludes_one { " ≠ 1" } else { "" }
        ),
        None => "—".to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::{Columns, PairRatios, Rates, Stats, rate_text, ratio_text};
    use hyq_env::Reason;

    #[test]
    fn stats_are_the_mean_with_its_interval_the_sample_sd_and_range() {
        let s = Stats::of(&[1.0, 2.0, 3.0], 0);
        assert_eq!((s.mean, s.sd, s.min, s.max), (2.0, 1.0, 1.0, 3.0));
        let [lo, hi] = s.ci95.unwrap_or_else(|| panic!("an interval"));
        assert!(
            (1.0..2.0).contains(&lo) && hi > 2.0 && hi <= 3.0,
            "{lo} {hi}"
        );
        assert_eq!(s, Stats::of(&[1.0, 2.0, 3.0], 0), "seeded: the same again");
        let one = Stats::of(&[4.0], 0);
        assert_eq!((one.mean, one.ci95, one.sd), (4.0, Some([4.0, 4.0]), 0.0));
        assert_eq!(one.text(2), "4.00 [4.00, 4.00]");
        // A value that is not a number has no interval, and the JSON leaves the key out.
        let bad = Stats::of(&[1.0, f64::NAN], 0);
        assert_eq!((bad.ci95, bad.text(1)), (None, "NaN [—]".to_owned()));
    }

    #[test]
    fn rates_count_every_episode_whose_end_includes_the_reason() {
        let ends: Vec<&[Reason]> = vec![
            &[Reason::Reached],
            &[Reason::Fell, Reason::JointLimit],
            &[Reason::Timeout],
            &[Reason::Reached],
        ];
        let r = Rates::of(ends.iter().copied()).unwrap_or_else(|| panic!("rates"));
        assert_eq!((r.reached.k, r.reached.n), (2, 4));
        assert_eq!(
            (r.fell.k, r.joint_limit.k, r.timeout.k, r.diverged.k),
            (1, 1, 1, 0)
        );
        assert_eq!(rate_text(&r.reached), "2 of 4 (50 %) [15 %, 85 %]");
        assert_eq!(Rates::of(std::iter::empty()), None);
    }

    #[test]
    fn pair_ratios_are_the_second_over_the_first_and_refuse_a_mean_that_can_be_zero() {
        let col = |v: [f64; 4]| Columns {
            travel_m: v.to_vec(),
            distance_walked_m: v.map(|x| x - 2.5).to_vec(),
            ret: v.to_vec(),
            steps: vec![100.0; 4],
        };
        let (a, b) = (col([2.0, 2.2, 1.8, 2.0]), col([4.0, 4.4, 3.6, 4.0]));
        let r = PairRatios::of(&a, &b, 3);
        let travel = r.travel_m.unwrap_or_else(|| panic!("a ratio"));
        // b is exactly twice a, episode by episode: every paired resample's ratio is 2.
        assert_eq!(
            (travel.mean, travel.ci95, travel.excludes_one),
            (2.0, [2.0, 2.0], true)
        );
        assert_eq!(ratio_text(r.travel_m.as_ref()), "2.000 [2.000, 2.000] ≠ 1");
        assert_eq!(ratio_text(r.steps.as_ref()), "1.000 [1.000, 1.000]");
        // a's K − D^T is −0.5, −0.3, −0.7, −0.5: all of one sign, so the ratio exists; a
        // divisor whose values straddle 0 has none.
        assert!(r.distance_walked_m.is_some());
        let zero = col([0.5, -0.5, 0.5, -0.5]);
        assert_eq!(PairRatios::of(&zero, &b, 3).travel_m, None);
        assert_eq!(ratio_text(None), "—");
    }
}
