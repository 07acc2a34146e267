//! Records of the velocity-command task (`velocity`: the command, every task term unscaled, the
//! task's reward and the trunk's measured velocity) read back from JSONL and get a plot of their
//! own, `<stem>_velocity.png`: the command with the measured velocity, the step reward and a
//! panel per task term, in hyq-tasks' order; records written before the measured velocity was
//! recorded read and plot without it; records of the
//! spec's task get none; a non-finite value is refused by its column's name; a plot without the
//! task's columns is an error, not a blank image.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::*;
use hyq_render::{
    EpisodeSeries, PlotOptions, PlotRecord, REGULARIZER_PLOT_CELL, TermValues,
    VELOCITY_COMMAND_COLUMNS, VELOCITY_MEASURED_COLUMNS, VelocityPlotRecord, parse_jsonl,
    plot_episode, plot_velocity_terms,
};
use hyq_spec::RewardBreakdown;

/// `n` steps of the velocity task: a command that changes at step 30, and terms that vary.
fn velocity_episode(n: u64) -> Vec<PlotRecord> {
    (1..=n)
        .map(|t| {
            let x = t as f64;
            let command = if t < 30 {
                [0.5, 0.0, 0.2]
            } else {
                [-0.3, 0.1, -0.4]
            };
            let terms = hyq_tasks::TermValues {
                tracking_lin_vel: (x / 9.0).sin().abs(),
                tracking_ang_vel: 1.0 - 0.01 * x,
                torques: 1e4 * x,
                feet_air_time: -0.1 * (t % 7) as f64,
                ..Default::default()
            };
            PlotRecord {
                t,
                episode: Some(3),
                reward: 0.01 * terms.tracking_lin_vel,
                terms: TermValues::all(&RewardBreakdown::NEUTRAL),
                d_n: Some(1.0),
                distance_to_goal: 5.0,
                regularizers: None,
                velocity: Some(VelocityPlotRecord {
                    command,
                    terms,
                    reward: 0.01 * terms.tracking_lin_vel,
                    // A follower that lags its command by a tenth.
                    measured: Some(command.map(|c| 0.9 * c)),
                }),
            }
        })
        .collect()
}

