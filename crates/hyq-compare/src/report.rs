//! The comparison report: one [`Report`] written as `report.json`, `report.md` and the plot
//! `trunk_x_z.png` into an output directory.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use hyq_env::Reason;
use serde::Serialize;

use crate::error::CompareError;
use crate::ledger::{Metric, ToleranceSource};
use crate::metrics::{OneStepErrors, OneStepSummary, TrajectoryComparison};
use crate::plot::{COLOURS, GREEN, Panel, plot_panels};
use crate::run::{TermSums, Trajectory};
use crate::scenario::Scenario;
use hyq_spec::REWARD_TERMS;

/// The JSON report's file name.
pub const JSON_FILE: &str = "report.json";
/// The Markdown report's file name.
pub const MARKDOWN_FILE: &str = "report.md";
/// The plot's file name.
pub const PLOT_FILE: &str = "trunk_x_z.png";

/// How many points the time series in the JSON report keep at most (evenly spaced, plus the
/// last), so that the file stays small for long runs.
pub const SERIES_POINTS: usize = 200;

/// One backend's run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SideReport {
    /// The label (usually the engine's name).
    pub label: String,
    /// The engine (`Backend::NAME`).
    pub engine: String,
    /// Why the episode ended (all reasons that held).
    pub end_reasons: Vec<Reason>,
    /// The step on which it ended.
    pub end_step: u64,
    /// That step's time (s).
    pub end_time_s: f64,
    /// Reward-term sums and the return.
    pub sums: TermSums,
    /// Trunk z after holding the standing pose for 2 s (m).
    pub standing_height_m: f64,
    /// Mean trunk z over the run (m).
    pub mean_trunk_z_m: f64,
    /// C at the end of the run (m).
    pub final_position: [f64; 3],
    /// The configuration overrides this side ran with.
    pub overrides: Vec<String>,
    /// `[randomize]`'s draws and pushes, when it is on (else not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub randomize: Option<hyq_env::EpisodeRandomization>,
}

/// Time series for plotting: the trunk's x and z per backend and the three divergences, over
/// the whole run of each backend (x, z) or the common part (divergences).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Series {
    /// Time of each point (s), per backend.
    pub time_s: [Vec<f64>; 2],
    /// Trunk x (m), per backend.
    pub x_m: [Vec<f64>; 2],
    /// Trunk z (m), per backend.
    pub z_m: [Vec<f64>; 2],
    /// Time of each divergence point (s).
    pub divergence_time_s: Vec<f64>,
    /// e_p(t) (m).
    pub trunk_position_m: Vec<f64>,
    /// e_R(t) (rad).
    pub trunk_orientation_rad: Vec<f64>,
    /// e_q(t) (rad).
    pub joint_angle_rad: Vec<f64>,
}

/// Indices 0..len thinned to at most [`SERIES_POINTS`] (+ the last).
pub(crate) fn thin(len: usize) -> Vec<usize> {
    if len == 0 {
        return Vec::new();
    }
    let stride = len.div_ceil(SERIES_POINTS).max(1);
    let mut idx: Vec<usize> = (0..len).step_by(stride).collect();
    if idx.last() != Some(&(len - 1)) {
        idx.push(len - 1);
    }
    idx
}

impl Series {
    /// The full-resolution series of two runs (the plot uses every point).
    pub fn from_runs(a: &Trajectory, b: &Trajectory) -> Self {
        let mut s = Series::default();
        for (k, traj) in [a, b].into_iter().enumerate() {
            s.time_s[k] = (0..traj.len()).map(|t| t as f64 * traj.env_dt).collect();
            s.x_m[k] = traj.positions.iter().map(|p| p[0]).collect();
            s.z_m[k] = traj.positions.iter().map(|p| p[2]).collect();
        }
        s
    }

