//! `cargo xtask vendor-check` and `cargo xtask vendor-diff`: `vendor/rapier3d` is the published
//! rapier3d crate plus the patches in `vendor/patches/`, and nothing else.
//!
//! The check
//! 1. takes the published `.crate` archive from cargo's registry cache (having cargo download it
//!    first when it is not there) and refuses it unless its SHA-256 is the one crates.io
//!    published ([`CRATE_SHA256`], the checksum `Cargo.lock` recorded before the patch);
//! 2. unpacks it and applies `vendor/patches/*.patch` in name order, each hunk exactly where it
//!    says (no fuzz, no offset);
//! 3. compares the result with `vendor/rapier3d` file by file: the same files plus `LICENSE` and
//!    `PATCHES.md`, the same bytes, except that every file a patch touches starts with the line
//!    [`HEADER`] (Apache-2.0 §4(b): modified files carry a notice saying so);
//! 4. runs rapier's own multibody tests and the tests the patches add, on the vendored tree.
//!
//! `vendor-diff` prints what the vendored tree holds beyond the pristine crate and the committed
//! patches, as an upstream-ready diff (paths as in rapier's repository, notice lines left out):
//! the next patch file, or nothing when the tree is clean.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::workspace::{cargo, workspace_root};

/// The vendored crate.
const CRATE: &str = "rapier3d";
/// Its published version.
const VERSION: &str = "0.36.1";
/// SHA-256 of the published `rapier3d-0.36.1.crate` (crates.io's checksum).
const CRATE_SHA256: &str = "033e2edc815d61ab97bd74ed5d1cbea5ebe575218774a7cfedbd3551f0033317";
/// The first line of every vendored file a patch touches.
pub const HEADER: &str = "// Changed by the hyq-env project (Apache-2.0 §4(b)); the changes: PATCHES.md at this crate's root.";
/// Files the vendored tree has beyond the published crate.
const ADDED: [&str; 2] = ["LICENSE", "PATCHES.md"];

/// rapier's tests that exercise multibodies, run by the check: the library's tests under
/// `dynamics::joint::multibody_joint` (its regression tests, the unit tests of `multibody.rs`
/// and those the patches add) and these integration tests.
const MULTIBODY_TESTS: [&str; 9] = [
    "multibody_armature",
    "multibody_coupling",
    "multibody_coupling_topology",
    "multibody_dof_inertia",
    "multibody_spring",
    "gyroscopic",
    "issue_954_multibody_parallel_contact",
    "issue_968_multibody_weld_settle",
    "loop_closure_com_repro",
];

/// `cargo xtask vendor-check [--no-tests]`.
pub fn vendor_check(args: &[String]) -> Result<(), String> {
    let mut run_tests = true;
    for arg in args {
        match arg.as_str() {
            "--no-tests" => run_tests = false,
            other => {
                return Err(format!(
                    "`cargo xtask vendor-check`: unknown argument `{other}`"
                ));
            }
        }
    }
    let root = workspace_root();
    let patches = check_tree(&root)?;
    println!("vendor/{CRATE} is {CRATE} {VERSION} (sha256 {CRATE_SHA256}) plus {patches} patches");
    if run_tests {
        let tests = run_vendored_tests(&root)?;
        println!("vendor/{CRATE}: {tests} multibody tests passed");
    }
    Ok(())
}

/// The stage of `cargo xtask test`: the tree check and the tests; returns how many tests passed.
pub fn stage(root: &Path) -> Result<u64, String> {
    check_tree(root)?;
    run_vendored_tests(root)
}

