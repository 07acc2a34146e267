//! No two files of this crate import each other, directly or round a loop: every `crate::`
//! path outside a test module names the file it reaches (or a name the crate root re-exports
//! from one), and the graph of those edges has no cycle. The report modules hand the plot plain
//! lines to draw, so the plot knows no report; the ledger's `Check` and the one-step report
//! live in `report.rs`, which `compare.rs` fills.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The identifier at the start of `s`.
fn ident(s: &str) -> &str {
    let end = s
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(s.len());
    &s[..end]
}

/// The first path segments `src` reaches through `crate::` (`crate::a::X`, `crate::X`,
/// `crate::{a::X, b}`), outside its test modules.
fn crate_paths(src: &str) -> Vec<String> {
    let code = src.split("#[cfg(test)]").next().unwrap_or("");
    let mut out = Vec::new();
    for (_, rest) in code
        .match_indices("crate::")
        .map(|(i, m)| (i, &code[i + m.len()..]))
    {
        if let Some(group) = rest.strip_prefix('{') {
            let inner = group.split('}').next().unwrap_or("");
            out.extend(inner.split(',').map(|p| ident(p.trim()).to_owned()));
        } else {
            out.push(ident(rest).to_owned());
        }
    }
    out.retain(|s| !s.is_empty());
    out
}

/// The names lib.rs re-exports, with the module each comes from (`pub use m::{A, B};`).
fn reexports(lib: &str) -> BTreeMap<String, String> {
    let mut map = BTreeMap::new();
    for stmt in lib.split(';') {
        let Some(rest) = stmt.trim().strip_prefix("pub use ") else {
            continue;
        };
        let module = ident(rest).to_owned();
        let names = rest[module.len()..].trim_start_matches("::");
        for name in names.split(|c: char| !(c.is_alphanumeric() || c == '_')) {
            if !name.is_empty() {
                map.insert(name.to_owned(), module.clone());
            }
        }
    }
    map
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Each file's edges to the other files of the crate.
fn graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let files: BTreeSet<String> = std::fs::read_dir(src)
        .unwrap_or_else(|e| panic!("{}: {e}", src.display()))
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter_map(|n| n.strip_suffix(".rs").map(str::to_owned))
        .filter(|n| n != "lib")
        .collect();
    let names = reexports(&read(&src.join("lib.rs")));
    let mut edges = BTreeMap::new();
    for file in &files {
        let to: BTreeSet<String> = crate_paths(&read(&src.join(format!("{file}.rs"))))
            .into_iter()
            .filter_map(|seg| match files.contains(&seg) {
                true => Some(seg),
                false => names.get(&seg).cloned(),
            })
            .filter(|m| m != file)
            .collect();
        edges.insert(file.clone(), to);
    }
    edges
}

/// A loop through `from` if there is one: the files from `from` back to it.
fn loop_through(edges: &BTreeMap<String, BTreeSet<String>>, from: &str) -> Option<Vec<String>> {
    let mut stack = vec![vec![from.to_owned()]];
    let mut seen = BTreeSet::new();
    while let Some(path) = stack.pop() {
        let last = path.last().cloned().unwrap_or_default();
        for next in edges.get(&last).into_iter().flatten() {
            if next == from {
                return Some([path.clone(), vec![next.clone()]].concat());
            }
            if seen.insert(next.clone()) {
                stack.push([path.clone(), vec![next.clone()]].concat());
            }
        }
    }
    None
}

#[test]
fn no_file_of_the_crate_imports_another_round_a_loop() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let edges = graph(&src);
    assert!(edges.len() > 5, "read the crate's files: {edges:?}");
    assert!(
        edges["policy"].contains("report") && edges["plot"].contains("error"),
        "the edges are found: {edges:?}"
    );
    let loops: Vec<String> = edges
        .keys()
        .filter_map(|f| loop_through(&edges, f))
        .map(|l| l.join(" → "))
        .collect();
    assert!(loops.is_empty(), "import circles: {loops:?}");
}

#[test]
fn the_finder_sees_a_loop_and_grouped_and_re_exported_paths() {
    assert_eq!(
        crate_paths(
            "use crate::a::X;\nuse crate::{b::Y, c};\nfn f() { crate::Z::new() }\n#[cfg(test)]\nuse crate::d;"
        ),
        ["a", "b", "c", "Z"]
    );
    let names = reexports("pub use a::{X, Y};\npub use b::Z;\nmod a;");
    assert_eq!(names.get("Y").map(String::as_str), Some("a"));
    assert_eq!(names.get("Z").map(String::as_str), Some("b"));
    let edges: BTreeMap<String, BTreeSet<String>> = [
        ("a", vec!["b"]),
        ("b", vec!["c"]),
        ("c", vec!["a"]),
        ("d", vec!["a"]),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_owned(), v.into_iter().map(str::to_owned).collect()))
    .collect();
    assert_eq!(
        loop_through(&edges, "a").map(|l| l.join(" → ")),
        Some("a → b → c → a".to_owned())
    );
    assert_eq!(loop_through(&edges, "d"), None);
}
