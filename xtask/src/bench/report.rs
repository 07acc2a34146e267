//! The report: where and when the run happened, every figure's median, min and max, and each
//! target's verdict, in Markdown.

use std::fmt::Write as _;
use std::path::Path;

use super::command::{run, shell};
use super::plan::Series;
use super::stats::{Goal, Rep, TARGETS, evaluate, samples, summary};
use crate::cli::strings;

pub(super) fn fmt_value(series: Series, x: f64) -> String {
    if series.is_share() {
        format!("{:.2} %", 100.0 * x)
    } else {
        format!("{x:.0}")
    }
}

/// Where and when the run happened.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Host {
    /// The exact command.
    pub command: String,
    /// UTC date and time.
    pub date: String,
    /// `model name` from /proc/cpuinfo.
    pub cpu: String,
    /// Online CPUs.
    pub cores: String,
    /// Load averages (1, 5, 15 min) at the start and at the end.
    pub load_start: String,
    /// The same at the end.
    pub load_end: String,
    /// The anchors' Python and package versions.
    pub anchors: String,
    /// The git commit (and `-dirty` with uncommitted changes).
    pub commit: String,
    /// `rustc --version`.
    pub rustc: String,
    /// Notes (skipped parts and why).
    pub notes: Vec<String>,
}

impl Host {
    /// The machine, the load, the commit and the toolchain now, and the command being run.
    pub(super) fn now() -> Self {
        let command = std::iter::once("cargo xtask bench-vs-anchors".to_string())
            .chain(std::env::args().skip(2))
            .collect::<Vec<_>>()
            .join(" ");
        Host {
            command,
            date: shell("date -u '+%Y-%m-%d %H:%M UTC'"),
            cpu: shell("grep -m1 'model name' /proc/cpuinfo | cut -d: -f2"),
            cores: shell("getconf _NPROCESSORS_ONLN"),
            load_start: shell("cut -d' ' -f1-3 /proc/loadavg"),
            commit: shell("git rev-parse --short HEAD; git diff --quiet HEAD || echo -dirty")
                .replace('\n', ""),
            rustc: shell("rustc --version"),
            ..Host::default()
        }
    }
}

/// The Markdown report: where and when it ran, every figure, every target's verdict, the notes.
pub fn markdown(host: &Host, reps: &[Rep]) -> String {
    let mut s = String::new();
    markdown_host(&mut s, host, reps.len());
    markdown_figures(&mut s, reps);
    markdown_targets(&mut s, reps);
    // Writing to a String cannot fail.
    let _ = writeln!(
        s,
        "\nRatios are taken within each repetition (same minutes, same load), then summarised. \
         Single-env rates are per CPU second of the process; the vector env's scaling is in \
         wall-clock time and needs both cores free to reach 2×."
    );
    for note in &host.notes {
        let _ = writeln!(s, "\nNote: {note}");
    }
    s
}

/// The report's opening lines: the command, the date, the machine, its load and the build.
fn markdown_host(s: &mut String, host: &Host, reps: usize) {
    // Writing to a String cannot fail.
    let _ = writeln!(s, "Command: `{}`  ", host.command);
    let _ = writeln!(s, "Date: {}  ", host.date);
    let _ = writeln!(s, "CPU: {} ({} cores online)  ", host.cpu, host.cores);
    let _ = writeln!(
        s,
        "Load average (1/5/15 min): {} at the start, {} at the end  ",
        host.load_start, host.load_end
    );
    let _ = writeln!(
        s,
        "Build: release (thin LTO), commit {}, {}  ",
        host.commit, host.rustc
    );
    if !host.anchors.is_empty() {
        let _ = writeln!(s, "Anchors: {}  ", host.anchors);
    }
    let _ = writeln!(
        s,
        "Repetitions: {reps}, each running every row below once, in turn\n"
    );
}

/// The figures' table: each series' median, min and max over the repetitions.
fn markdown_figures(s: &mut String, reps: &[Rep]) {
    // Writing to a String cannot fail.
    let _ = writeln!(s, "| figure | unit | median | min | max | runs |");
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|");
    for series in Series::ALL {
        let (label, unit) = series.label();
        let v = samples(reps, series);
        match summary(&v) {
            Some((med, lo, hi)) => {
                let _ = writeln!(
                    s,
                    "| {label} | {unit} | {} | {} | {} | {} |",
                    fmt_value(series, med),
                    fmt_value(series, lo),
                    fmt_value(series, hi),
                    v.len()
                );
            }
            None => {
                let _ = writeln!(s, "| {label} | {unit} | not measured | | | 0 |");
            }
        }
    }
}

/// The targets' table: each target's bound, the median, min and max of its ratio or share, and
/// the verdict.
fn markdown_targets(s: &mut String, reps: &[Rep]) {
    // Writing to a String cannot fail.
    let _ = writeln!(
        s,
        "\n| target | bound | median | min | max | verdict |\n|---|---|---:|---:|---:|---|"
    );
    for t in TARGETS {
        let v = evaluate(reps, t.goal);
        let (bound, series) = match t.goal {
            Goal::RatioAtLeast { target, num, .. } => (format!("≥ {target}×"), num),
            Goal::AtMost { target, series } => (format!("≤ {:.0} %", 100.0 * target), series),
        };
        let f = |x: f64| {
            if series.is_share() {
                fmt_value(series, x)
            } else {
                format!("{x:.2}×")
            }
        };
        match v.summary {
            Some((med, lo, hi)) => {
                let _ = writeln!(
                    s,
                    "| {} | {bound} | {} | {} | {} | {} |",
                    t.label,
                    f(med),
                    f(lo),
                    f(hi),
                    v.text
                );
            }
            None => {
                let _ = writeln!(s, "| {} | {bound} | | | | {} |", t.label, v.text);
            }
        }
    }
}

/// Writes the report and the raw measurements into the target directory (`$CARGO_TARGET_DIR`
/// or `target/`).
pub(super) fn write_reports(root: &Path, report: &str, raw: &str) -> Result<(), String> {
    let target = crate::workspace::target_dir(root);
    std::fs::create_dir_all(&target)
        .map_err(|e| format!("cannot create {}: {e}", target.display()))?;
    for (name, text) in [
        ("bench-vs-anchors.md", report),
        ("bench-vs-anchors.jsonl", raw),
    ] {
        let path = target.join(name);
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The anchors' Python and the versions of the pinned packages `pins` installed for `python`.
pub(super) fn python_versions(python: &Path, anchors: &Path, pins: &[(String, String)]) -> String {
    let versions = format!(
        "import sys, importlib.metadata as m\nout = ['Python ' + sys.version.split()[0]]\n\
         for p in {:?}:\n    try: out.append(p + ' ' + m.version(p))\n    \
         except m.PackageNotFoundError: pass\nprint(', '.join(out))",
        pins.iter().map(|(p, _)| p.as_str()).collect::<Vec<_>>()
    );
    run(python, &strings(&["-c", &versions]), anchors, &[])
        .map(|s| s.trim().to_string())
        .unwrap_or_default()
}
