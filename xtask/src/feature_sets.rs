//! Every stage of `cargo xtask test` builds shared dependencies with the same features.
//!
//! Cargo unifies a dependency's features over the packages one command selects, and a build with
//! a set of features no earlier stage used compiles that dependency again, with everything built
//! on it. The stages select differently (the workspace without the optional engines, each
//! engine's crates, the Python package), so a dependency that one of them reaches with extra
//! features (DART's cxx-build turning on proc-macro2's `span-locations` for the proc macros,
//! pyo3's macros turning on syn's `extra-traits`) recompiled serde, nalgebra, rapier3d and the
//! rest: with the union held, `.ci/run` on an idle 2-core machine took 174 s for DART's stage
//! (400 s before) and 127 s for the Python stage (267 s).
//! `hyq-workspace-hack` holds the union; this test, from `cargo tree`, finds a dependency whose
//! builds in two stages differ with neither holding the other's.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use crate::stages::{engine_selection, optional_engines, python_features, workspace_selection};
use crate::workspace::{cargo, is_member, workspace_members, workspace_root};

/// Each dependency (`name vX.Y.Z`) of a selection with the feature lists it is built with (one
/// per build of it: a build-time and a run-time one may differ).
type Builds = BTreeMap<String, BTreeSet<String>>;

/// `cargo tree`'s lines (`{p} [{f}]`, no prefix) parsed into [`Builds`], leaving out the
/// workspace's own crates and other path dependencies (their lines name a directory).
fn parse_tree(text: &str) -> Builds {
    let mut builds = Builds::new();
    for line in text.lines() {
        let line = line.replace(" (*)", "").replace(" (proc-macro)", "");
        let (Some(open), true) = (line.find(" ["), line.ends_with(']')) else {
            continue;
        };
        let package = &line[..open];
        if package.contains(" (") {
            continue;
        }
        let features = line[open + 2..line.len() - 1].to_string();
        builds
            .entry(package.to_string())
            .or_default()
            .insert(features);
    }
    builds
}

/// The dependencies two selections build differently, neither's builds holding the other's
/// (a stage that also builds a dependency the way only it needs, such as DART's cxx-build's own
/// hashbrown, recompiles nothing of the others'), one line each.
fn differing(selections: &[(String, Builds)]) -> Vec<String> {
    let mut found = Vec::new();
    for (i, (name_a, a)) in selections.iter().enumerate() {
        for (name_b, b) in &selections[i + 1..] {
            for (package, builds_a) in a {
                let Some(builds_b) = b.get(package) else {
                    continue;
                };
                if !builds_a.is_subset(builds_b) && !builds_b.is_subset(builds_a) {
                    found.push(format!(
                        "{package}: {name_a} builds it with {builds_a:?}, {name_b} with {builds_b:?}"
                    ));
                }
            }
        }
    }
    found
}

/// The dependencies' builds of `cargo tree` over `selection` following `edges`.
fn builds(root: &Path, selection: &[String], edges: &str) -> Builds {
    let output = cargo(root)
        .args([
            "tree",
            "--locked",
            "-e",
            edges,
            "-f",
            "{p} [{f}]",
            "--prefix",
            "none",
        ])
        .args(selection)
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "cargo tree {selection:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    parse_tree(&String::from_utf8_lossy(&output.stdout))
}

#[test]
fn every_stage_builds_shared_dependencies_with_the_same_features() {
    let root = workspace_root();
    let members = workspace_members(&root).expect("cargo metadata lists the members");
    let all = "normal,build,dev";
    let mut selections = vec![(
        "rust workspace".to_string(),
        builds(&root, &workspace_selection(&members), all),
    )];
    for engine in optional_engines().filter(|e| is_member(&members, e.crate_name)) {
        let selection = engine_selection(engine, &members);
        selections.push((engine.name.to_string(), builds(&root, &selection, all)));
    }
    // maturin builds the package's library alone: no dev-dependencies.
    let features = python_features(&optional_engines().collect::<Vec<_>>());
    let python = ["-p", "hyq-py", "--features", &features].map(String::from);
    selections.push(("python".to_string(), builds(&root, &python, "normal,build")));
    assert!(
        selections
            .iter()
            .all(|(_, b)| b.keys().any(|k| k.starts_with("nalgebra v")))
    );
    let found = differing(&selections);
    assert!(
        found.is_empty(),
        "give crates/hyq-workspace-hack the union of these features:\n{}",
        found.join("\n")
    );
}

#[test]
fn a_dependency_built_with_features_no_other_stage_uses_is_found() {
    let first = parse_tree(
        "hyq-env v0.1.0 (crates/hyq-env) []\n\
         proc-macro2 v1.0.107 [default,proc-macro]\n\
         hashbrown v0.17.1 [default-hasher]\n",
    );
    let second = parse_tree(
        "proc-macro2 v1.0.107 [default,proc-macro,span-locations] (*)\n\
         hashbrown v0.17.1 []\nhashbrown v0.17.1 [default-hasher]\n",
    );
    assert!(!first.contains_key("hyq-env v0.1.0 (crates/hyq-env)"));
    let found = differing(&[("a".into(), first), ("b".into(), second)]);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].starts_with("proc-macro2 v1.0.107: a builds it with"));
}
