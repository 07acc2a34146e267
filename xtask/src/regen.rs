//! `cargo xtask regen-reports [--dev]`: remakes every committed file a `hyq` command wrote and
//! shows that nothing changed. The commands are read from the documents that already state them,
//! so there is no second list to keep: each `docs/comparison/*/report.md` names the command that
//! wrote its directory, and `docs/media/README.md` gives the command of each image and GIF
//! (`cargo run --release -p hyq-cli -- ARGS`). One build of `hyq` with every engine (release; the
//! dev profile with `--dev`, which gives the same bytes) runs them all from the workspace root,
//! then `git status` lists what differs under `docs/comparison` and `docs/media`: the command
//! fails if anything does. The training curves in `docs/media` come from training runs
//! (`docs/training.md`), not from `hyq`, and are left alone.

use std::path::Path;
use std::process::Command;

use crate::workspace::{run_cargo, workspace_root};

/// The folders whose files the commands write.
const OUTPUTS: [&str; 2] = ["docs/comparison", "docs/media"];

/// The start of a media command in `docs/media/README.md`; its `hyq` arguments follow ` -- `.
const MEDIA_PREFIX: &str = "cargo run --release -p hyq-cli";

/// `cargo xtask regen-reports`.
pub fn regen_reports(args: &[String]) -> Result<(), String> {
    let dev = match args {
        [] => false,
        [flag] if flag == "--dev" => true,
        _ => {
            return Err(format!(
                "`cargo xtask regen-reports` takes only --dev, got {args:?}"
            ));
        }
    };
    let root = workspace_root();
    // The check is against the committed files, so uncommitted edits there would be blamed on
    // the commands.
    let edited = git(&root, &["status", "--porcelain", "--"])?;
    if !edited.trim().is_empty() {
        return Err(format!(
            "commit or stash the changes under {} first, so that what the commands change \
             shows:\n{edited}",
            OUTPUTS.join(" and ")
        ));
    }
    let commands = commands(&root)?;
    let mut build = crate::cli::strings(&["build", "--locked", "-p", "hyq-cli"]);
    if !dev {
        build.push("--release".into());
    }
    let features: Vec<&str> = hyq_engines::ENGINES
        .iter()
        .filter_map(|e| e.feature)
        .collect();
    build.push("--features".into());
    build.push(features.join(","));
    if !run_cargo(&root, &build)?.success() {
        return Err("building hyq failed".into());
    }
    // Where cargo put it: `$CARGO_TARGET_DIR` when set, as for every xtask build.
    let hyq = crate::workspace::target_dir(&root)
        .join(if dev { "debug" } else { "release" })
        .join("hyq");
    for words in &commands {
        println!("$ hyq {}", words.join(" "));
        let status = Command::new(&hyq)
            .args(words)
            .current_dir(&root)
            .status()
            .map_err(|e| format!("cannot start {}: {e}", hyq.display()))?;
        if !status.success() {
            return Err(format!("`hyq {}` failed ({status})", words.join(" ")));
        }
    }
    let changed = git(&root, &["status", "--porcelain", "--"])?;
    if changed.trim().is_empty() {
        println!(
            "{} commands rewrote {} byte for byte",
            commands.len(),
            OUTPUTS.join(" and ")
        );
        Ok(())
    } else {
        let stat = git(&root, &["diff", "--stat", "--"])?;
        Err(format!(
            "the regenerated files differ from the committed ones:\n{changed}{stat}"
        ))
    }
}

/// `git ARGS OUTPUTS...` in `root`, its stdout.
fn git(root: &Path, args: &[&str]) -> Result<String, String> {
    let out = Command::new("git")
        .args(args)
        .args(OUTPUTS)
        .current_dir(root)
        .output()
        .map_err(|e| format!("cannot start git: {e}"))?;
    if !out.status.success() {
        return Err(format!("git {} failed ({})", args.join(" "), out.status));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Every command's `hyq` arguments: each comparison report's, in the folders' order, then the
/// media README's.
fn commands(root: &Path) -> Result<Vec<Vec<String>>, String> {
    let read = |path: &Path| {
        std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))
    };
    let mut dirs: Vec<_> = std::fs::read_dir(root.join("docs/comparison"))
        .map_err(|e| format!("cannot list docs/comparison: {e}"))?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| p.join("report.md").is_file())
        .collect();
    dirs.sort();
    let mut commands = Vec::new();
    for dir in dirs {
        let report = dir.join("report.md");
        let words = report_command(&read(&report)?)
            .ok_or_else(|| format!("{} names no `hyq compare` command", report.display()))??;
        commands.push(words);
    }
    for line in read(&root.join("docs/media/README.md"))?.lines() {
        if let Some(rest) = line.strip_prefix(MEDIA_PREFIX) {
            let (_, args) = rest
                .split_once(" -- ")
                .ok_or_else(|| format!("docs/media/README.md: no ` -- ` in `{line}`"))?;
            commands.push(words(args)?);
        }
    }
    Ok(commands)
}

/// The arguments of the `hyq compare` command a report states (its first line starting so).
fn report_command(report: &str) -> Option<Result<Vec<String>, String>> {
    report
        .lines()
        .find_map(|line| line.strip_prefix("hyq "))
        .map(words)
}

/// `line` split at white space; a quote would need a shell's rules, so it is refused.
fn words(line: &str) -> Result<Vec<String>, String> {
    if line.contains(['\'', '"', '\\']) {
        return Err(format!(
            "`{line}` needs a shell to split (quotes or escapes)"
        ));
    }
    Ok(line.split_whitespace().map(String::from).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_committed_report_and_media_file_has_its_command() {
        let commands = commands(&workspace_root()).unwrap_or_else(|e| panic!("{e}"));
        let compares = commands.iter().filter(|c| c[0] == "compare").count();
        let reports = std::fs::read_dir(workspace_root().join("docs/comparison"))
            .expect("docs/comparison")
            .count();
        assert_eq!(compares, reports, "one command per comparison report");
        // Each media command writes into docs/media, where the README says its file is.
        let media: Vec<_> = commands.iter().filter(|c| c[0] != "compare").collect();
        assert!(media.len() >= 4, "{media:?}");
        for c in media {
            assert!(
                c.iter().any(|w| w.starts_with("docs/media/")),
                "{c:?} writes outside docs/media"
            );
        }
    }

    #[test]
    fn a_quoted_argument_is_refused_not_split_wrongly() {
        assert!(words("compare --set 'a=[1, 2]'").is_err());
        assert_eq!(
            words("compare  --seed 3").unwrap_or_else(|e| panic!("{e}")),
            ["compare", "--seed", "3"]
        );
        assert!(report_command("no command here").is_none());
    }
}