    /// Fills the divergence series from a comparison (full resolution).
    pub fn with_divergences(mut self, c: &TrajectoryComparison, env_dt: f64) -> Self {
        self.divergence_time_s = (0..c.samples).map(|t| t as f64 * env_dt).collect();
        self.trunk_position_m = c.series[0].clone();
        self.trunk_orientation_rad = c.series[1].clone();
        self.joint_angle_rad = c.series[2].clone();
        self
    }

    /// The same series with at most [`SERIES_POINTS`] + 1 points each.
    pub fn thinned(&self) -> Self {
        let pick = |v: &[f64], idx: &[usize]| idx.iter().map(|&i| v[i]).collect::<Vec<f64>>();
        let mut s = Series::default();
        for k in 0..2 {
            let idx = thin(self.time_s[k].len());
            s.time_s[k] = pick(&self.time_s[k], &idx);
            s.x_m[k] = pick(&self.x_m[k], &idx);
            s.z_m[k] = pick(&self.z_m[k], &idx);
        }
        let idx = thin(self.divergence_time_s.len());
        s.divergence_time_s = pick(&self.divergence_time_s, &idx);
        s.trunk_position_m = pick(&self.trunk_position_m, &idx);
        s.trunk_orientation_rad = pick(&self.trunk_orientation_rad, &idx);
        s.joint_angle_rad = pick(&self.joint_angle_rad, &idx);
        s
    }
}

/// The one-step comparison's part of the report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OneStepReport {
    /// Shared states compared.
    pub states: usize,
    /// Of those, states where either backend had a foot or the trunk on the ground during the
    /// sub-step.
    pub states_in_contact: usize,
    /// Physics sub-steps taken from each shared state (1).
    pub sub_steps: u32,
    /// Per quantity: max, median, max without contact.
    pub summary: Vec<OneStepSummary>,
    /// Per state.
    pub per_state: Vec<OneStepErrors>,
}

/// One metric checked against the ledger.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Check {
    /// The metric.
    pub metric: Metric,
    /// Its measured value.
    pub value: f64,
    /// Its tolerance.
    pub tolerance: f64,
    /// value ≤ tolerance.
    pub within: bool,
    /// Where the tolerance came from.
    #[serde(flatten)]
    pub source: ToleranceSource,
}

/// A whole comparison.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    /// The robot's name (its profile's `name`).
    pub robot: String,
    /// The scenario.
    pub scenario: Scenario,
    /// What it does.
    pub description: String,
    /// The seed.
    pub seed: u64,
    /// The run length asked for (s).
    pub seconds: f64,
    /// Δt_env (s).
    pub env_dt_s: f64,
    /// Actions in the script (= t_max).
    pub script_steps: u64,
    /// FNV-1a of the script's bits: the same for both sides by construction.
    pub script_fingerprint: String,
    /// Overrides applied to both sides.
    pub overrides: Vec<String>,
    /// Overrides applied to the second side only.
    pub overrides_b: Vec<String>,
    /// The two engines, as the ledger names them.
    pub engines: [String; 2],
    /// The ledger used ("built-in" or its path).
    pub ledger: String,
    /// Per backend.
    pub sides: [SideReport; 2],
    /// Divergences over time and contact agreement.
    pub trajectory: TrajectoryComparison,
    /// The one-step comparison from shared states.
    pub one_step: OneStepReport,
    /// Every metric against the ledger.
    pub checks: Vec<Check>,
    /// How many metrics are outside the ledger's tolerances.
    pub flagged: usize,
    /// Time series (full resolution here; thinned in the JSON file).
    pub series: Series,
}

impl Report {
    /// The checks outside the ledger.
    pub fn flags(&self) -> impl Iterator<Item = &Check> {
        self.checks.iter().filter(|c| !c.within)
    }

