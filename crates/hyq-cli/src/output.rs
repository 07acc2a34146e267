//! What the subcommands print besides their tables: a report as one JSON line on stdout, and
//! the progress bar on stderr.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;

/// Prints `value` as one line of JSON on stdout; `what` names it in the (unreachable) failure.
pub fn print_json_line(value: &impl Serialize, what: &str) {
    match serde_json::to_string(value) {
        Ok(line) => println!("{line}"),
        // Every report and summary is made of finite numbers (the environment never emits NaN,
        // the soak checks it), strings, booleans and lists and objects of those, all of which
        // JSON holds.
        Err(e) => unreachable!("{what} serialises to JSON: {e}"),
    }
}

/// Prints `message` as one warning line on stderr, `hyq: warning: …` (nothing if stderr is
/// closed: a warning must not stop a command).
pub fn warn(message: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "hyq: warning: {message}");
}

/// A progress bar of `total` env steps.
pub fn progress_bar(total: u64) -> ProgressBar {
    // Drawn on stderr only when it is a terminal (indicatif hides it otherwise), so piped and
    // captured output stays clean.
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} steps ({per_sec}) {msg}",
    ) {
        bar.set_style(style);
    }
    bar
}
