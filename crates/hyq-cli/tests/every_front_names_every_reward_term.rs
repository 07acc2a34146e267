//! Invariant: every front that reports reward terms names every term of hyq-spec's table
//! (`hyq_spec::REWARD_TERMS`), so a term added to the table reaches them all without another
//! edit: the step record's `terms` (an opt-in term when it is on), the legends of the
//! reward-terms plot, the columns of `hyq run`'s summary table and the keys of its JSON lines
//! (a sum for each reward and penalty, a mean for each multiplier), and the rows of the
//! comparison report (Markdown and JSON). The Python info is checked by the package's
//! `test_info_keeps_one_shape.py`, the README's tables by xtask's docs tests.

#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq_ok, scratch};
use hyq_spec::{REWARD_TERMS, RewardBreakdown, TermKind, TermValues};

/// A configuration with every opt-in term on (the height penalty).
const ALL_ON: &str =
    "[task.height_penalty]\nnominal_height_m = 0.62\ntolerance_m = 0.1\nrate_per_m = 2.0\n";

fn summed() -> impl Iterator<Item = &'static str> {
    REWARD_TERMS
        .iter()
        .filter(|t| t.kind.is_summed())
        .map(|t| t.name)
}

#[test]
fn the_record_and_the_summaries_name_every_term() {
    let dir = scratch("every_term_run");
    std::fs::create_dir_all(&dir).unwrap();
    let config = dir.join("all_on.toml");
    std::fs::write(&config, ALL_ON).unwrap();
    let record = dir.join("run.jsonl");
    let json = hyq_ok(&[
        "run",
        "--policy",
        "stand",
        "--config",
        config.to_str().unwrap(),
        "--set",
        "task.max_time_steps=3",
        "--record",
        record.to_str().unwrap(),
        "--json",
    ]);

    let line = std::fs::read_to_string(&record).unwrap();
    let first: serde_json::Value = serde_json::from_str(line.lines().next().unwrap()).unwrap();
    // (serde_json's objects sort their keys: the order is compared as sets.)
    let mut keys: Vec<&str> = first["terms"]
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    let mut all: Vec<&str> = REWARD_TERMS.iter().map(|t| t.name).collect();
    keys.sort_unstable();
    all.sort_unstable();
    assert_eq!(keys, all, "the record's terms");

    let summary: serde_json::Value = serde_json::from_str(json.trim()).unwrap();
    let mut sums: Vec<&str> = summary["terms"]
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    let mut expected: Vec<&str> = summed().collect();
    sums.sort_unstable();
    expected.sort_unstable();
    assert_eq!(sums, expected);
    for t in REWARD_TERMS
        .iter()
        .filter(|t| t.kind == TermKind::Multiplier)
    {
        let key = format!("mean_{}", t.name);
        assert!(summary[&key].is_f64(), "{key} missing from {summary}");
    }

    let table = hyq_ok(&["run", "--policy", "stand", "--set", "task.max_time_steps=2"]);
    // The first line is the title (robot, backend, policy, seed); the table's header follows.
    let header: Vec<&str> = table.lines().nth(1).unwrap().split_whitespace().collect();
    for name in summed() {
        assert!(
            header.contains(&name),
            "summary table lacks {name}: {header:?}"
        );
    }
}

#[test]
fn the_reward_plot_has_a_legend_entry_for_every_term() {
    let record = hyq_render::PlotRecord {
        t: 1,
        episode: Some(1),
        reward: 0.0,
        terms: TermValues::all(&RewardBreakdown::NEUTRAL),
        d_n: Some(1.0),
        distance_to_goal: 5.0,
        regularizers: None,
        velocity: None,
    };
    let series = hyq_render::EpisodeSeries::from_records(&[record]);
    let legend = hyq_render::reward_plot_legend(&series);
    for term in &REWARD_TERMS {
        assert!(
            legend
                .iter()
                .any(|l| l.split_whitespace().any(|w| w == term.name)),
            "no legend entry names {}: {legend:?}",
            term.name
        );
    }
}

#[test]
fn the_comparison_report_has_a_row_for_every_summed_term() {
    let dir = scratch("every_term_compare");
    let _ = std::fs::remove_dir_all(&dir);
    hyq_ok(&[
        "compare",
        "--backends",
        "rapier,rapier",
        "--scenario",
        "limit",
        "--one-step-states",
        "2",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let markdown = std::fs::read_to_string(dir.join("report.md")).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    for name in summed() {
        assert!(
            markdown.contains(&format!("| Σ {name} |")),
            "report.md has no row for {name}"
        );
        for side in json["sides"].as_array().unwrap() {
            assert!(side["sums"][name].is_f64(), "report.json sums lack {name}");
        }
    }
}