    /// The report as pretty JSON, its time series thinned to [`SERIES_POINTS`].
    pub fn to_json(&self) -> String {
        let mut thinned = self.clone();
        thinned.series = self.series.thinned();
        // Per-state one-step errors stay: at most 1000 states, a few hundred bytes each.
        match serde_json::to_string_pretty(&thinned) {
            Ok(s) => s,
            // Every field is a number, string, bool or list of those; JSON writes a
            // non-finite number as null rather than failing.
            Err(e) => unreachable!("a comparison report serialises to JSON: {e}"),
        }
    }

    /// Writes `report.json`, `report.md` and `trunk_x_z.png` into `dir` (created if missing);
    /// returns the three paths.
    pub fn write(
        &self,
        dir: impl AsRef<Path>,
        command: &str,
    ) -> Result<[PathBuf; 3], CompareError> {
        let dir = dir.as_ref();
        prepare_output_dir(dir)?;
        write_report_files(dir, self.to_json(), self.to_markdown(command), |png| {
            plot_trunk_x_z(self, png)
        })
    }

    /// The Markdown report; `command` is the command line that produced it (shown verbatim).
    pub fn to_markdown(&self, command: &str) -> String {
        let mut m = String::new();
        self.markdown_header(&mut m, command);
        self.markdown_per_backend(&mut m);
        self.markdown_trajectory(&mut m);
        self.markdown_one_step(&mut m);
        self.markdown_checks(&mut m);
        // Writing into a String cannot fail.
        let _ = writeln!(m, "\n## Plot\n\n![trunk x and z over time]({PLOT_FILE})");
        m
    }

    /// The title, the command, the run's settings and the verdict.
    fn markdown_header(&self, w: &mut String, command: &str) {
        let [a, b] = &self.sides;
        markdown_title(
            w,
            &[&a.label, &b.label],
            self.scenario,
            &self.robot,
            &self.description,
            command,
        );
        let _ = writeln!(
            w,
            "Seed {}, {} s ({} env steps of {} s), the same {} actions fed to both (script fingerprint `{}`). Ledger: {}.",
            self.seed,
            self.seconds,
            self.script_steps,
            self.env_dt_s,
            self.script_steps,
            self.script_fingerprint,
            self.ledger
        );
        if !self.overrides.is_empty() {
            let _ = writeln!(
                w,
                "Overrides on both sides: `{}`.",
                self.overrides.join(" ")
            );
        }
        if !self.overrides_b.is_empty() {
            let _ = writeln!(
                w,
                "Overrides on {} only: `{}`.",
                b.label,
                self.overrides_b.join(" ")
            );
        }
        let draws = self.sides.iter().map(|s| [s.randomize.as_ref()]);
        if let Some(alike) = crate::randomized::drew_alike(draws) {
            let _ = writeln!(w, "{}", crate::randomized::line(alike, "both sides"));
        }
        let verdict = if self.flagged == 0 {
            "**Every metric is within the ledger.**".to_owned()
        } else {
            format!(
                "**{} metric(s) outside the ledger** (marked ✗ below).",
                self.flagged
            )
        };
        let _ = writeln!(w, "\n{verdict}\n");
    }

