//! A plot of values whose range spans more than f64 can hold (a reward of +1e308 on one step and
//! −1e308 on another, a term near f64::MAX, D_n of 1e308) finishes and writes both PNGs: the
//! axes are padded without overflowing to infinity, on which the plotting library never stops.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::sync::mpsc;
use std::time::Duration;

use common::scratch_dir;
use hyq_render::{EpisodeSeries, PlotOptions, PlotRecord, TermValues, plot_episode};
use hyq_spec::RewardBreakdown;

/// Longer than any plot takes (well under a second each); a hang becomes a failure instead of a
/// test run that never ends.
const PATIENCE: Duration = Duration::from_secs(120);

fn record(t: u64, reward: f64, r_e: f64, d_n: f64) -> PlotRecord {
    PlotRecord {
        t,
        episode: Some(1),
        reward,
        terms: TermValues::all(&RewardBreakdown {
            r_e,
            ..RewardBreakdown::NEUTRAL
        }),
        d_n: Some(d_n),
        distance_to_goal: 1.0,
        regularizers: None,
        velocity: None,
    }
}

#[test]
fn values_spanning_more_than_f64_are_plotted_and_the_plot_finishes() {
    let records = [
        record(1, 1e308, f64::MAX, 0.5),
        record(2, -1e308, -f64::MAX, 1e308),
        record(3, 0.0, 1.7e308, 1.0),
    ];
    let dir = scratch_dir("beyond-f64");
    let (done, wait) = mpsc::channel();
    let out = dir.clone();
    std::thread::spawn(move || {
        let series = EpisodeSeries::from_records(&records);
        let options = PlotOptions {
            k_exp: Some(5.0),
            ..PlotOptions::default()
        };
        let _ = done.send(plot_episode(&series, &options, &out, "ep").map_err(|e| e.to_string()));
    });
    let plots = wait
        .recv_timeout(PATIENCE)
        .unwrap_or_else(|_| panic!("the plots did not finish within {PATIENCE:?}"))
        .unwrap();
    assert!(plots.rewards.is_file() && plots.distance.is_file());
    std::fs::remove_dir_all(dir).unwrap();
}

/// Plots `records` as one episode in a thread, failing if it does not finish in [`PATIENCE`].
fn plots_finish(records: Vec<PlotRecord>, tag: &str) {
    let dir = scratch_dir(tag);
    let (done, wait) = mpsc::channel();
    let out = dir.clone();
    std::thread::spawn(move || {
        let series = EpisodeSeries::from_records(&records);
        let options = PlotOptions {
            k_exp: Some(5.0),
            ..PlotOptions::default()
        };
        let _ = done.send(plot_episode(&series, &options, &out, "ep").map_err(|e| e.to_string()));
    });
    let plots = wait
        .recv_timeout(PATIENCE)
        .unwrap_or_else(|_| panic!("{tag}: the plots did not finish within {PATIENCE:?}"))
        .unwrap();
    assert!(plots.rewards.is_file() && plots.distance.is_file());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_huge_d_n_alone_does_not_hang_the_plot() {
    // One line with D_n = 1.7e308 kept the plotter at full CPU forever: the distance panel's
    // axis was D_n · 1.08, infinite.
    plots_finish(vec![record(1, 0.0, 0.0, 1.7e308)], "huge-d-n");
}

#[test]
fn every_series_at_the_end_of_f64_is_plotted_and_the_plot_finishes() {
    // Each series of a record at ±f64::MAX on some step: the time axis, the reward, a term,
    // D_n (both panels) and D.
    let mut far = record(4, 0.0, 0.0, f64::MAX);
    far.distance_to_goal = f64::MAX;
    let records = vec![
        record(1, f64::MAX, 0.0, 0.5),
        record(2, -f64::MAX, -f64::MAX, 1.0),
        record(3, 0.0, f64::MAX, -f64::MAX),
        far,
        record(u64::MAX, 0.0, 0.0, 0.0),
    ];
    plots_finish(records, "every-series");
}
