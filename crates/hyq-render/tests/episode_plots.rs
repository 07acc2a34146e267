//! The environment's JSONL step records parse into episodes, and each episode's two plots are
//! written as PNGs of the documented size with real content; the R_e points a plot draws sit on
//! the spec's curve for records made by the spec's rules; bad records are refused by line and
//! key.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::*;
use hyq_render::{
    DISTANCE_PLOT_SIZE, EpisodeSeries, PlotError, PlotOptions, PlotRecord, REGULARIZER_PLOT_CELL,
    REWARD_PLOT_SIZE, TermValues, cumulative, parse_jsonl, plot_distance, plot_episode, plot_jsonl,
    split_episodes,
};
use hyq_spec::nalgebra::{Point3, UnitQuaternion};
use hyq_spec::reward::exponential::cumulative_exponential_reward;
use hyq_spec::{EpisodeRules, RobotDescription, StepSnapshot, TaskConfig};

const K_EXP: f64 = 5.0;

/// An episode scored by the spec's rules: the trunk walks 4 m towards a goal 5 m away, yawing a
/// little (so m_yaw dips), then falls (so the fall penalty is paid).
fn spec_episode() -> Vec<PlotRecord> {
    let config = TaskConfig {
        base_rew_scaling: Some(1.0),
        norm_rew_scaling: Some(10.0),
        exp_rew_scaling: Some(K_EXP),
        fall_penalty: 20.0,
        ..TaskConfig::default()
    };
    let robot = RobotDescription::hyq_spec();
    let angles: Vec<f64> = robot
        .joint_ranges()
        .iter()
        .map(|r| 0.5 * (r.lower() + r.upper()))
        .collect();
    let start = Point3::new(0.0, 0.0, 0.6);
    let rules = EpisodeRules::new(&config, start, Point3::new(5.0, 0.0, 0.6)).unwrap();
    let mut previous = start;
    let mut records = Vec::new();
    for step in 1..=200u64 {
        let position = Point3::new(0.02 * step as f64, 0.0, 0.6);
        let yaw = 0.08 * (step as f64 / 15.0).sin();
        let outcome = rules
            .evaluate_step(&StepSnapshot {
                step,
                previous_position: previous,
                position,
                orientation: UnitQuaternion::from_euler_angles(0.0, 0.0, yaw),
                joint_angles: &angles,
                joint_ranges: robot.joint_ranges(),
                trunk_contact: step == 200,
            })
            .unwrap();
        previous = position;
        let b = outcome.reward;
        records.push(PlotRecord {
            t: step,
            episode: None,
            reward: b.total,
            terms: TermValues::all(&b),
            d_n: outcome.normalised_distance,
            distance_to_goal: outcome.distance,
            regularizers: None,
            velocity: None,
        });
    }
    records
}

