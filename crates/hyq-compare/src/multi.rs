//! A comparison of three or more backends in one report: every side runs the same plan once,
//! every pair of sides is compared as a two-backend comparison would be (its own full report in
//! a subdirectory), and the top-level report puts the sides and the pairs side by side, with a
//! plot of every side's trunk x and z and every pair's divergence.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::compare::{Plan, Side};
use crate::error::CompareError;
use crate::ledger::Ledger;
use crate::metrics::Divergence;
use crate::plot::{COLOURS, PAIR_COLOURS, Panel, plot_panels};
use crate::report::{
    MARKDOWN_FILE, PLOT_FILE, Report, SideReport, prepare_output_dir, write_report_files,
};
use crate::scenario::Scenario;

/// One pair's summary in a [`MultiReport`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PairSummary {
    /// The two sides' labels.
    pub labels: [String; 2],
    /// The subdirectory holding the pair's full report.
    pub dir: String,
    /// Trunk position divergence over time (m).
    pub trunk_position: Divergence,
    /// Trunk orientation divergence over time (rad).
    pub trunk_orientation: Divergence,
    /// Worst joint's angle divergence over time (rad).
    pub joint_angles: Divergence,
    /// |return A − return B|.
    pub return_diff: f64,
    /// |standing height A − standing height B| (m).
    pub standing_height_diff_m: f64,
    /// Metrics outside the ledger.
    pub flagged: usize,
    /// Their names.
    pub flagged_metrics: Vec<String>,
}

/// A comparison of several backends (see the module docs).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MultiReport {
    /// The robot's name.
    pub robot: String,
    /// The scenario.
    pub scenario: Scenario,
    /// What it does.
    pub description: String,
    /// The seed.
    pub seed: u64,
    /// The run length (s).
    pub seconds: f64,
    /// Actions in the script.
    pub script_steps: u64,
    /// The script's fingerprint (the same for every side).
    pub script_fingerprint: String,
    /// Overrides applied to every side.
    pub overrides: Vec<String>,
    /// The ledger used.
    pub ledger: String,
    /// Per side.
    pub sides: Vec<SideReport>,
    /// Per pair, in the order (1, 2), (1, 3), …, (2, 3), …
    pub pairs: Vec<PairSummary>,
    /// Metrics outside the ledger, over every pair.
    pub flagged: usize,
    /// Every pair's full report.
    #[serde(skip)]
    pub reports: Vec<Report>,
    /// Per side: time (s), trunk x (m), trunk z (m).
    #[serde(skip)]
    pub traces: Vec<[Vec<f64>; 3]>,
}

/// Compares every pair of `sides` (each ran `plan`) against `ledger`. The one-step comparison
/// of a pair samples its shared states from the pair's first side.
pub fn compare_all(
    plan: &Plan,
    sides: &mut [Side],
    ledger: &Ledger,
) -> Result<MultiReport, CompareError> {
    let spec = plan.spec();
    let mut reports = Vec::new();
    let mut pairs = Vec::new();
    for i in 0..sides.len() {
        for j in i + 1..sides.len() {
            let (head, tail) = sides.split_at_mut(j);
            let report = plan.pair(&mut head[i], &mut tail[0], ledger)?;
            let [a, b] = &report.sides;
            let value = |name: &str| {
                report
                    .checks
                    .iter()
                    .find(|c| c.metric.name() == name)
                    .map_or(f64::NAN, |c| c.value)
            };
            pairs.push(PairSummary {
                labels: [a.label.clone(), b.label.clone()],
                dir: pair_dir(&a.label, &b.label),
                trunk_position: report.trajectory.trunk_position,
                trunk_orientation: report.trajectory.trunk_orientation,
                joint_angles: report.trajectory.joint_angles,
                return_diff: value("return_diff"),
                standing_height_diff_m: value("standing_height_diff_m"),
                flagged: report.flagged,
                flagged_metrics: report.flags().map(|c| c.metric.name().to_owned()).collect(),
            });
            reports.push(report);
        }
    }
    let first = reports.first().ok_or(CompareError::Scenario {
        scenario: spec.scenario.name(),
        reason: "a comparison needs at least two backends".into(),
    })?;
    let traces = sides
        .iter()
        .map(|s| {
            let t = s.trajectory();
            [
                (0..t.len()).map(|k| k as f64 * t.env_dt).collect(),
                t.positions.iter().map(|p| p[0]).collect(),
                t.positions.iter().map(|p| p[2]).collect(),
            ]
        })
        .collect();
    Ok(MultiReport {
        robot: first.robot.clone(),
        scenario: first.scenario,
        description: first.description.clone(),
        seed: first.seed,
        seconds: first.seconds,
        script_steps: first.script_steps,
        script_fingerprint: first.script_fingerprint.clone(),
        overrides: first.overrides.clone(),
        ledger: first.ledger.clone(),
        sides: sides.iter().map(|s| s.report(&spec.overrides)).collect(),
        flagged: pairs.iter().map(|p| p.flagged).sum(),
        pairs,
        reports,
        traces,
    })
}

