//! Checks that the project's documents stay true to the code: every workspace member has its
//! heading in ARCHITECTURE.md's code map, CI runs the test command the README gives, the
//! observation tables of the README and of docs/spec.md are hyq-spec's `SPEC_TABLE` row for row,
//! and docs/spec.md has a heading for every section of the original spec, marks its three
//! deviations, and names only tests that exist; that every crate root's module table names every
//! public module; that no front lists the engines itself, and that every install line is the
//! engine registry's.

#[cfg(test)]
mod tests {
    use crate::workspace::{workspace_members, workspace_root};

    fn read(name: &str) -> String {
        let path = workspace_root().join(name);
        std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
    }

    #[test]
    fn architecture_code_map_has_a_heading_for_every_workspace_member() {
        let architecture = read("ARCHITECTURE.md");
        let headings: Vec<&str> = architecture
            .lines()
            .filter(|l| l.starts_with("### "))
            .collect();
        let members = workspace_members(&workspace_root()).expect("workspace members");
        assert!(!members.is_empty());
        for member in members {
            assert!(
                headings.iter().any(|h| h.contains(&format!("`{member}`"))),
                "ARCHITECTURE.md's code map has no `### ... `{member}`` heading"
            );
        }
    }

    #[test]
    fn ci_runs_the_test_command_the_readme_gives() {
        let readme = read("README.md");
        let ci = read(".ci/run");
        let command = "cargo xtask test";
        assert!(
            readme.contains(command),
            "README.md does not give `{command}`"
        );
        assert!(
            ci.lines()
                .any(|l| !l.trim_start().starts_with('#') && l.contains(command)),
            ".ci/run does not run `{command}`"
        );
    }

    /// The README's env card rows `| i | `name` | min | max | unit |`, parsed.
    fn readme_observation_rows(readme: &str) -> Vec<(usize, String, f64, f64, bool)> {
        readme
            .lines()
            .filter_map(|line| {
                let cells: Vec<&str> = line.trim().strip_prefix('|')?.split('|').collect();
                if cells.len() != 6 {
                    return None;
                }
                let index = cells[0].trim().parse().ok()?;
                let name = cells[1].trim().strip_prefix('`')?.strip_suffix('`')?;
                let min = cells[2].trim().parse().ok()?;
                let max = cells[3].trim().parse().ok()?;
                let estimated = cells[4].contains("(estimated)");
                Some((index, name.to_string(), min, max, estimated))
            })
            .collect()
    }

    #[test]
    fn readme_observation_table_is_the_spec_table() {
        let rows = readme_observation_rows(&read("README.md"));
        let spec: Vec<(usize, String, f64, f64, bool)> = hyq_spec::SPEC_TABLE
            .iter()
            .map(|r| (r.index, r.name.to_string(), r.min, r.max, r.estimated))
            .collect();
        assert_eq!(
            rows, spec,
            "README.md's observation table differs from SPEC_TABLE"
        );
    }

    #[test]
    fn spec_page_observation_table_is_the_spec_table() {
        let rows = readme_observation_rows(&read("docs/spec.md"));
        let spec: Vec<(usize, String, f64, f64, bool)> = hyq_spec::SPEC_TABLE
            .iter()
            .map(|r| (r.index, r.name.to_string(), r.min, r.max, r.estimated))
            .collect();
        assert_eq!(
            rows, spec,
            "docs/spec.md's observation table differs from SPEC_TABLE"
        );
    }