#[test]
fn velocity_records_get_a_plot_of_the_command_and_every_task_term() {
    let dir = scratch_dir("velocity_plots");
    let records = velocity_episode(60);
    // The JSONL form reads back to the same records.
    let jsonl: String = records
        .iter()
        .map(|r| serde_json::to_string(r).unwrap() + "\n")
        .collect();
    assert!(
        jsonl
            .lines()
            .all(|l| l.contains(r#""velocity":{"command":"#))
    );
    let parsed = parse_jsonl(jsonl.as_bytes(), "mem").unwrap();
    assert_eq!(parsed.records, records);

    let series = EpisodeSeries::from_records(&parsed.records);
    let names: Vec<&str> = series.velocity.iter().map(|(n, _)| *n).collect();
    let expected: Vec<&str> = VELOCITY_COMMAND_COLUMNS
        .iter()
        .chain(hyq_tasks::TERM_NAMES)
        .copied()
        .collect();
    assert_eq!(names, expected);
    assert_eq!(series.velocity[0].1[28], 0.5);
    assert_eq!(series.velocity[0].1[29], -0.3);
    let torques = series
        .velocity
        .iter()
        .find(|(n, _)| *n == "torques")
        .unwrap();
    assert_eq!(torques.1[9], 1e5);
    // The trunk's measured velocity, in its own columns beside the command's.
    let measured: Vec<&str> = series.velocity_measured.iter().map(|(n, _)| *n).collect();
    assert_eq!(measured, VELOCITY_MEASURED_COLUMNS);
    assert_eq!(series.velocity_measured[0].1[28], 0.45);
    assert_eq!(series.velocity_measured[2].1[29], 0.9 * -0.4);

    let plots = plot_episode(&series, &PlotOptions::default(), &dir, "ep").unwrap();
    let path = plots.velocity.clone().unwrap();
    assert_eq!(path, dir.join("ep_velocity.png"));
    assert_eq!(plots.regularizers, None);
    // The command, the step reward and the 14 terms, two panels to a row.
    let rows = (hyq_tasks::TERM_NAMES.len() as u32 + 2).div_ceil(2);
    let (size, colours) = png_size_and_colours(&path);
    assert_eq!(
        size,
        (REGULARIZER_PLOT_CELL.0, 60 + rows * REGULARIZER_PLOT_CELL.1)
    );
    assert!(colours > 50, "{colours} colours");
    // The same series draws the same bytes; another command draws other bytes.
    let again = dir.join("again.png");
    plot_velocity_terms(&series, &PlotOptions::default(), &again).unwrap();
    assert_eq!(
        std::fs::read(&path).unwrap(),
        std::fs::read(&again).unwrap()
    );
    let mut other = series.clone();
    other.velocity[1].1[40] = 0.9;
    plot_velocity_terms(&other, &PlotOptions::default(), &again).unwrap();
    assert_ne!(
        std::fs::read(&path).unwrap(),
        std::fs::read(&again).unwrap()
    );
    // The measured velocity is drawn: another measured value draws other bytes.
    let mut other = series.clone();
    other.velocity_measured[0].1[40] = -0.2;
    plot_velocity_terms(&other, &PlotOptions::default(), &again).unwrap();
    assert_ne!(
        std::fs::read(&path).unwrap(),
        std::fs::read(&again).unwrap()
    );
    // A record written before the measured velocity was recorded reads and plots without it.
    let old: String = jsonl
        .lines()
        .map(|l| {
            let cut = l.find(r#","measured":["#).unwrap();
            let end = cut + l[cut..].find(']').unwrap() + 1;
            format!("{}{}\n", &l[..cut], &l[end..])
        })
        .collect();
    let old = parse_jsonl(old.as_bytes(), "old").unwrap();
    assert!(
        old.records
            .iter()
            .all(|r| r.velocity.unwrap().measured.is_none())
    );
    let old = EpisodeSeries::from_records(&old.records);
    assert!(old.velocity_measured.is_empty());
    assert_eq!(old.velocity, series.velocity);
    plot_velocity_terms(&old, &PlotOptions::default(), &again).unwrap();
    assert_ne!(
        std::fs::read(&path).unwrap(),
        std::fs::read(&again).unwrap()
    );

    // A non-finite value is refused by its column's name.
    let mut bad = series.clone();
    let k = names.iter().position(|n| *n == "foot_slip").unwrap();
    bad.velocity[k].1[7] = f64::INFINITY;
    let e = plot_velocity_terms(&bad, &PlotOptions::default(), dir.join("x.png"));
    assert!(e.unwrap_err().to_string().contains("foot_slip"));
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn records_of_the_spec_task_get_no_velocity_plot() {
    let dir = scratch_dir("no_velocity_plot");
    let mut records = velocity_episode(20);
    for r in &mut records {
        r.velocity = None;
    }
    let jsonl = serde_json::to_string(&records[0]).unwrap();
    assert!(!jsonl.contains("velocity"), "{jsonl}");
    let series = EpisodeSeries::from_records(&records);
    assert!(series.velocity.is_empty());
    let plots = plot_episode(&series, &PlotOptions::default(), &dir, "ep").unwrap();
    assert_eq!(plots.velocity, None);
    assert!(!dir.join("ep_velocity.png").exists());
    let e = plot_velocity_terms(&series, &PlotOptions::default(), dir.join("x.png"));
    assert!(e.unwrap_err().to_string().contains("velocity"));
    assert!(!dir.join("x.png").exists());
    std::fs::remove_dir_all(dir).unwrap();
}

/// Decodes a PNG and returns its size and how many distinct colours it has.
fn png_size_and_colours(path: &std::path::Path) -> ((u32, u32), usize) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    let mut colours: Vec<[u8; 3]> = buf.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    colours.sort_unstable();
    colours.dedup();
    ((info.width, info.height), colours.len())
}