/// A pair's subdirectory name: `rapier_vs_dart`, labels made file-name safe.
fn pair_dir(a: &str, b: &str) -> String {
    let safe = |s: &str| {
        s.chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect::<String>()
    };
    format!("{}_vs_{}", safe(a), safe(b))
}

impl MultiReport {
    /// Writes `report.json`, `report.md` and `trunk_x_z.png` into `dir`, and each pair's full
    /// report into `dir/<a>_vs_<b>/`; returns the top-level paths.
    pub fn write(
        &self,
        dir: impl AsRef<Path>,
        command: &str,
    ) -> Result<[PathBuf; 3], CompareError> {
        let dir = dir.as_ref();
        prepare_output_dir(dir)?;
        for (report, pair) in self.reports.iter().zip(&self.pairs) {
            report.write(dir.join(&pair.dir), command)?;
        }
        let text = match serde_json::to_string_pretty(self) {
            Ok(s) => s,
            Err(e) => unreachable!("a comparison report serialises to JSON: {e}"),
        };
        write_report_files(dir, text, self.to_markdown(command), |png| {
            plot_many(self, png)
        })
    }

    /// The Markdown report; `command` is the command line that produced it.
    pub fn to_markdown(&self, command: &str) -> String {
        let mut m = String::new();
        self.markdown_header(&mut m, command);
        self.markdown_per_backend(&mut m);
        self.markdown_pairs(&mut m);
        // Writing into a String cannot fail.
        let _ = writeln!(
            m,
            "\n## Plot\n\n![trunk x and z over time, every backend]({PLOT_FILE})"
        );
        m
    }

    /// The title, the run (seed, length, script, ledger), the overrides and the verdict.
    fn markdown_header(&self, w: &mut String, command: &str) {
        let labels: Vec<&str> = self.sides.iter().map(|s| s.label.as_str()).collect();
        crate::report::markdown_title(
            w,
            &labels,
            self.scenario,
            &self.robot,
            &self.description,
            command,
        );
        let _ = writeln!(
            w,
            "Seed {}, {} s ({} env steps), the same {} actions fed to every backend (script fingerprint `{}`). Ledger: {}.",
            self.seed,
            self.seconds,
            self.script_steps,
            self.script_steps,
            self.script_fingerprint,
            self.ledger
        );
        if !self.overrides.is_empty() {
            let _ = writeln!(
                w,
                "Overrides on every side: `{}`.",
                self.overrides.join(" ")
            );
        }
        let draws = self.sides.iter().map(|s| [s.randomize.as_ref()]);
        if let Some(alike) = crate::randomized::drew_alike(draws) {
            let _ = writeln!(w, "{}", crate::randomized::line(alike, "every side"));
        }
        let verdict = if self.flagged == 0 {
            "**Every metric of every pair is within the ledger.**".to_owned()
        } else {
            format!(
                "**{} metric(s) outside the ledger**, over all pairs (listed per pair below).",
                self.flagged
            )
        };
        let _ = writeln!(w, "\n{verdict}\n");
    }

