//! Checks that the project's documents stay true to the code: every workspace member has its
//! heading in ARCHITECTURE.md's code map, and CI runs the test command the README gives.

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
}
