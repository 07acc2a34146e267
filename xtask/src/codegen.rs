//! `cargo xtask codegen`: writes the documents' sections that are made from the code's one
//! statement of each schema (rust-analyzer's `cargo xtask codegen`): the README's info table (from
//! hyq-env's `INFO_KEYS`), the keys `[randomize]` adds to it (`RANDOMIZE_INFO_KEYS`, in the README
//! and docs/robustness.md) and step record table (from `RECORD_KEYS`), the same record table in
//! the command's README, the reward terms' names (hyq-spec's `REWARD_TERMS`) where a page lists
//! them, and the configuration's tables and `[task]` keys (`EnvConfig::TABLES`, `TaskConfig`).
//!
//! A section sits between `<!-- codegen:NAME -->` and `<!-- end codegen:NAME -->` in its file;
//! everything outside the markers is left as written. The test `generated_sections_are_fresh`
//! fails when a file's section is not what the code gives, so a new key or term is one edit in
//! the code and one run of the command.
//!
//! The generation runs inside that test, where hyq-env and hyq-spec are (dev-)dependencies:
//! `cargo xtask codegen` runs it with `HYQ_CODEGEN=write`, which writes the stale sections
//! instead of failing, and `--check` runs it as it is. So the `xtask` binary, which CI builds
//! first, does not compile the environment (rust-analyzer's code generation runs the same way).

/// The environment variable that makes `generated_sections_are_fresh` write the stale sections.
const WRITE_VAR: &str = "HYQ_CODEGEN";

/// `cargo xtask codegen [--check]`: runs `generated_sections_are_fresh`, writing the stale
/// sections (or, with `--check`, failing on them).
pub fn codegen(args: &[String]) -> Result<(), String> {
    let check = match args {
        [] => false,
        [flag] if flag == "--check" => true,
        _ => return Err("usage: cargo xtask codegen [--check]".into()),
    };
    let root = crate::workspace::workspace_root();
    let mut command = crate::workspace::cargo(&root);
    command.args([
        "test",
        "--quiet",
        "-p",
        "xtask",
        "--bin",
        "xtask",
        "--",
        "--exact",
        "--nocapture",
        "codegen::tests::generated_sections_are_fresh",
    ]);
    if !check {
        command.env(WRITE_VAR, "write");
    }
    let status = command
        .status()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if status.success() {
        Ok(())
    } else if check {
        Err("generated sections are stale: run `cargo xtask codegen`".into())
    } else {
        Err(format!("the generation failed ({status})"))
    }
}

#[cfg(test)]
mod generate {
    use std::path::Path;

    use hyq_env::{EnvConfig, INFO_KEYS, InfoKey, InfoValue, RANDOMIZE_INFO_KEYS, RECORD_KEYS};
    use hyq_spec::{REWARD_TERMS, TermKind};

    /// One generated section: the file (from the repository root), the section's name, and what
    /// it holds.
    struct Section {
        file: &'static str,
        name: &'static str,
        render: fn() -> String,
    }

    /// Every generated section.
    const SECTIONS: [Section; 10] = [
        Section {
            file: "README.md",
            name: "config-keys",
            render: config_keys,
        },
        Section {
            file: "README.md",
            name: "info-table",
            render: info_table,
        },
        Section {
            file: "README.md",
            name: "randomize-info-table",
            render: randomize_info_table,
        },
        Section {
            file: "README.md",
            name: "record-table",
            render: record_table,
        },
        Section {
            file: "crates/hyq-cli/README.md",
            name: "record-table",
            render: record_table,
        },
        Section {
            file: "crates/hyq-cli/README.md",
            name: "config-tables",
            render: config_tables,
        },
        Section {
            file: "crates/hyq-py/README.md",
            name: "term-names",
            render: term_names,
        },
        Section {
            file: "docs/robustness.md",
            name: "randomize-info-table",
            render: randomize_info_table,
        },
        Section {
            file: "crates/hyq-spec/README.md",
            name: "term-table",
            render: term_table,
        },
        Section {
            file: "crates/hyq-engines/README.md",
            name: "engine-table",
            render: engine_table,
        },
    ];