    /// Each backend's run, a column per backend.
    fn markdown_per_backend(&self, w: &mut String) {
        let labels: Vec<&str> = self.sides.iter().map(|s| s.label.as_str()).collect();
        let _ = writeln!(w, "## Per backend\n");
        let _ = writeln!(w, "| | {} |", labels.join(" | "));
        let _ = writeln!(w, "|---|{}", "---|".repeat(labels.len()));
        let mut row = |name: &str, f: &dyn Fn(&SideReport) -> String| {
            let cells: Vec<String> = self.sides.iter().map(f).collect();
            let _ = writeln!(w, "| {name} | {} |", cells.join(" | "));
        };
        row("end reason", &|s| {
            if s.end_reasons.is_empty() {
                "—".to_owned()
            } else {
                let r: Vec<&str> = s.end_reasons.iter().map(|r| r.as_str()).collect();
                r.join(" + ")
            }
        });
        row("end step (time)", &|s| {
            format!("{} ({:.2} s)", s.end_step, s.end_time_s)
        });
        row("return Σr", &|s| format!("{:.4}", s.sums.ret));
        row("standing height (2 s stand)", &|s| {
            format!("{:.4} m", s.standing_height_m)
        });
        row("mean trunk z", &|s| format!("{:.4} m", s.mean_trunk_z_m));
        row("final trunk position", &|s| {
            format!(
                "({:.3}, {:.3}, {:.3}) m",
                s.final_position[0], s.final_position[1], s.final_position[2]
            )
        });
    }

    /// Each pair's divergences, ledger verdict and report.
    fn markdown_pairs(&self, w: &mut String) {
        let _ = writeln!(w, "\n## Per pair\n");
        let _ = writeln!(
            w,
            "Each pair's full report (every metric, the one-step comparison from states of the pair's first backend's run, the ledger's verdict) is in its subdirectory.\n"
        );
        let _ = writeln!(
            w,
            "| pair | trunk position RMS / max | orientation RMS / max | worst joint RMS / max | return diff | standing height diff | outside the ledger | report |\n|---|---|---|---|---|---|---|---|"
        );
        for p in &self.pairs {
            let flagged = if p.flagged == 0 {
                "none".to_owned()
            } else {
                format!("{}: {}", p.flagged, p.flagged_metrics.join(", "))
            };
            let _ = writeln!(
                w,
                "| {} vs {} | {} / {} m | {} / {} rad | {} / {} rad | {} | {} m | {} | [{}]({}/{MARKDOWN_FILE}) |",
                p.labels[0],
                p.labels[1],
                sig(p.trunk_position.rms),
                sig(p.trunk_position.max),
                sig(p.trunk_orientation.rms),
                sig(p.trunk_orientation.max),
                sig(p.joint_angles.rms),
                sig(p.joint_angles.max),
                sig(p.return_diff),
                sig(p.standing_height_diff_m),
                flagged,
                p.dir,
                p.dir
            );
        }
    }
}

/// A number with 4 significant digits (as the pair reports write them).
fn sig(v: f64) -> String {
    crate::report::sig(v)
}

/// Draws a several-backend report's plot into `path` (PNG, [`crate::PLOT_SIZE`]): every backend's
/// trunk x and z, and every pair's trunk position divergence.
pub fn plot_many(report: &MultiReport, path: &Path) -> Result<(), CompareError> {
    let labels: Vec<&str> = report.sides.iter().map(|s| s.label.as_str()).collect();
    let title = format!(
        "{}: scenario {}, seed {}",
        labels.join(" vs "),
        report.scenario,
        report.seed
    );
    let x: Vec<(&str, &[f64], &[f64])> = labels
        .iter()
        .zip(&report.traces)
        .map(|(l, t)| (*l, t[0].as_slice(), t[1].as_slice()))
        .collect();
    let z: Vec<(&str, &[f64], &[f64])> = labels
        .iter()
        .zip(&report.traces)
        .map(|(l, t)| (*l, t[0].as_slice(), t[2].as_slice()))
        .collect();
    let names: Vec<String> = report
        .pairs
        .iter()
        .map(|p| format!("{} vs {}", p.labels[0], p.labels[1]))
        .collect();
    let d: Vec<(&str, &[f64], &[f64])> = names
        .iter()
        .zip(&report.reports)
        .map(|(n, r)| {
            (
                n.as_str(),
                r.series.divergence_time_s.as_slice(),
                r.series.trunk_position_m.as_slice(),
            )
        })
        .collect();
    plot_panels(
        path,
        &title,
        [
            Panel::new("trunk x", "x (m)", &x, &COLOURS),
            Panel::new("trunk z", "z (m)", &z, &COLOURS),
            Panel::new("trunk position divergence per pair", "m", &d, &PAIR_COLOURS),
        ],
    )
}