/// `cargo xtask vendor-diff`.
pub fn vendor_diff(args: &[String]) -> Result<(), String> {
    if let Some(arg) = args.first() {
        return Err(format!(
            "`cargo xtask vendor-diff`: unknown argument `{arg}`"
        ));
    }
    let root = workspace_root();
    let work = work_dir(&root).join("diff");
    reset_dir(&work)?;
    let expected = expected_tree(&root)?;
    let vendored = read_tree(&root.join("vendor").join(CRATE))?;
    for (side, tree, strip) in [("a", &expected.files, false), ("b", &vendored, true)] {
        for (path, bytes) in tree {
            if ADDED.contains(&path.as_str()) {
                continue;
            }
            let bytes = if strip {
                strip_header(bytes).unwrap_or(bytes)
            } else {
                bytes
            };
            let dest = work.join(side).join(path);
            if let Some(parent) = dest.parent() {
                std::fs::create_dir_all(parent)
                    .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
            }
            std::fs::write(&dest, bytes)
                .map_err(|e| format!("cannot write {}: {e}", dest.display()))?;
        }
    }
    let status = Command::new("git")
        .current_dir(&work)
        .args([
            "diff",
            "--no-index",
            "--no-prefix",
            "--no-color",
            "--no-ext-diff",
            "--no-renames",
            "a",
            "b",
        ])
        .status()
        .map_err(|e| format!("cannot run git diff: {e}"))?;
    match status.code() {
        Some(0) | Some(1) => Ok(()),
        _ => Err(format!("`git diff --no-index` failed ({status})")),
    }
}

/// Files of a tree: path relative to its root (with `/`) → bytes.
type Tree = BTreeMap<String, Vec<u8>>;

/// The pristine crate with the patches applied, and which files they touched.
struct Expected {
    files: Tree,
    touched: Vec<String>,
    patches: usize,
}

/// Where the check unpacks and builds: `vendor-check` in the target directory.
fn work_dir(root: &Path) -> PathBuf {
    crate::workspace::target_dir(root).join("vendor-check")
}

fn reset_dir(dir: &Path) -> Result<(), String> {
    if dir.exists() {
        std::fs::remove_dir_all(dir)
            .map_err(|e| format!("cannot remove {}: {e}", dir.display()))?;
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))
}

/// Steps 1–3 of the check; returns the number of patches.
fn check_tree(root: &Path) -> Result<usize, String> {
    let expected = expected_tree(root)?;
    let vendored = read_tree(&root.join("vendor").join(CRATE))?;
    compare(&expected, &vendored)?;
    Ok(expected.patches)
}

/// Compares the vendored tree with the expected one; the error lists every difference.
fn compare(expected: &Expected, vendored: &Tree) -> Result<(), String> {
    let mut problems = Vec::new();
    for (path, want) in &expected.files {
        let Some(have) = vendored.get(path) else {
            problems.push(format!("{path}: missing"));
            continue;
        };
        if expected.touched.contains(path) {
            match strip_header(have) {
                None => problems.push(format!(
                    "{path}: changed by a patch but its first line is not the notice `{HEADER}`"
                )),
                Some(body) if body != want.as_slice() => problems.push(format!(
                    "{path}: differs from the published file plus the patches (run `cargo xtask vendor-diff`)"
                )),
                Some(_) => {}
            }
        } else if have != want {
            problems.push(format!(
                "{path}: differs from the published file plus the patches (run `cargo xtask vendor-diff`)"
            ));
        }
    }
    for path in vendored.keys() {
        if !expected.files.contains_key(path) && !ADDED.contains(&path.as_str()) {
            problems.push(format!(
                "{path}: not in the published crate and created by no patch"
            ));
        }
    }
    for added in ADDED {
        if !vendored.contains_key(added) {
            problems.push(format!("{added}: missing"));
        }
    }
    let license = vendored.get("LICENSE").map(|b| String::from_utf8_lossy(b));
    if license.is_some_and(|l| !(l.contains("Apache License") && l.contains("Version 2.0"))) {
        problems.push("LICENSE: not the Apache License 2.0 text".into());
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "vendor/{CRATE} is not {CRATE} {VERSION} plus vendor/patches:\n  {}",
            problems.join("\n  ")
        ))
    }
}

/// The file without its first line when that line is [`HEADER`].
fn strip_header(bytes: &[u8]) -> Option<&[u8]> {
    bytes
        .strip_prefix(HEADER.as_bytes())
        .and_then(|rest| rest.strip_prefix(b"\n"))
}