    /// The text of the README's env card from `**{name}**` to the next bold paragraph heading.
    fn env_card_part<'a>(readme: &'a str, name: &str) -> &'a str {
        let start = readme
            .find(&format!("\n**{name}**"))
            .unwrap_or_else(|| panic!("README.md's env card has no **{name}** part"));
        let rest = &readme[start + 1..];
        let end = rest[2..].find("\n**").map_or(rest.len(), |i| i + 2);
        &rest[..end]
    }

    /// The names in the first cell of every table row of `text` (`| r_b, r_n | …` or
    /// `` | `r_b`, `r_n` | … ``).
    fn first_cell_names(text: &str) -> Vec<String> {
        text.lines()
            .filter_map(|l| l.trim().strip_prefix('|')?.split('|').next())
            .flat_map(|cell| cell.split(','))
            .map(|name| name.trim().trim_matches('`').to_owned())
            .collect()
    }

    #[test]
    fn readme_env_card_names_every_reward_term() {
        let readme = read("README.md");
        let reward = env_card_part(&readme, "Reward");
        let info = first_cell_names(env_card_part(&readme, "Info"));
        let record = env_card_part(&readme, "Step record");
        let terms_row = record
            .lines()
            .find(|l| l.starts_with("| `terms` |"))
            .expect("the step record table has a `terms` row");
        for term in &hyq_spec::REWARD_TERMS {
            let name = term.name;
            assert!(
                first_cell_names(reward).iter().any(|n| n == name),
                "README.md's reward table has no row for {name}"
            );
            assert!(
                reward
                    .lines()
                    .any(|l| l.starts_with("r = ") && l.contains(name)),
                "README.md's reward formula does not name {name}"
            );
            assert!(
                info.iter().any(|n| n == name),
                "README.md's info table has no {name}"
            );
            assert!(
                terms_row.contains(&format!("`{name}`")),
                "README.md's step record `terms` row does not name {name}"
            );
        }
    }

    /// The sections of the original spec, each of which docs/spec.md must have as a heading.
    const ORIGINAL_SECTIONS: [&str; 20] = [
        "1", "2", "3", "4", "4.1", "4.2", "4.3", "4.4", "5", "5.1", "5.1.1", "5.1.2", "5.2", "5.3",
        "5.4", "6", "6.1", "6.2", "6.3", "6.4",
    ];

    /// The sections whose printed formula the project changes.
    const DEVIATIONS: [&str; 3] = ["4.1", "4.3", "6.2"];

    /// The text of docs/spec.md from the heading of section `number` to the next `## ` heading.
    fn spec_section<'a>(page: &'a str, number: &str) -> &'a str {
        let heading = format!("\n## §{number} ");
        let start = page
            .find(&heading)
            .unwrap_or_else(|| panic!("docs/spec.md has no `## §{number} ...` heading"));
        let body = &page[start + 1..];
        let end = body[1..].find("\n## ").map_or(body.len(), |i| i + 1);
        &body[..end]
    }

    #[test]
    fn spec_page_has_a_heading_for_every_section_of_the_original() {
        let page = read("docs/spec.md");
        let missing: Vec<&str> = ORIGINAL_SECTIONS
            .into_iter()
            .filter(|s| !page.lines().any(|l| l.starts_with(&format!("## §{s} "))))
            .collect();
        assert!(
            missing.is_empty(),
            "docs/spec.md lacks a `## §N <title>` heading for the original's section(s) {missing:?}"
        );
    }

    #[test]
    fn spec_page_marks_exactly_the_three_deviations() {
        let page = read("docs/spec.md");
        for number in DEVIATIONS {
            assert!(
                spec_section(&page, number).contains("**Deviation.**"),
                "docs/spec.md's §{number} changes a printed formula but is not marked \
                 `**Deviation.**`"
            );
        }
        assert_eq!(
            page.matches("**Deviation.**").count(),
            DEVIATIONS.len(),
            "docs/spec.md marks `**Deviation.**` outside §4.1, §4.3 and §6.2"
        );
    }

    /// The backticked spans of `text`, in order.
    fn backticked(text: &str) -> Vec<&str> {
        text.split('`').skip(1).step_by(2).collect()
    }

    /// Whether the file at `path` (from the repository root) defines a function `name`, Rust or
    /// Python; panics naming the page's reference when the file is missing.
    fn check_test_exists(file: &str, name: &str) {
        let path = crate::workspace::workspace_root().join(file);
        let source = std::fs::read_to_string(&path).unwrap_or_else(|e| {
            panic!("docs/spec.md names `{file}::{name}`, but {file} cannot be read ({e}); paths are from the repository root")
        });
        let defined = [
            format!("fn {name}("),
            format!("fn {name}<"),
            format!("def {name}("),
        ]
        .iter()
        .any(|d| source.contains(d.as_str()));
        assert!(
            defined,
            "docs/spec.md names `{file}::{name}`, which {file} does not define"
        );
    }

    /// Checks the tests named by one run of backticked spans: a span naming a `.rs` or `.py`
    /// file sets the current file (and names a test after `::`); a later bare identifier names a
    /// test in the current file. Returns how many were checked.
    fn check_spans(spans: &[&str]) -> usize {
        let mut file: Option<&str> = None;
        let mut checked = 0;
        for span in spans {
            let source = [".rs", ".py"].iter().find_map(|ext| {
                span.find(ext)
                    .map(|i| (&span[..i + ext.len()], &span[i + ext.len()..]))
            });
            if let Some((f, rest)) = source {
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
    fn every_test_the_spec_page_names_exists() {
        let page = read("docs/spec.md");
        let mut checked = 0;
        for segment in page.split("**Shown by:**").skip(1) {
            let end = segment
                .find("\n- **")
                .into_iter()
                .chain(segment.find("\n#"))
                .min()
                .unwrap_or(segment.len());
            checked += check_spans(&backticked(&segment[..end]));
        }
        for line in page.lines().filter(|l| l.starts_with("| §")) {
            checked += check_spans(&backticked(line));
        }
        assert!(
            checked >= 100,
            "only {checked} test references found in docs/spec.md: has its format changed?"
        );
    }

    #[test]
    fn a_changed_bound_is_noticed() {
        let row = "| 12 | `lf_haa_speed` | -12.0 | 12.0 | rad/s |";
        let parsed = readme_observation_rows(row);
        assert_eq!(
            parsed,
            vec![(12, "lf_haa_speed".into(), -12.0, 12.0, false)]
        );
        let changed = readme_observation_rows(&row.replace("| 12.0 |", "| 13.0 |"));
        assert_ne!(parsed, changed);
    }

    /// The directories of the fronts, which reach the engines through hyq-engines alone.
    const FRONTS: [&str; 7] = [
        "crates/hyq-cli/src",
        "crates/hyq-py/src",
        "crates/hyq-py/python/hyq",
        "spec-tests/src",
        "crates/hyq-env/src",
        "crates/hyq-compare/src",
        "xtask/src",
    ];

    /// The files (or, ending in `/`, directories) of a front that name one engine by design, and
    /// why.
    const NAMES_AN_ENGINE: [(&str, &str); 3] = [
        (
            "crates/hyq-cli/src/model.rs",
            "the MJCF `hyq model` writes is MuJoCo's format, with the [physics.mujoco] options",
        ),
        (
            "xtask/src/mujoco.rs",
            "`cargo xtask setup mujoco` fetches that engine's library",
        ),
        (
            "xtask/src/bench/",
            "bench-vs-anchors measures chosen engines against the MuJoCo and DART anchors",
        ),
    ];

    /// The places in `text` (a Rust or Python source) where code names an engine: an engine's
    /// name as a string literal, or its backend crate. Comments, docstrings and the test module
    /// at the end of a Rust file (from its `#[cfg(test)]`) are left out.
    fn engine_mentions(text: &str, python: bool) -> Vec<String> {
        let mut tokens = Vec::new();
        for engine in &hyq_engines::ENGINES {
            tokens.push(format!("\"{}\"", engine.name));
            tokens.push(format!("'{}'", engine.name));
            tokens.push(engine.crate_name.replace('-', "_"));
        }
        let mut found = Vec::new();
        let mut in_docstring = false;
        for (i, line) in text.lines().enumerate() {
            let code = line.trim_start();
            if !python && code.starts_with("#[cfg(test)]") {
                break;
            }
            let quotes = code.matches("\"\"\"").count();
            let doc = in_docstring || quotes > 0;
            if quotes % 2 == 1 {
                in_docstring = !in_docstring;
            }
            let comment = if python {
                code.starts_with('#')
            } else {
                code.starts_with("//")
            };
            if doc || comment {
                continue;
            }
            for token in &tokens {
                if code.contains(token.as_str()) {
                    found.push(format!("line {}: {token}", i + 1));
                }
            }
        }
        found
    }

    /// Every `.rs` and `.py` file under `dir`.
    fn sources(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        let entries =
            std::fs::read_dir(dir).unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()));
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                sources(&path, out);
            } else if path.extension().is_some_and(|x| x == "rs" || x == "py") {
                out.push(path);
            }
        }
    }

    /// The fronts (the command, the Python package, spec-tests, the env's configuration, the
    /// comparison, xtask's stages) name no engine: they take the engines from hyq-engines' table
    /// and dispatch through its macros, so adding an engine edits none of them.
    #[test]
    fn no_front_lists_the_engines_itself() {
        let root = workspace_root();
        let mut offenders = Vec::new();
        let mut checked = 0;
        for front in FRONTS {
            let mut files = Vec::new();
            sources(&root.join(front), &mut files);
            for path in files {
                let relative = path.strip_prefix(&root).unwrap_or(&path);
                let name = relative.to_string_lossy();
                if NAMES_AN_ENGINE
                    .iter()
                    .any(|(file, _)| name.starts_with(file))
                {
                    continue;
                }
                let text = std::fs::read_to_string(&path).unwrap_or_default();
                let python = name.ends_with(".py");
                checked += 1;
                for mention in engine_mentions(&text, python) {
                    offenders.push(format!("{name} {mention}"));
                }
            }
        }
        assert!(
            checked > 50,
            "only {checked} source files found under the fronts"
        );
        assert!(
            offenders.is_empty(),
            "fronts that name an engine themselves (take it from hyq-engines instead): {offenders:#?}"
        );
    }

    #[test]
    fn an_engine_named_in_code_is_noticed() {
        let rust = "// \"dart\" in a comment\nmatch name {\n    \"dart\" => 1,\n}\n#[cfg(test)]\n\"mujoco\"";
        assert_eq!(engine_mentions(rust, false), ["line 3: \"dart\""]);
        let python =
            "\"\"\"Docs: backend=\"mujoco\".\n\"\"\"\n# 'dart'\nx = 'dart'\nimport hyq_mujoco\n";
        assert_eq!(
            engine_mentions(python, true),
            ["line 4: 'dart'", "line 5: hyq_mujoco"]
        );
    }

    /// The public modules a crate root declares (`pub mod name;`, `pub mod name {}`), in order.
    fn declared_modules(root: &str) -> Vec<&str> {
        root.lines()
            .filter_map(|line| line.strip_prefix("pub mod "))
            .filter_map(|rest| rest.split([';', ' ', '{']).next())
            .collect()
    }

    /// The modules a crate root's module table names: its rows `//! | [`name`] | ...` (a link
    /// target after the span, as in ``[`env`](mod@env)``, is left out).
    fn tabled_modules(root: &str) -> Vec<&str> {
        root.lines()
            .filter_map(|line| line.strip_prefix("//! | [`"))
            .filter_map(|rest| rest.split_once("`]").map(|(name, _)| name))
            .collect()
    }

    /// What a crate root's module table gets wrong: a public module it omits, a row naming no
    /// module. Empty for a root without a table.
    fn module_table_mismatches(root: &str) -> Vec<String> {
        let declared = declared_modules(root);
        let tabled = tabled_modules(root);
        if tabled.is_empty() {
            return Vec::new();
        }
        let omitted = declared.iter().filter(|m| !tabled.contains(m));
        let unknown = tabled.iter().filter(|m| !declared.contains(m));
        omitted
            .map(|m| format!("module `{m}` is not in the table"))
            .chain(unknown.map(|m| format!("the table names `{m}`, which is no module")))
            .collect()
    }

    /// A crate whose root documents its modules in a table (hyq-spec's sections, hyq-env's
    /// parts) lists every public module there, so that a new module is not left out of the map.
    #[test]
    fn every_module_table_names_every_module() {
        let root = workspace_root();
        let mut tables = 0;
        let mut problems = Vec::new();
        for dir in ["crates", "."] {
            let entries =
                std::fs::read_dir(root.join(dir)).unwrap_or_else(|e| panic!("{dir}: {e}"));
            for entry in entries.flatten() {
                let lib = entry.path().join("src").join("lib.rs");
                let Ok(text) = std::fs::read_to_string(&lib) else {
                    continue;
                };
                if !tabled_modules(&text).is_empty() {
                    tables += 1;
                }
                for problem in module_table_mismatches(&text) {
                    problems.push(format!("{}: {problem}", lib.display()));
                }
            }
        }
        assert!(tables >= 2, "only {tables} module tables found");
        assert!(problems.is_empty(), "{problems:#?}");
    }

    #[test]
    fn a_module_table_that_omits_a_module_is_noticed() {
        let root = "//! | [`env`](mod@env) | the env |\n//! | [`goal`] | goals |\n\
                    pub mod env;\npub mod goal;\npub mod info;\nmod private;\npub mod page {}\n";
        assert_eq!(
            module_table_mismatches(root),
            [
                "module `info` is not in the table",
                "module `page` is not in the table"
            ]
        );
        let extra = "//! | [`gone`] | gone |\npub mod here;\n//! | [`here`] | here |\n";
        assert_eq!(
            module_table_mismatches(extra),
            ["the table names `gone`, which is no module"]
        );
        assert!(module_table_mismatches("pub mod untabled;\n").is_empty());
    }

    /// Every file that tells users how to install an engine's library gives the line hyq-engines'
    /// table gives (hyq-dart's build script cannot read the table, which depends on it, and the
    /// documents are prose): the same packages wherever `apt-get install` names one of them.
    #[test]
    fn every_install_line_is_the_registrys() {
        let files = [
            "README.md",
            ".ci/run",
            "crates/hyq-cli/README.md",
            "crates/hyq-py/README.md",
            "crates/hyq-dart/README.md",
            "crates/hyq-dart/build.rs",
        ];
        let mut checked = 0;
        for engine in &hyq_engines::ENGINES {
            let Some(needs) = engine.needs else { continue };
            let Some((_, packages)) = needs.install.split_once("apt-get install -y ") else {
                continue;
            };
            let first = packages.split(' ').next().unwrap_or(packages);
            for file in files {
                for line in read(file).lines() {
                    if line.contains("apt-get install") && line.contains(first) {
                        checked += 1;
                        assert!(
                            line.contains(packages),
                            "{file}: `{line}` does not install `{packages}` ({})",
                            engine.name
                        );
                    }
                }
            }
        }
        assert!(checked >= files.len(), "only {checked} install lines found");
    }
}
