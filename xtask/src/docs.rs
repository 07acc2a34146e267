//! Checks that the project's documents stay true to the code: every workspace member has its
//! heading in ARCHITECTURE.md's code map, CI runs the test command the README gives, and the
//! README's observation table is hyq-spec's `SPEC_TABLE` row for row.

#[cfg(test)]
mod tests {
    use crate::stages::{workspace_members, workspace_root};

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
}