/// Steps 1 and 2: the published crate, verified, unpacked, with the patches applied.
fn expected_tree(root: &Path) -> Result<Expected, String> {
    let archive = published_crate(root)?;
    let unpacked = work_dir(root).join("pristine");
    reset_dir(&unpacked)?;
    let status = Command::new("tar")
        .arg("xzf")
        .arg(&archive)
        .arg("-C")
        .arg(&unpacked)
        .status()
        .map_err(|e| format!("cannot run tar: {e}"))?;
    if !status.success() {
        return Err(format!("`tar xzf {}` failed ({status})", archive.display()));
    }
    let mut files = read_tree(&unpacked.join(format!("{CRATE}-{VERSION}")))?;
    let mut touched = Vec::new();
    let patch_dir = root.join("vendor").join("patches");
    let entries = match std::fs::read_dir(&patch_dir) {
        Ok(entries) => entries.filter_map(|e| e.ok().map(|e| e.path())).collect(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
        Err(e) => return Err(format!("cannot read {}: {e}", patch_dir.display())),
    };
    let mut patch_files: Vec<PathBuf> = entries
        .into_iter()
        .filter(|p| p.extension().is_some_and(|x| x == "patch"))
        .collect();
    patch_files.sort();
    for patch in &patch_files {
        let text = std::fs::read_to_string(patch)
            .map_err(|e| format!("cannot read {}: {e}", patch.display()))?;
        for path in
            apply_patch(&mut files, &text).map_err(|e| format!("{}: {e}", patch.display()))?
        {
            if !touched.contains(&path) {
                touched.push(path);
            }
        }
    }
    Ok(Expected {
        files,
        touched,
        patches: patch_files.len(),
    })
}

/// The published `.crate` archive in cargo's registry cache, downloaded by `cargo fetch` when
/// missing, after checking its SHA-256.
fn published_crate(root: &Path) -> Result<PathBuf, String> {
    let name = format!("{CRATE}-{VERSION}.crate");
    let archive = match find_in_cache(&name) {
        Some(path) => path,
        None => {
            fetch(root)?;
            find_in_cache(&name).ok_or_else(|| {
                format!("`cargo fetch` did not put {name} into cargo's registry cache")
            })?
        }
    };
    let sum = sha256(&archive)?;
    if sum != CRATE_SHA256 {
        return Err(format!(
            "{} has SHA-256 {sum}, not crates.io's {CRATE_SHA256}",
            archive.display()
        ));
    }
    Ok(archive)
}

/// `$CARGO_HOME/registry/cache/*/name`, if there.
fn find_in_cache(name: &str) -> Option<PathBuf> {
    let home = std::env::var_os("CARGO_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cargo")))?;
    let cache = home.join("registry").join("cache");
    std::fs::read_dir(cache)
        .ok()?
        .filter_map(|e| e.ok())
        .map(|e| e.path().join(name))
        .find(|p| p.is_file())
}

/// Has cargo download the published crate: `cargo fetch` on a one-dependency manifest (its own
/// workspace, so the project's `[patch]` does not apply).
fn fetch(root: &Path) -> Result<(), String> {
    let dir = work_dir(root).join("fetch");
    reset_dir(&dir)?;
    std::fs::create_dir_all(dir.join("src")).map_err(|e| format!("cannot create: {e}"))?;
    let manifest = format!(
        "[package]\nname = \"vendor-check-fetch\"\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n[dependencies]\n{CRATE} = \"={VERSION}\"\n\n[workspace]\n"
    );
    std::fs::write(dir.join("Cargo.toml"), manifest).map_err(|e| format!("cannot write: {e}"))?;
    std::fs::write(dir.join("src").join("lib.rs"), "").map_err(|e| format!("cannot write: {e}"))?;
    println!(
        "$ cargo fetch --manifest-path {}",
        dir.join("Cargo.toml").display()
    );
    let status = cargo(&dir)
        .args(["fetch", "--manifest-path"])
        .arg(dir.join("Cargo.toml"))
        .status()
        .map_err(|e| format!("cannot start cargo: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(
            "`cargo fetch` of {CRATE} {VERSION} failed ({status})"
        ))
    }
}