    /// Each backend's end, return, reward-term sums and heights.
    fn markdown_per_backend(&self, w: &mut String) {
        let [a, b] = &self.sides;
        let _ = writeln!(w, "## Per backend\n");
        let _ = writeln!(w, "| | {} | {} |\n|---|---|---|", a.label, b.label);
        let reasons = |s: &SideReport| {
            if s.end_reasons.is_empty() {
                "—".to_owned()
            } else {
                s.end_reasons
                    .iter()
                    .map(|r| r.as_str())
                    .collect::<Vec<_>>()
                    .join(" + ")
            }
        };
        let mut row = |name: &str, f: &dyn Fn(&SideReport) -> String| {
            let _ = writeln!(w, "| {name} | {} | {} |", f(a), f(b));
        };
        row("end reason", &|s| reasons(s));
        row("end step (time)", &|s| {
            format!("{} ({:.2} s)", s.end_step, s.end_time_s)
        });
        row("return Σr", &|s| format!("{:.4}", s.sums.ret));
        // Σ of every reward and penalty term, in hyq-spec's table order.
        for term in REWARD_TERMS.iter().filter(|t| t.kind.is_summed()) {
            row(&format!("Σ {}", term.name), &|s| {
                format!("{:.4}", s.sums.terms.get(term.name).unwrap_or_default())
            });
        }
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

    /// The divergence over time and the contact-flag agreement.
    fn markdown_trajectory(&self, w: &mut String) {
        let [a, b] = &self.sides;
        let t = &self.trajectory;
        let _ = writeln!(
            w,
            "\n## Divergence over time\n\nOver the {} samples both runs lived through (reset + {} steps).\n",
            t.samples,
            t.samples.saturating_sub(1)
        );
        let _ = writeln!(
            w,
            "| quantity | RMS | max | max at step |\n|---|---|---|---|"
        );
        for (name, unit, d) in [
            ("trunk position ‖C_A − C_B‖", "m", &t.trunk_position),
            ("trunk orientation angle", "rad", &t.trunk_orientation),
            ("joint angle, worst joint", "rad", &t.joint_angles),
        ] {
            let _ = writeln!(
                w,
                "| {name} | {} {unit} | {} {unit} | {} |",
                sig(d.rms),
                sig(d.max),
                d.max_at_step
            );
        }
        let _ = writeln!(
            w,
            "\nContact-flag agreement per tracked body (latched flags, steps 1..):\n"
        );
        let _ = writeln!(
            w,
            "| body | agreement | steps in contact ({}) | steps in contact ({}) |\n|---|---|---|---|",
            a.label, b.label
        );
        for c in &t.contacts {
            let _ = writeln!(
                w,
                "| {} | {:.1} % | {} | {} |",
                c.link, c.agreement_pct, c.steps_in_contact[0], c.steps_in_contact[1]
            );
        }
    }

    /// The one-step comparison from shared states.
    fn markdown_one_step(&self, w: &mut String) {
        let [a, _] = &self.sides;
        let o = &self.one_step;
        let _ = writeln!(
            w,
            "\n## One step from a shared state\n\n{} states sampled evenly from {}'s run ({} of them with a foot or the trunk on the ground); each backend is put into the state, given the same joint torques (the shared PD actuator on that state and the targets that followed it), and advanced {} physics sub-step.\n",
            o.states, a.label, o.states_in_contact, o.sub_steps
        );
        let _ = writeln!(
            w,
            "| quantity | max | at state (step) | median | max with no foot or trunk contact |\n|---|---|---|---|---|"
        );
        for s in &o.summary {
            let free = s
                .max_without_contact
                .map_or("—".to_owned(), |v| format!("{} {}", sig(v), s.unit));
            let _ = writeln!(
                w,
                "| {} | {} {u} | {} | {} {u} | {free} |",
                s.quantity,
                sig(s.max),
                s.max_at_step,
                sig(s.median),
                u = s.unit
            );
        }
    }

    /// Every metric against the ledger.
    fn markdown_checks(&self, w: &mut String) {
        let _ = writeln!(w, "\n## Checks against the ledger\n");
        let _ = writeln!(
            w,
            "| metric | value | tolerance | | source |\n|---|---|---|---|---|"
        );
        for c in &self.checks {
            let source = match &c.source {
                ToleranceSource::Default => "default".to_owned(),
                ToleranceSource::Known { reason, scenario } => {
                    format!("known ({scenario}): {reason}")
                }
            };
            let _ = writeln!(
                w,
                "| {} | {} | {} | {} | {} |",
                c.metric,
                sig(c.value),
                sig(c.tolerance),
                if c.within { "✓" } else { "✗" },
                source.replace('|', "/")
            );
        }
    }
}

/// The opening every scenario report shares (two backends or more): the title naming the
/// backends and the scenario, the robot, what the scenario does, and the command verbatim.
pub(crate) fn markdown_title(
    w: &mut String,
    labels: &[&str],
    scenario: Scenario,
    robot: &str,
    description: &str,
    command: &str,
) {
    // Writing into a String cannot fail.
    let _ = writeln!(
        w,
        "# Comparison: {}, scenario `{scenario}`\n",
        labels.join(" vs ")
    );
    let _ = writeln!(w, "Robot: `{robot}`.\n");
    let _ = writeln!(w, "Scenario: {description}.\n");
    let _ = writeln!(w, "```\n{command}\n```\n");
}

/// A number with 4 significant digits (plain notation between 1e-3 and 1e4).
pub(crate) fn sig(v: f64) -> String {
    if v == 0.0 {
        "0".to_owned()
    } else if !v.is_finite() {
        v.to_string()
    } else if (1e-3..1e4).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

/// Writes a report's three files into `dir` (already prepared by [`prepare_output_dir`]):
/// `json` (a newline appended) as [`JSON_FILE`], `markdown` as [`MARKDOWN_FILE`], and the plot
/// `draw` makes as [`PLOT_FILE`]; returns the three paths in that order.
pub(crate) fn write_report_files(
    dir: &Path,
    json: String,
    markdown: String,
    draw: impl FnOnce(&Path) -> Result<(), CompareError>,
) -> Result<[PathBuf; 3], CompareError> {
    let paths = [
        dir.join(JSON_FILE),
        dir.join(MARKDOWN_FILE),
        dir.join(PLOT_FILE),
    ];
    let write = |path: &Path, text: String| {
        std::fs::write(path, text).map_err(|e| CompareError::Output {
            path: path.to_owned(),
            message: e.to_string(),
        })
    };
    write(&paths[0], json + "\n")?;
    write(&paths[1], markdown)?;
    draw(&paths[2])?;
    Ok(paths)
}

/// Creates `dir` if needed and checks that a file can be written in it, before any
/// simulation runs (so an unwritable directory fails at once).
pub fn prepare_output_dir(dir: &Path) -> Result<(), CompareError> {
    let fail = |path: &Path, e: std::io::Error| CompareError::Output {
        path: path.to_owned(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(|e| fail(dir, e))?;
    let probe = dir.join(".hyq-compare-write-test");
    std::fs::write(&probe, b"").map_err(|e| fail(dir, e))?;
    std::fs::remove_file(&probe).map_err(|e| fail(&probe, e))
}

/// Draws the report's plot into `path` (PNG, [`crate::PLOT_SIZE`]).
pub fn plot_trunk_x_z(report: &Report, path: &Path) -> Result<(), CompareError> {
    let s = &report.series;
    let [a, b] = &report.sides;
    let title = format!(
        "{} vs {}: scenario {}, seed {}",
        a.label, b.label, report.scenario, report.seed
    );
    let x = [
        (
            a.label.as_str(),
            s.time_s[0].as_slice(),
            s.x_m[0].as_slice(),
        ),
        (
            b.label.as_str(),
            s.time_s[1].as_slice(),
            s.x_m[1].as_slice(),
        ),
    ];
    let z = [
        (
            a.label.as_str(),
            s.time_s[0].as_slice(),
            s.z_m[0].as_slice(),
        ),
        (
            b.label.as_str(),
            s.time_s[1].as_slice(),
            s.z_m[1].as_slice(),
        ),
    ];
    let d = [(
        "divergence",
        s.divergence_time_s.as_slice(),
        s.trunk_position_m.as_slice(),
    )];
    plot_panels(
        path,
        &title,
        [
            Panel::new("trunk x", "x (m)", &x, &COLOURS),
            Panel::new("trunk z", "z (m)", &z, &COLOURS),
            Panel::new("trunk position divergence |C_A − C_B|", "m", &d, &[GREEN]),
        ],
    )
}