    /// The robot the documents describe (the spec's HyQ): its observation length and joint count.
    fn documented_robot() -> (usize, usize) {
        let hyq = hyq_spec::RobotDescription::hyq_spec();
        (hyq_spec::SPEC_TABLE.len(), hyq.joint_ranges().len())
    }

    /// The documented robot's body count (the bundled HyQ's links).
    fn documented_links() -> usize {
        hyq_physics::bundled::hyq().num_links()
    }

    /// `names` as a list of code spans: `` `a`, `b` ``.
    fn spans<'a>(names: impl IntoIterator<Item = &'a str>) -> String {
        names
            .into_iter()
            .map(|n| format!("`{n}`"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The reward terms' names, the opt-in ones said to be so: `` `r_b`, …, `fall_penalty` (`m_height`
    /// when configured) ``.
    pub(super) fn term_names() -> String {
        let always = REWARD_TERMS.iter().filter(|t| t.opt_in.is_none());
        let opt_in: Vec<&str> = REWARD_TERMS
            .iter()
            .filter(|t| t.opt_in.is_some())
            .map(|t| t.name)
            .collect();
        let mut text = spans(always.map(|t| t.name));
        if !opt_in.is_empty() {
            text.push_str(&format!(" ({} when configured)", spans(opt_in)));
        }
        text
    }

    /// hyq-spec's crate README table: a row per reward term, in the table's order.
    fn term_table() -> String {
        let mut out = String::from(
            "| term | kind | spec | sum over an episode | reported |\n|---|---|---|---|---|\n",
        );
        for t in &REWARD_TERMS {
            let kind = match t.kind {
                TermKind::Reward => "reward",
                TermKind::Multiplier => "multiplier",
                TermKind::Penalty => "penalty",
            };
            let sum = t.sum_name.map_or("", |s| s);
            let reported = if t.opt_in.is_some() {
                "when configured"
            } else {
                "always"
            };
            out.push_str(&format!(
                "| `{}` | {kind} | {} | {sum} | {reported} |\n",
                t.name, t.section
            ));
        }
        out
    }

    /// hyq-engines' crate README table: a row per engine of `ENGINES`.
    fn engine_table() -> String {
        let mut out = String::from(
            "| name | engine | crate | cargo feature | needs (install) |\n|---|---|---|---|---|\n",
        );
        for e in &hyq_engines::ENGINES {
            let feature = e
                .feature
                .map_or("none (always built)".to_owned(), |f| format!("`{f}`"));
            let needs = e.needs.map_or("nothing".to_owned(), |n| {
                format!("{} (`{}`)", n.what, n.install)
            });
            out.push_str(&format!(
                "| `{}` | {} | `{}` | {feature} | {needs} |\n",
                e.name, e.summary, e.crate_name
            ));
        }
        out
    }

    /// A Markdown table with the header `key | type | meaning`.
    fn table(rows: &[(String, String, String)]) -> String {
        let mut out = String::from("| key | type | meaning |\n|---|---|---|\n");
        for (key, kind, meaning) in rows {
            out.push_str(&format!("| {key} | {kind} | {meaning} |\n"));
        }
        out
    }

    /// The info table: a row per key, the reward terms a row per kind, the end reasons one row.
    pub(super) fn info_table() -> String {
        info_rows(&INFO_KEYS)
    }

    /// The table of the keys `[randomize]` adds to the info, a row per key.
    pub(super) fn randomize_info_table() -> String {
        info_rows(&RANDOMIZE_INFO_KEYS)
    }

    /// The table of `keys`, as [`info_table`] describes it.
    fn info_rows(keys: &[InfoKey]) -> String {
        let (_, joints) = documented_robot();
        let links = documented_links();
        let mut rows = Vec::new();
        for key in keys {
            let kind = key.kind(joints, links);
            match key.value {
                InfoValue::Terms => {
                    for term_kind in TermKind::ALL {
                        let names = REWARD_TERMS.iter().filter(|t| t.kind == term_kind);
                        let meaning = term_kind.meaning().to_owned();
                        rows.push((spans(names.map(|t| t.name)), kind.clone(), meaning));
                    }
                }
                _ => rows.push((spans(key.names()), kind, key.meaning.to_owned())),
            }
        }
        table(&rows)
    }

    /// The step record table, written for the documented robot.
    pub(super) fn record_table() -> String {
        let (obs, joints) = documented_robot();
        let fill = |text: &str| {
            text.replace("{obs}", &obs.to_string())
                .replace("{joints}", &joints.to_string())
                .replace("{terms}", &term_names())
                .replace("{randomize}", &randomize_names())
                .replace("{regularizers}", &regularizer_names())
                .replace(
                    "{velocity}",
                    &spans(hyq_env::velocity::TERM_NAMES.iter().copied()),
                )
        };
        let rows: Vec<_> = RECORD_KEYS
            .iter()
            .map(|k| {
                let when = if k.optional {
                    " (written only when set)"
                } else {
                    ""
                };
                (
                    format!("`{}`", k.name),
                    fill(k.kind),
                    fill(k.meaning) + when,
                )
            })
            .collect();
        table(&rows)
    }

    /// The names the record writes under `randomize`: the info's `randomize.` keys without their
    /// prefix.
    fn randomize_names() -> String {
        let prefix = hyq_env::randomize::RANDOMIZE_PREFIX;
        spans(
            RANDOMIZE_INFO_KEYS
                .iter()
                .map(|k| k.name.strip_prefix(prefix).unwrap_or(k.name)),
        )
    }

    /// The names the record writes under `regularizers`: the info's `regularizers.` term keys
    /// without their prefix.
    fn regularizer_names() -> String {
        let prefix = hyq_env::regularizers::REGULARIZER_PREFIX;
        spans(
            hyq_env::REGULARIZER_INFO_KEYS[1..]
                .iter()
                .map(|k| k.name.strip_prefix(prefix).unwrap_or(k.name)),
        )
    }

    /// The keys of `[task]` (hyq-spec's `TaskConfig`), in the order a written configuration holds
    /// them.
    fn task_keys() -> Vec<String> {
        let written = toml::to_string(&hyq_spec::TaskConfig::default()).unwrap_or_default();
        written
            .lines()
            .filter_map(|line| line.split_once(" = ").map(|(key, _)| key.to_owned()))
            .collect()
    }

    /// The configuration's tables as `` `[name]` `` spans.
    fn table_spans() -> Vec<String> {
        EnvConfig::TABLES
            .iter()
            .map(|t| format!("`[{t}]`"))
            .collect()
    }

    /// The README's sentence on the configuration's keys and tables.
    fn config_keys() -> String {
        let keys: Vec<String> = task_keys().iter().map(|k| format!("`{k}`")).collect();
        let others = &table_spans()[1..];
        format!(
            "the spec's user variables keep their spec names in `[task]` ({}), beside {}",
            keys.join(", "),
            and_list(others)
        )
    }

    /// `items` as prose lists them: `a, b and c`.
    fn and_list(items: &[String]) -> String {
        match items.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
            _ => items.join(""),
        }
    }

    /// The command README's list of the configuration's tables.
    fn config_tables() -> String {
        table_spans().join(", ")
    }

    /// `text` with every section of `file` replaced by what the code gives; an error names a
    /// section whose markers are missing.
    pub(super) fn regenerate(file: &str, text: &str) -> Result<String, String> {
        let mut out = text.to_owned();
        for section in SECTIONS.iter().filter(|s| s.file == file) {
            let open = format!("<!-- codegen:{} -->", section.name);
            let close = format!("<!-- end codegen:{} -->", section.name);
            let start = out
                .find(&open)
                .ok_or_else(|| format!("{file} has no `{open}` marker"))?
                + open.len();
            let end = out[start..]
                .find(&close)
                .ok_or_else(|| format!("{file} has no `{close}` after `{open}`"))?
                + start;
            let body = (section.render)();
            // A block (a table) sits on lines of its own between the markers; a span, inline.
            let body = if body.ends_with('\n') {
                format!("\n{body}")
            } else {
                body
            };
            out.replace_range(start..end, &body);
        }
        Ok(out)
    }

    /// The files with generated sections.
    fn files() -> Vec<&'static str> {
        let mut files: Vec<&str> = SECTIONS.iter().map(|s| s.file).collect();
        files.dedup();
        files
    }

    /// The files whose sections differ from what the code gives, with their new text.
    pub(super) fn stale(root: &Path) -> Result<Vec<(&'static str, String)>, String> {
        let mut out = Vec::new();
        for file in files() {
            let path = root.join(file);
            let text = std::fs::read_to_string(&path)
                .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
            let fresh = regenerate(file, &text)?;
            if fresh != text {
                out.push((file, fresh));
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::generate::{
        info_table, randomize_info_table, record_table, regenerate, stale, term_names,
    };
    use super::*;
    use hyq_env::{INFO_KEYS, RANDOMIZE_INFO_KEYS, RECORD_KEYS};

    /// Every generated section is what the code gives: a key, term or table added in the code
    /// and not yet written into the documents fails here, naming the file. With
    /// `HYQ_CODEGEN=write` (`cargo xtask codegen`), it writes them instead.
    #[test]
    fn generated_sections_are_fresh() {
        let root = crate::workspace::workspace_root();
        let stale = stale(&root).unwrap_or_else(|e| panic!("{e}"));
        if std::env::var(WRITE_VAR).as_deref() == Ok("write") {
            for (file, text) in &stale {
                std::fs::write(root.join(file), text)
                    .unwrap_or_else(|e| panic!("cannot write {file}: {e}"));
                println!("wrote {file}");
            }
            return;
        }
        let names: Vec<&str> = stale.iter().map(|(f, _)| *f).collect();
        assert!(
            names.is_empty(),
            "stale generated sections in {names:?}: run `cargo xtask codegen`"
        );
    }

    #[test]
    fn a_section_is_replaced_between_its_markers_only() {
        let text = "a <!-- codegen:term-names -->old<!-- end codegen:term-names --> b";
        let fresh = regenerate("crates/hyq-py/README.md", text).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            fresh,
            format!(
                "a <!-- codegen:term-names -->{}<!-- end codegen:term-names --> b",
                term_names()
            )
        );
        assert!(fresh.contains("`r_b`") && fresh.contains("`m_height` when configured"));
        let err = regenerate("crates/hyq-py/README.md", "no markers").expect_err("refused");
        assert!(err.contains("codegen:term-names"), "{err}");
    }

    #[test]
    fn every_info_key_and_record_key_is_in_its_table() {
        let info = info_table();
        for key in &INFO_KEYS {
            for name in key.names() {
                assert!(info.contains(&format!("`{name}`")), "{name}");
            }
        }
        let randomize = randomize_info_table();
        for key in &RANDOMIZE_INFO_KEYS {
            assert!(
                randomize.contains(&format!("| `{}` |", key.name)),
                "{}",
                key.name
            );
            let name = key.name.strip_prefix("randomize.").unwrap_or(key.name);
            assert!(record_table().contains(&format!("`{name}`")), "{name}");
        }
        let record = record_table();
        for key in &RECORD_KEYS {
            assert!(
                record.contains(&format!("| `{}` |", key.name)),
                "{}",
                key.name
            );
        }
        assert!(!record.contains('{'), "a placeholder left: {record}");
    }
}