/// SHA-256 of a file, by coreutils' `sha256sum`.
fn sha256(path: &Path) -> Result<String, String> {
    let out = Command::new("sha256sum")
        .arg(path)
        .output()
        .map_err(|e| format!("cannot run sha256sum: {e}"))?;
    if !out.status.success() {
        return Err(format!("`sha256sum {}` failed", path.display()));
    }
    String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .next()
        .map(str::to_string)
        .ok_or_else(|| "sha256sum printed nothing".into())
}

/// Every file under `dir` (a crate root), except a `target/` build directory at its top.
fn read_tree(dir: &Path) -> Result<Tree, String> {
    fn walk(dir: &Path, prefix: &str, out: &mut Tree) -> Result<(), String> {
        let entries =
            std::fs::read_dir(dir).map_err(|e| format!("cannot read {}: {e}", dir.display()))?;
        for entry in entries {
            let entry = entry.map_err(|e| format!("cannot read {}: {e}", dir.display()))?;
            let name = entry.file_name().to_string_lossy().into_owned();
            let rel = if prefix.is_empty() {
                name.clone()
            } else {
                format!("{prefix}/{name}")
            };
            let path = entry.path();
            if path.is_dir() {
                if rel != "target" {
                    walk(&path, &rel, out)?;
                }
            } else {
                let bytes = std::fs::read(&path)
                    .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
                out.insert(rel, bytes);
            }
        }
        Ok(())
    }
    let mut out = Tree::new();
    walk(dir, "", &mut out)?;
    Ok(out)
}

/// Applies a unified diff (as `git diff` writes it, paths `a/…` and `b/…` relative to the crate
/// root) to `files`, strictly: every hunk at its stated line, context and removed lines equal.
/// Returns the paths it touched.
fn apply_patch(files: &mut Tree, text: &str) -> Result<Vec<String>, String> {
    let mut touched = Vec::new();
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    let mut i = 0;
    while i < lines.len() {
        let Some(old) = lines[i].strip_prefix("--- ") else {
            i += 1;
            continue;
        };
        let new = lines
            .get(i + 1)
            .and_then(|l| l.strip_prefix("+++ "))
            .ok_or_else(|| format!("line {}: `---` without `+++`", i + 1))?;
        let old = old.trim_end();
        let path = new
            .trim_end()
            .strip_prefix("b/")
            .ok_or_else(|| format!("line {}: target path does not start with b/", i + 2))?
            .to_string();
        i += 2;
        let source = patch_source(files, old, &path)?;
        let mut result: Vec<String> = Vec::new();
        let mut next = 0; // first source line not yet copied
        while i < lines.len() && lines[i].starts_with("@@ ") {
            apply_hunk(&lines, &mut i, &path, &source, &mut next, &mut result)?;
        }
        result.extend(source[next..].iter().cloned());
        files.insert(path.clone(), result.concat().into_bytes());
        touched.push(path);
    }
    Ok(touched)
}

/// The lines of the file a patch's `--- old` names: none for a file it creates (which must not
/// exist yet), else the file of `path`, which the patch must not rename.
fn patch_source(files: &Tree, old: &str, path: &str) -> Result<Vec<String>, String> {
    if old == "/dev/null" {
        if files.contains_key(path) {
            return Err(format!("{path}: created by the patch but already exists"));
        }
        return Ok(Vec::new());
    }
    if old.strip_prefix("a/") != Some(path) {
        return Err(format!("{path}: renames are not supported"));
    }
    let bytes = files
        .get(path)
        .ok_or_else(|| format!("{path}: no such file to patch"))?;
    Ok(String::from_utf8(bytes.clone())
        .map_err(|_| format!("{path}: not UTF-8"))?
        .split_inclusive('\n')
        .map(str::to_string)
        .collect())
}

