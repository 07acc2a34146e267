//! Invariant: `docs/spec-deviations.md` stays true to the tests. Every test it names as showing a
//! reason (`file.rs::test`, or a test listed after a file under "Shown by") exists in that file,
//! and each of RULINGS' three deviations (§4.1, §4.3, §6.2) has its entry.

use std::path::{Path, PathBuf};

const PAGE: &str = include_str!("../../../docs/spec-deviations.md");

/// The backticked spans of `text`, in order.
fn backticked(text: &str) -> Vec<&str> {
    text.split('`').skip(1).step_by(2).collect()
}

/// `tests/x.rs` for `x.rs`; `src/…` and `tests/…` as they are, in this crate; `crates/…` and
/// `spec-tests/…` from the repository root.
fn resolve(file: &str) -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    if file.starts_with("crates/") || file.starts_with("spec-tests/") {
        manifest.join("../..").join(file)
    } else if file.starts_with("src/") || file.starts_with("tests/") {
        manifest.join(file)
    } else {
        manifest.join("tests").join(file)
    }
}

fn check_test_exists(file: &str, name: &str) {
    let path = resolve(file);
    let source =
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(
        source.contains(&format!("fn {name}(")) || source.contains(&format!("fn {name}<")),
        "the page names `{file}::{name}`, which {} lacks",
        path.display()
    );
}

/// Checks the tests named by one run of backticked spans: a span with `.rs` sets the current file
/// (and names a test after `::`); a later bare identifier names a test in the current file.
fn check_spans(spans: &[&str]) -> usize {
    let mut file: Option<&str> = None;
    let mut checked = 0;
    for span in spans {
        if let Some((path, rest)) = span.split_once(".rs") {
            let f = &span[..path.len() + 3];
            file = Some(f);
            if let Some(name) = rest.strip_prefix("::") {
                check_test_exists(f, name);
                checked += 1;
            }
        } else if let Some(f) = file
            && span
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        {
            check_test_exists(f, span);
            checked += 1;
        }
    }
    checked
}

#[test]
fn every_named_test_exists() {
    let mut checked = 0;
    for segment in PAGE.split("**Shown by:**").skip(1) {
        let end = segment
            .find("\n- **")
            .into_iter()
            .chain(segment.find("\n#"))
            .min()
            .unwrap_or(segment.len());
        checked += check_spans(&backticked(&segment[..end]));
    }
    for line in PAGE.lines().filter(|l| l.starts_with("| §")) {
        checked += check_spans(&backticked(line));
    }
    assert!(
        checked >= 60,
        "only {checked} test references found: has the page's format changed?"
    );
}

#[test]
fn each_ruled_deviation_has_an_entry() {
    for heading in [
        "### §4.1 Base reward (deviation)",
        "### §4.3 Exponential reward (deviation)",
        "### §6.2 Reach joint limits (deviation)",
    ] {
        assert!(PAGE.contains(heading), "missing {heading}");
    }
}
