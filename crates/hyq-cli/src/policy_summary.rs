//! The summary `hyq compare --policy` prints: per engine the mean of each episode figure with
//! its 95 % interval, each end reason's rate with its Wilson interval and the gait diagnostics;
//! per pair the ratios of means with their intervals and the foot-contact pattern agreement;
//! then the open-loop replay. Every figure is read from the report, so the terminal and
//! report.md say the same.

use std::fmt::Write as _;

use hyq_compare::gait::Figure;
use hyq_compare::{PolicyReport, Rate, ratio_text};

use crate::table::Table;

/// "3/20 [5, 36] %": the count and its Wilson interval in per cent.
fn rate_cell(r: &Rate) -> String {
    format!(
        "{}/{} [{:.0}, {:.0}] %",
        r.k,
        r.n,
        100.0 * r.ci95[0],
        100.0 * r.ci95[1]
    )
}

/// A gait figure times `scale` with its interval (`dp` places), "(k eps)" when only k of the
/// `episodes` had it, "-" when none did.
fn figure_cell(f: Option<Figure>, scale: f64, dp: usize, episodes: u32) -> String {
    let Some(f) = f else {
        return "-".to_owned();
    };
    let text = match f.stats.ci95 {
        Some([lo, hi]) => format!(
            "{:.dp$} [{:.dp$}, {:.dp$}]",
            scale * f.stats.mean,
            scale * lo,
            scale * hi
        ),
        None => format!("{:.dp$} [-]", scale * f.stats.mean),
    };
    if f.episodes == episodes as usize {
        text
    } else {
        format!("{text} ({} eps)", f.episodes)
    }
}

/// The per-engine tables: figures, rates, gait.
fn sides(report: &PolicyReport, out: &mut String) {
    let mut figures = Table::new(&[
        "<engine",
        "<travel (m)",
        "<K - D^T (m)",
        "<return",
        "<steps",
    ]);
    let mut rates = Table::new(&[
        "<engine",
        "<reached",
        "<fell",
        "<joint limit",
        "<timeout",
        "<ended by",
    ]);
    let mut gait = Table::new(&[
        "<engine",
        "<foot slip (mm)",
        "<at bounds (%)",
        "<action change",
        "<stance (s)",
    ]);
    for s in &report.sides {
        figures.row(vec![
            s.label.clone(),
            s.travel_m.text(3),
            s.distance_walked_m.text(3),
            s.ret.text(2),
            s.steps.text(1),
        ]);
        let ends: Vec<String> = s
            .ended_by
            .iter()
            .map(|e| format!("{} {}", e.reasons, e.episodes))
            .collect();
        let rate = |f: fn(&hyq_compare::Rates) -> &Rate| {
            s.rates.as_ref().map_or("-".to_owned(), |r| rate_cell(f(r)))
        };
        rates.row(vec![
            s.label.clone(),
            rate(|r| &r.reached),
            rate(|r| &r.fell),
            rate(|r| &r.joint_limit),
            rate(|r| &r.timeout),
            ends.join(", "),
        ]);
        let g = &s.gait;
        let n = report.episodes;
        gait.row(vec![
            s.label.clone(),
            figure_cell(g.foot_slip_mm, 1.0, 2, n),
            figure_cell(g.actions_at_bounds, 100.0, 1, n),
            figure_cell(g.action_change, 1.0, 4, n),
            figure_cell(g.stance_s, 1.0, 3, n),
        ]);
    }
    // Writing into a String cannot fail.
    let _ = writeln!(out, "\nmean [95 % bootstrap CI] over the episodes:");
    out.push_str(&figures.render());
    let _ = writeln!(out, "\nend rates, k/n [Wilson 95 % CI]:");
    out.push_str(&rates.render());
    let _ = writeln!(out, "\ngait, mean [95 % CI] over the episodes:");
    out.push_str(&gait.render());
    velocity(report, out);
}

/// Under the velocity task, each engine's tracking errors, its commanded stands' feet speed
/// and drift, and its falls; nothing under the spec's task.
fn velocity(report: &PolicyReport, out: &mut String) {
    if report.sides.iter().all(|s| s.velocity.is_none()) {
        return;
    }
    let mut t = Table::new(&[
        "<engine",
        "<forward error (m/s)",
        "<yaw error (rad/s)",
        "<stand: feet speed (m/s)",
        "<stand: drift (m)",
        "<fell",
    ]);
    let n = report.episodes;
    for s in &report.sides {
        let v = s.velocity.unwrap_or_default();
        t.row(vec![
            s.label.clone(),
            figure_cell(v.forward_error_mps, 1.0, 3, n),
            figure_cell(v.yaw_error_radps, 1.0, 3, n),
            figure_cell(v.standing_feet_speed_mps, 1.0, 3, n),
            figure_cell(v.standing_drift_m, 1.0, 3, n),
            s.rates
                .as_ref()
                .map_or("-".to_owned(), |r| rate_cell(&r.fell)),
        ]);
    }
    // Writing into a String cannot fail.
    let _ = writeln!(
        out,
        "\nvelocity task, mean [95 % CI] over the episodes (stand: episodes commanded zero throughout):"
    );
    out.push_str(&t.render());
}