/// Applies the hunk whose header is `lines[*i]` to `source` at `*next` (the first source line
/// not yet copied), appending to `result`; leaves `*i` after the hunk.
fn apply_hunk(
    lines: &[&str],
    i_at: &mut usize,
    path: &str,
    source: &[String],
    next_at: &mut usize,
    result: &mut Vec<String>,
) -> Result<(), String> {
    let mut i = *i_at;
    let mut next = *next_at;
    let (start, mut old_left, mut new_left) =
        hunk_header(lines[i]).ok_or_else(|| format!("line {}: malformed hunk header", i + 1))?;
    // Line numbers count from 1; a hunk that adds to an empty side starts at 0.
    let at = if old_left == 0 {
        start
    } else {
        start.saturating_sub(1)
    };
    if at < next || at > source.len() {
        return Err(format!(
            "{path}: hunk at line {start} is out of order or range"
        ));
    }
    result.extend(source[next..at].iter().cloned());
    next = at;
    i += 1;
    while old_left + new_left > 0 || lines.get(i).is_some_and(|l| l.starts_with('\\')) {
        let line = lines
            .get(i)
            .ok_or_else(|| format!("{path}: the patch ends inside a hunk"))?;
        let (kind, body) = line.split_at(line.len().min(1));
        match kind {
            " " | "-" if old_left > 0 => {
                if source.get(next).map(String::as_str) != Some(body) {
                    return Err(format!(
                        "{path}: line {} does not match the patch's context",
                        next + 1
                    ));
                }
                if kind == " " {
                    if new_left == 0 {
                        return Err(format!("{path}: hunk longer than its header says"));
                    }
                    new_left -= 1;
                    result.push(body.to_string());
                }
                old_left -= 1;
                next += 1;
            }
            "+" if new_left > 0 => {
                new_left -= 1;
                result.push(body.to_string());
            }
            "\\" => {
                // `\ No newline at end of file`: the previous line has no newline.
                if let Some(last) = result.last_mut()
                    && last.ends_with('\n')
                {
                    last.pop();
                }
            }
            _ => {
                return Err(format!("line {}: does not fit the hunk's header", i + 1));
            }
        }
        i += 1;
    }
    *i_at = i;
    *next_at = next;
    Ok(())
}

/// The old side's first line and the two sides' lengths of a hunk header
/// `@@ -start,len +start,len @@` (a missing length is 1).
fn hunk_header(header: &str) -> Option<(usize, usize, usize)> {
    let mut parts = header.strip_prefix("@@ -")?.split_whitespace();
    let side = |text: &str| -> Option<(usize, usize)> {
        let mut it = text.split(',');
        let start = it.next()?.parse().ok()?;
        let len = it.next().map_or(Some(1), |l| l.parse().ok())?;
        Some((start, len))
    };
    let (start, old_len) = side(parts.next()?)?;
    let (_, new_len) = side(parts.next()?.strip_prefix('+')?)?;
    Some((start, old_len, new_len))
}