fn to_jsonl(records: &[PlotRecord]) -> String {
    records
        .iter()
        .map(|r| serde_json::to_string(r).unwrap() + "\n")
        .collect()
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

#[test]
fn episode_plots_are_written_with_their_size_and_real_content() {
    let dir = scratch_dir("plots");
    let series = EpisodeSeries::from_records(&spec_episode());
    let plots = plot_episode(&series, &PlotOptions::default(), &dir, "ep").unwrap();
    assert_eq!(plots.rewards, dir.join("ep_rewards.png"));
    assert_eq!(plots.distance, dir.join("ep_distance.png"));
    assert_eq!(
        plots.regularizers, None,
        "no regularisers in the records, no plot of them"
    );
    assert!(!dir.join("ep_regularizers.png").exists());
    for (path, size) in [
        (&plots.rewards, REWARD_PLOT_SIZE),
        (&plots.distance, DISTANCE_PLOT_SIZE),
    ] {
        let (got, colours) = png_size_and_colours(path);
        assert_eq!(got, size, "{}", path.display());
        // Lines, text, legends and anti-aliasing: far from a single colour.
        assert!(colours > 50, "{} has {colours} colours", path.display());
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn r_e_points_of_a_spec_episode_sit_on_the_spec_curve() {
    let series = EpisodeSeries::from_records(&spec_episode());
    let sum_r_e = cumulative(series.term("r_e").unwrap());
    for (d_n, r_e) in series.d_n.iter().zip(&sum_r_e) {
        let d_n = d_n.unwrap();
        let curve = cumulative_exponential_reward(d_n, K_EXP);
        assert!(
            (curve - r_e).abs() < 1e-9,
            "D_n {d_n}: Σ r_e {r_e} vs R_e {curve}"
        );
    }
    // The episode exercises the multiplier and the fall penalty panels.
    assert!(series.term("m_yaw").unwrap().iter().any(|&m| m < 1.0));
    assert_eq!(series.term("fall_penalty").unwrap().last(), Some(&20.0));
}

#[test]
fn jsonl_with_several_episodes_gives_one_plot_pair_each() {
    let dir = scratch_dir("jsonl");
    let one = spec_episode();
    // Two episodes back to back: t starts again, which marks a reset.
    let text = to_jsonl(&one[..50]) + "\n" + &to_jsonl(&one[..30]);
    let path = dir.join("run.jsonl");
    std::fs::write(&path, text).unwrap();
    let options = PlotOptions {
        k_exp: Some(K_EXP),
        env_dt_s: Some(0.01),
        ..PlotOptions::default()
    };
    let plotted = plot_jsonl(&path, &options, dir.join("plots")).unwrap();
    assert_eq!(plotted.torn_last_line, None);
    let plots = plotted.plots;
    assert_eq!(plots.len(), 2);
    assert!(plots[1].rewards.ends_with("episode_002_rewards.png"));
    for p in &plots {
        assert!(p.rewards.is_file() && p.distance.is_file());
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn episodes_split_on_an_episode_key_or_a_time_reset() {
    let records = spec_episode();
    let mut numbered: Vec<PlotRecord> = records[..6].to_vec();
    for (i, r) in numbered.iter_mut().enumerate() {
        r.episode = Some(if i < 4 { 7 } else { 8 });
        r.t = i as u64 + 1; // t never resets: only the key splits
    }
    let split = split_episodes(&numbered);
    assert_eq!(split.iter().map(|e| e.len()).collect::<Vec<_>>(), [4, 2]);

    let mut reset = records[..5].to_vec();
    reset.extend_from_slice(&records[..3]);
    let split = split_episodes(&reset);
    assert_eq!(split.iter().map(|e| e.len()).collect::<Vec<_>>(), [5, 3]);
    assert!(split_episodes(&[]).is_empty());
}

#[test]
fn records_in_the_environments_schema_parse_with_extra_keys_ignored() {
    // `hyq-env`'s record (its `record` module): more keys than the plots need, `m_height` only
    // when the height penalty is on, `d_n` null when K is too small.
    let line = r#"{"episode":3,"t":1,"obs":[0.1,0.2],"action":[0.0],"joint_targets":[0.5],"reward":0.5,"terms":{"r_b":0.1,"r_n":0.2,"r_e":0.2,"r_reach":0.0,"m_yaw":1.0,"m_pitch":1.0,"joint_penalty":0.0,"fall_penalty":0.0},"yaw":0.0,"pitch":0.0,"distance_to_goal":4.9,"d_n":null,"goal":[5.0,0.0,0.6],"initial_position":[0.0,0.0,0.6],"terminated":false,"truncated":false,"reasons":[]}"#;
    let records = parse_jsonl(line.as_bytes(), "input").unwrap().records;
    assert_eq!(records.len(), 1);
    let r = &records[0];
    assert_eq!((r.episode, r.t, r.d_n), (Some(3), 1, None));
    assert_eq!(r.terms.values.m_height, 1.0);
    assert_eq!(r.terms.values.r_n, 0.2);
    let with_height = line.replace(r#""m_pitch":1.0,"#, r#""m_pitch":1.0,"m_height":0.5,"#);
    let records = parse_jsonl(with_height.as_bytes(), "input")
        .unwrap()
        .records;
    assert_eq!(records[0].terms.values.m_height, 0.5);
}

#[test]
fn bad_records_are_refused_with_line_and_key() {
    let good = to_jsonl(&spec_episode()[..2]);
    let missing = r#"{"t":3,"reward":0.5,"d_n":0.9,"distance_to_goal":4.5}"#;
    let err = parse_jsonl((good.clone() + missing).as_bytes(), "run.jsonl").unwrap_err();
    let msg = err.to_string();
    assert!(matches!(err, PlotError::Json { line: 3, .. }), "{msg}");
    assert!(
        msg.contains("run.jsonl line 3") && msg.contains("terms"),
        "{msg}"
    );

    let err = parse_jsonl("not json\n".as_bytes(), "x").unwrap_err();
    assert!(matches!(err, PlotError::Json { line: 1, .. }), "{err}");
}

#[test]
fn bad_series_and_options_are_refused_by_name() {
    let dir = scratch_dir("bad-series");
    let good = EpisodeSeries::from_records(&spec_episode());

    let err = plot_distance(
        &EpisodeSeries::new(),
        &PlotOptions::default(),
        dir.join("a.png"),
    )
    .unwrap_err();
    assert!(matches!(err, PlotError::Empty { .. }), "{err}");

    let mut nan = good.clone();
    nan.terms[hyq_spec::terms::term_index("r_n").unwrap()][17] = f64::NAN;
    let err = plot_distance(&nan, &PlotOptions::default(), dir.join("b.png")).unwrap_err();
    assert!(
        matches!(
            err,
            PlotError::NonFinite {
                field: "r_n",
                index: 17,
                ..
            }
        ),
        "{err}"
    );

    let mut short = good.clone();
    short.terms[hyq_spec::terms::term_index("m_pitch").unwrap()].pop();
    let err = plot_distance(&short, &PlotOptions::default(), dir.join("c.png")).unwrap_err();
    assert!(
        matches!(
            err,
            PlotError::Length {
                field: "m_pitch",
                ..
            }
        ),
        "{err}"
    );

    let options = PlotOptions {
        k_exp: Some(-1.0),
        ..PlotOptions::default()
    };
    let err = plot_distance(&good, &options, dir.join("d.png")).unwrap_err();
    assert!(matches!(err, PlotError::KExp { .. }), "{err}");
    let options = PlotOptions {
        env_dt_s: Some(0.0),
        ..PlotOptions::default()
    };
    let err = plot_distance(&good, &options, dir.join("d.png")).unwrap_err();
    assert!(matches!(err, PlotError::EnvDt { .. }), "{err}");

    // r_e off: the distance plot is still drawn, without the curve.
    let off = PlotOptions {
        k_exp: None,
        ..PlotOptions::default()
    };
    plot_distance(&good, &off, dir.join("e.png")).unwrap();
    assert!(png_size_and_colours(&dir.join("e.png")).1 > 50);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_torn_last_line_is_left_out_and_reported_while_a_bad_line_before_it_is_an_error() {
    // A run stopped by a full disk or Ctrl-C leaves a last line without its end.
    let good = to_jsonl(&spec_episode()[..3]);
    let full = to_jsonl(&spec_episode()[..4]);
    let torn = &full[..good.len() + 40];
    let read = parse_jsonl(torn.as_bytes(), "run.jsonl").unwrap();
    assert_eq!(read.records.len(), 3);
    assert_eq!(read.torn_last_line, Some(4));
    let whole = parse_jsonl(good.as_bytes(), "run.jsonl").unwrap();
    assert_eq!((whole.records.len(), whole.torn_last_line), (3, None));

    // Torn in the middle, or a last line that is whole but wrong: errors, as before.
    let middle = format!("{}\n{}", &full[..good.len() + 40], &good);
    let err = parse_jsonl(middle.as_bytes(), "run.jsonl").unwrap_err();
    assert!(matches!(err, PlotError::Json { line: 4, .. }), "{err}");
    let wrong_last = format!("{good}{{\"t\": 1}}");
    let err = parse_jsonl(wrong_last.as_bytes(), "run.jsonl").unwrap_err();
    assert!(matches!(err, PlotError::Json { line: 4, .. }), "{err}");
}

/// A reader that counts the bytes taken from it.
struct Counting<R> {
    inner: R,
    taken: std::rc::Rc<std::cell::Cell<usize>>,
}

impl<R: std::io::Read> std::io::Read for Counting<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.taken.set(self.taken.get() + n);
        Ok(n)
    }
}

#[test]
fn a_line_longer_than_the_limit_is_refused_without_reading_on() {
    // hyq plot /dev/zero used to read one endless line until memory ran out.
    use std::io::Read;
    let taken = std::rc::Rc::new(std::cell::Cell::new(0));
    let endless = Counting {
        inner: std::io::repeat(b'x').take(64 << 20),
        taken: taken.clone(),
    };
    let err = parse_jsonl(std::io::BufReader::new(endless), "zero").unwrap_err();
    assert!(err.to_string().contains("1 MiB"), "{err}");
    assert!(
        taken.get() <= hyq_render::MAX_RECORD_LINE_BYTES + (64 << 10),
        "read {} bytes",
        taken.get()
    );
}

/// Records holding gait regularisers (`[regularizers]`, the terms that were on) get a third plot,
/// a panel per term, unscaled; the series holds each term's column in the records' order; the
/// spec's two plots are drawn from the same series as without them.
#[test]
fn records_with_regularisers_get_a_panel_per_term() {
    let dir = scratch_dir("regularizers");
    let mut records = spec_episode();
    for (i, r) in records.iter_mut().enumerate() {
        let line = format!(
            r#"{{"action_rate": {}, "foot_slip": 0.25, "collision": 0.0}}"#,
            i as f64 * 0.5
        );
        r.regularizers = Some(serde_json::from_str(&line).unwrap());
    }
    let series = EpisodeSeries::from_records(&records);
    let names: Vec<&str> = series.regularizers.iter().map(|(n, _)| *n).collect();
    assert_eq!(names, ["action_rate", "foot_slip", "collision"]);
    assert_eq!(series.regularizers[0].1[3], 1.5);
    let jsonl = to_jsonl(&records);
    let parsed = parse_jsonl(jsonl.as_bytes(), "mem").unwrap();
    let back: Vec<_> = parsed.records.iter().map(|r| r.regularizers).collect();
    let written: Vec<_> = records.iter().map(|r| r.regularizers).collect();
    assert!(
        back == written,
        "the record's regularizers object reads back"
    );
    let plots = plot_episode(&series, &PlotOptions::default(), &dir, "ep").unwrap();
    let path = plots.regularizers.clone().unwrap();
    assert_eq!(path, dir.join("ep_regularizers.png"));
    let (size, colours) = png_size_and_colours(&path);
    assert_eq!(
        size,
        (REGULARIZER_PLOT_CELL.0, 60 + 2 * REGULARIZER_PLOT_CELL.1)
    );
    assert!(colours > 50, "{colours} colours");
    // A non-finite value is refused by the term's name.
    let mut bad = series.clone();
    bad.regularizers[1].1[7] = f64::NAN;
    let e = hyq_render::plot_regularizers(&bad, &PlotOptions::default(), dir.join("x.png"));
    assert!(e.unwrap_err().to_string().contains("foot_slip"));
    std::fs::remove_dir_all(dir).unwrap();
}