/// The per-pair table: ratios of means (second over first), contact agreement, and the first
/// episodes' trunk divergence.
fn pairs(report: &PolicyReport, out: &mut String) {
    let mut t = Table::new(&[
        "<pair",
        "<travel ratio",
        "<K - D^T ratio",
        "<return ratio",
        "<contact agreement (%)",
        "<1st episode trunk rms / max (m)",
    ]);
    for p in &report.pairs {
        let r = &p.ratios;
        t.row(vec![
            format!("{} / {}", p.labels[1], p.labels[0]),
            ratio_text(r.travel_m.as_ref()),
            ratio_text(r.distance_walked_m.as_ref()),
            ratio_text(r.ret.as_ref()),
            figure_cell(p.contact_agreement, 100.0, 1, report.episodes),
            format!("{:.4} / {:.4}", p.trunk_position.rms, p.trunk_position.max),
        ]);
    }
    if report.pairs.is_empty() {
        return;
    }
    // Writing into a String cannot fail.
    let _ = writeln!(
        out,
        "\nper pair, second over first (paired bootstrap; ≠ 1: the interval excludes 1):"
    );
    out.push_str(&t.render());
}

/// The summary's text, up to (not including) the line saying where the reports went.
pub fn policy_summary(report: &PolicyReport) -> String {
    let mut out = String::new();
    // Writing into a String cannot fail.
    let _ = writeln!(
        out,
        "policy {} on {} ({} episode(s) per backend, seed {}), closed loop:",
        report.policy, report.robot, report.episodes, report.seed
    );
    sides(report, &mut out);
    match report.drew_alike {
        Some(true) => {
            let _ = writeln!(
                out,
                "\nrandomised: every engine drew the same values in each episode"
            );
        }
        Some(false) => {
            let _ = writeln!(
                out,
                "\nrandomised: the engines did NOT draw the same values"
            );
        }
        None => {}
    }
    for s in &report.sides {
        // With `[randomize]` on, the falls and pushes (the push target's figure).
        if let Some(r) = &s.randomized {
            let _ = writeln!(
                out,
                "{}: fell {}, {:.2} pushes per episode",
                s.label,
                r.fell_text(s.episodes.len()),
                r.pushes_mean
            );
        }
    }
    pairs(report, &mut out);
    if let Some(r) = &report.replay {
        let _ = writeln!(out);
        for run in &r.runs {
            let _ = writeln!(
                out,
                "{}'s actions replayed on {}: travel {:.3} m, trunk position vs {}'s run rms {:.4} m",
                r.source, run.label, run.travel_m, r.source, run.trunk_position.rms
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{figure_cell, rate_cell};
    use hyq_compare::gait::Figure;
    use hyq_compare::{Rate, Stats};

    #[test]
    fn cells_carry_the_interval_and_say_when_episodes_lacked_a_figure() {
        let r = Rate {
            mean: 0.15,
            ci95: [0.0524, 0.3604],
            k: 3,
            n: 20,
        };
        assert_eq!(rate_cell(&r), "3/20 [5, 36] %");
        let f = Figure {
            stats: Stats {
                mean: 0.5,
                ci95: Some([0.25, 0.75]),
                ..Stats::default()
            },
            episodes: 4,
        };
        assert_eq!(figure_cell(Some(f), 100.0, 1, 4), "50.0 [25.0, 75.0]");
        assert_eq!(figure_cell(Some(f), 1.0, 2, 5), "0.50 [0.25, 0.75] (4 eps)");
        assert_eq!(figure_cell(None, 1.0, 2, 5), "-");
    }

    /// The summary of the standing policy, 2 episodes of 30 steps on rapier, with `keys` set.
    fn stand_summary(keys: &[(&str, &str)]) -> String {
        use hyq_compare::{PolicyPlan, PolicySpec};
        let mut all = vec![("task.max_time_steps", "30")];
        all.extend_from_slice(keys);
        let config = hyq_env::EnvConfig::load(None, &all).unwrap();
        let spec = PolicySpec {
            policy: "stand".into(),
            seed: 3,
            episodes: 2,
            configuration: Vec::new(),
        };
        let model = hyq_physics::bundled::hyq();
        let plan = PolicyPlan::new(model, config, hyq_env::Stand, spec).unwrap();
        let side = plan
            .run_side::<hyq_engines::backends::Rapier>("rapier")
            .unwrap();
        super::policy_summary(&plan.report(&[side], &[]))
    }

    #[test]
    fn the_velocity_task_adds_its_table_and_the_spec_task_does_not() {
        let text = stand_summary(&[
            ("task.kind", "\"velocity\""),
            ("command.lin_vel_x", "[0.3, 0.3]"),
            ("command.lin_vel_y", "[0.0, 0.0]"),
            ("command.ang_vel_yaw", "[0.0, 0.0]"),
        ]);
        assert!(text.contains("velocity task, mean [95 % CI]"), "{text}");
        let row = text
            .lines()
            .skip_while(|l| !l.starts_with("velocity task"))
            .find(|l| l.trim_start().starts_with("rapier"))
            .unwrap();
        // The robot stands, so its forward error is about the commanded 0.3 m/s; no falls, and
        // no stand figures (the command was not zero).
        let cells: Vec<&str> = row.split_whitespace().collect();
        let forward: f64 = cells[1].parse().unwrap();
        assert!((forward - 0.3).abs() < 0.02, "{row}");
        assert_eq!(cells.iter().filter(|c| **c == "-").count(), 2, "{row}");
        assert!(row.contains("0/2 [0, 66] %"), "{row}");
        assert!(!stand_summary(&[]).contains("velocity task"));
    }
}