/// Runs rapier's multibody tests on the vendored tree (its own `Cargo.lock`, its own target
/// directory); returns how many passed.
fn run_vendored_tests(root: &Path) -> Result<u64, String> {
    let manifest = root.join("vendor").join(CRATE).join("Cargo.toml");
    let manifest = manifest.to_string_lossy().into_owned();
    let target = crate::workspace::target_dir(root).join("vendor-rapier3d");
    let mut passed = 0;
    let lib: Vec<&str> = vec![
        "test",
        "--manifest-path",
        &manifest,
        "--locked",
        "--lib",
        "--",
        "dynamics::joint::multibody_joint::",
    ];
    let mut integration: Vec<&str> = vec!["test", "--manifest-path", &manifest, "--locked"];
    for name in MULTIBODY_TESTS {
        integration.extend(["--test", name]);
    }
    for args in [lib, integration] {
        println!(
            "\n$ CARGO_TARGET_DIR={} cargo {}",
            target.display(),
            args.join(" ")
        );
        let out = cargo(root)
            .env("CARGO_TARGET_DIR", &target)
            .args(&args)
            .output()
            .map_err(|e| format!("cannot start cargo: {e}"))?;
        let stdout = String::from_utf8_lossy(&out.stdout);
        print!("{stdout}");
        if !out.status.success() {
            eprint!("{}", String::from_utf8_lossy(&out.stderr));
            return Err(format!(
                "`cargo {}` failed ({})",
                args.join(" "),
                out.status
            ));
        }
        passed += stdout
            .lines()
            .map(crate::workspace::passed_count)
            .sum::<u64>();
    }
    Ok(passed)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tree(files: &[(&str, &str)]) -> Tree {
        files
            .iter()
            .map(|(p, t)| (p.to_string(), t.as_bytes().to_vec()))
            .collect()
    }

    const PATCH: &str = "\
diff --git a/src/a.rs b/src/a.rs
--- a/src/a.rs
+++ b/src/a.rs
@@ -2,3 +2,3 @@
 two
-three
+THREE
 four
diff --git a/src/new.rs b/src/new.rs
new file mode 100644
--- /dev/null
+++ b/src/new.rs
@@ -0,0 +1,2 @@
+fn new() {}
+// end
";

    #[test]
    fn a_patch_applies_at_its_stated_lines_and_creates_files() {
        let mut files = tree(&[("src/a.rs", "one\ntwo\nthree\nfour\nfive\n")]);
        let touched = apply_patch(&mut files, PATCH).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(touched, ["src/a.rs", "src/new.rs"]);
        assert_eq!(files["src/a.rs"], b"one\ntwo\nTHREE\nfour\nfive\n");
        assert_eq!(files["src/new.rs"], b"fn new() {}\n// end\n");
    }

    #[test]
    fn a_patch_whose_context_does_not_match_is_refused() {
        let mut files = tree(&[("src/a.rs", "one\ntwo\nthree!\nfour\nfive\n")]);
        let err = apply_patch(&mut files, PATCH).expect_err("changed context must be refused");
        assert!(err.contains("src/a.rs"), "{err}");
        // Shifted by one line: no offset is searched for.
        let mut files = tree(&[("src/a.rs", "zero\none\ntwo\nthree\nfour\nfive\n")]);
        assert!(apply_patch(&mut files, PATCH).is_err());
    }

    #[test]
    fn the_vendored_tree_must_be_the_expected_one_with_notices_on_touched_files() {
        let mut files = tree(&[("src/a.rs", "a\n"), ("src/b.rs", "b\n")]);
        files.insert("src/a.rs".into(), b"A\n".to_vec());
        let expected = Expected {
            files,
            touched: vec!["src/a.rs".into()],
            patches: 1,
        };
        let good = tree(&[
            ("src/a.rs", &format!("{HEADER}\nA\n")),
            ("src/b.rs", "b\n"),
            ("LICENSE", "Apache License\nVersion 2.0, January 2004\n"),
            ("PATCHES.md", "# patches\n"),
        ]);
        assert_eq!(compare(&expected, &good), Ok(()));

        let mut no_notice = good.clone();
        no_notice.insert("src/a.rs".into(), b"A\n".to_vec());
        let err = compare(&expected, &no_notice).expect_err("a touched file needs the notice");
        assert!(err.contains("src/a.rs") && err.contains("notice"), "{err}");

        let mut edited = good.clone();
        edited.insert("src/b.rs".into(), b"b changed\n".to_vec());
        let err = compare(&expected, &edited).expect_err("an unpatched edit must be found");
        assert!(err.contains("src/b.rs"), "{err}");

        let mut extra = good.clone();
        extra.insert("src/c.rs".into(), b"c\n".to_vec());
        assert!(compare(&expected, &extra).is_err());

        let mut no_license = good;
        no_license.remove("LICENSE");
        assert!(compare(&expected, &no_license).is_err());
    }
}
