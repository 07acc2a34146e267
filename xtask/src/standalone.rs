//! The repository stands alone: a clone into any directory, with nothing beside it, holds every
//! rule its text cites and every file its code and docs point to. Two checks run over every text
//! file git tracks or would track (untracked files that are not ignored count too), except under
//! a `vendor/` directory:
//!
//! 1. **Section citations.** `§` followed by a number (`§4.3`, `§6`, `§5.1.2`) cites
//!    `docs/spec.md`, and the number must be one of that page's headings
//!    (`## §4.3 Exponential reward r_e`). `§` is kept for that page: right after the name of
//!    another document (an all-capitals word such as `RULINGS` or `README`, or `Apache`,
//!    `License`, `notes`) it is an error, as is `§ 4` with a space. Other documents' sections are
//!    cited in words ("section 4(b) of the Apache License").
//! 2. **Nothing outside the repository.** No `../shared` and no path starting `shared/` (a
//!    directory beside the repository, which a clone does not have); no `RULINGS` and no
//!    `000_fed6b28d2b6c7065` (the ruling page and the original spec's text file, whose content
//!    is `docs/spec.md`); and no absolute path (`/work/...`, `/home/...`, `/tmp/...`), except
//!    the system locations in [`SYSTEM_PATHS`] and the file-by-file [`EXCEPTIONS`], each with
//!    its reason.
//!
//! This file has to spell what it forbids, so it is the one file both checks skip. Each check
//! reports every offending `file:line` at once, with what to do about it.

use std::collections::BTreeSet;
use std::fmt;
use std::path::Path;
use std::process::Command;

use crate::workspace::workspace_root;

/// The page `§` citations resolve against.
const SPEC_PAGE: &str = "docs/spec.md";

/// This file, skipped by both checks (it spells the patterns it forbids).
const THIS_FILE: &str = "xtask/src/standalone.rs";

/// Words right before `§` that name another document, compared case-insensitively (all-capitals
/// words count as document names too, see [`names_another_document`]).
const OTHER_DOCUMENTS: [&str; 5] = ["notes", "apache", "license", "licence", "rulings"];

/// Absolute paths every machine has, allowed in any file: (prefix, why).
const SYSTEM_PATHS: [(&str, &str); 10] = [
    ("/dev/", "device files such as /dev/null"),
    ("/proc/", "Linux's process and CPU information"),
    ("/sys/", "Linux's kernel information"),
    ("/etc/", "system configuration"),
    ("/bin/", "system programs"),
    ("/usr/bin/", "system programs, e.g. `#!/usr/bin/env`"),
    (
        "/usr/include/",
        "system headers: Debian's DART, Eigen and Bullet, which the DART backend builds against",
    ),
    (
        "/usr/share/",
        "system data, e.g. the DejaVu fonts the bundled font subset was made from",
    ),
    ("/usr/lib/", "system libraries"),
    (
        "/nonexistent",
        "a path that exists on no machine, for tests of missing-file errors",
    ),
];

/// Findings allowed in one file: (file, the finding's text starts with, why).
const EXCEPTIONS: [(&str, &str, &str); 1] = [(
    ".gitignore",
    "/",
    "git patterns anchored at the repository root, not machine paths",
)];

/// A text file of the repository: its path from the root (with `/`) and its content.
struct TextFile {
    path: String,
    text: String,
}

/// Every text file git tracks or would track under `root` (not ignored), outside `vendor/`
/// directories and except this file. Binary files (a NUL byte, or not UTF-8) and files deleted
/// from the work tree are left out.
fn repository_text_files(root: &Path) -> Vec<TextFile> {
    let output = Command::new("git")
        .args([
            "ls-files",
            "-z",
            "--cached",
            "--others",
            "--exclude-standard",
        ])
        .current_dir(root)
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "cannot run `git ls-files` in {}: {e}; this check reads the files of a git \
                 checkout",
                root.display()
            )
        });
    assert!(
        output.status.success(),
        "`git ls-files` failed in {}: {}",
        root.display(),
        String::from_utf8_lossy(&output.stderr).trim()
    );
    let paths: BTreeSet<String> = output
        .stdout
        .split(|b| *b == 0)
        .filter(|p| !p.is_empty())
        .map(|p| String::from_utf8_lossy(p).into_owned())
        .collect();
    paths
        .into_iter()
        .filter(|path| path != THIS_FILE && !path.split('/').any(|c| c == "vendor"))
        .filter_map(|path| {
            let bytes = std::fs::read(root.join(&path)).ok()?;
            if bytes.contains(&0) {
                return None;
            }
            let text = String::from_utf8(bytes).ok()?;
            Some(TextFile { path, text })
        })
        .collect()
}

/// One offending place: `file:line: message`.
#[derive(Debug, PartialEq)]
struct Finding {
    file: String,
    line: usize,
    message: String,
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.file, self.line, self.message)
    }
}

/// The longest prefix of `s` of the form `N`, `N.N`, `N.N.N`…: a section number.
fn section_number(s: &str) -> &str {
    let bytes = s.as_bytes();
    let (mut end, mut i) = (0, 0);
    loop {
        let start = i;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            i += 1;
        }
        if i == start {
            return &s[..end];
        }
        end = i;
        if bytes.get(i) == Some(&b'.') {
            i += 1;
        } else {
            return &s[..end];
        }
    }
}

/// The section numbers of `page`'s headings that start with `§` (`## §4.3 Exponential ...`).
fn spec_headings(page: &str) -> BTreeSet<String> {
    page.lines()
        .filter_map(|line| {
            let title = line.strip_prefix('#')?.trim_start_matches('#');
            let rest = title.trim_start().strip_prefix('§')?;
            let number = section_number(rest);
            let after = &rest[number.len()..];
            (!number.is_empty() && (after.is_empty() || after.starts_with(' ')))
                .then(|| number.to_string())
        })
        .collect()
}

/// A `§` citation in a line: the section number, whether a space separates it from `§`, and
/// the word right before the `§`.
#[derive(Debug, PartialEq)]
struct Citation<'a> {
    number: &'a str,
    spaced: bool,
    after_word: &'a str,
}

/// The word that ends `s`, after skipping spaces: letters, digits, `_`, `-` and `.`.
fn last_word(s: &str) -> &str {
    let s = s.trim_end_matches([' ', '\t', '\u{a0}']);
    let start = s
        .char_indices()
        .rev()
        .find(|(_, c)| !(c.is_alphanumeric() || matches!(c, '_' | '-' | '.')))
        .map_or(0, |(i, c)| i + c.len_utf8());
    &s[start..]
}

/// Every `§` followed by a number (or by one space and a number) in `line`.
fn citations(line: &str) -> Vec<Citation<'_>> {
    line.match_indices('§')
        .filter_map(|(i, sign)| {
            let rest = &line[i + sign.len()..];
            let (spaced, digits) = match rest.strip_prefix(' ') {
                Some(after) if after.starts_with(|c: char| c.is_ascii_digit()) => (true, after),
                _ => (false, rest),
            };
            let number = section_number(digits);
            (!number.is_empty()).then(|| Citation {
                number,
                spaced,
                after_word: last_word(&line[..i]),
            })
        })
        .collect()
}

/// Whether `word` names a document other than the spec page: an all-capitals word of two or
/// more letters (a file stem such as `README`, with or without `.md`), or one of
/// [`OTHER_DOCUMENTS`].
fn names_another_document(word: &str) -> bool {
    let mut stem = word.trim_end_matches('.');
    for extension in [".md", ".txt", ".pdf"] {
        stem = stem.strip_suffix(extension).unwrap_or(stem);
    }
    let letters: Vec<char> = stem.chars().filter(|c| c.is_alphabetic()).collect();
    (letters.len() >= 2 && letters.iter().all(|c| c.is_uppercase()))
        || OTHER_DOCUMENTS
            .iter()
            .any(|name| stem.eq_ignore_ascii_case(name))
}

/// The `§` citations of `file` that do not resolve to one of `headings`.
fn unresolved_citations(file: &TextFile, headings: &BTreeSet<String>) -> Vec<Finding> {
    let mut findings = Vec::new();
    for (index, line) in file.text.lines().enumerate() {
        for c in citations(line) {
            let message = if names_another_document(c.after_word) {
                format!(
                    "`{} §{}`: `§` and a number cite {SPEC_PAGE}, not {}. Cite the rule by its \
                     section of {SPEC_PAGE} (`spec §{}` if that is the rule meant), and another \
                     document's sections in words (`section 4 of ...`)",
                    c.after_word, c.number, c.after_word, c.number
                )
            } else if c.spaced {
                format!(
                    "`§ {}`: write `§{}`, without the space, so that the citation can be checked",
                    c.number, c.number
                )
            } else if !headings.contains(c.number) {
                format!(
                    "`§{}` is not a heading of {SPEC_PAGE}: cite one of its sections (listed \
                     below), or add a `## §{} <title>` heading there if the page should have one",
                    c.number, c.number
                )
            } else {
                continue;
            };
            findings.push(Finding {
                file: file.path.clone(),
                line: index + 1,
                message,
            });
        }
    }
    findings
}

/// What a place outside the repository looks like, and what to do instead.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Outside {
    /// `../shared`, or a path starting `shared/`.
    Beside,
    /// The ruling page's name.
    Rulings,
    /// The original spec's text file's name.
    SpecText,
    /// An absolute path.
    Absolute,
}

impl Outside {
    fn advice(self) -> &'static str {
        match self {
            Outside::Beside => {
                "points beside the repository, which a clone does not have: put what it needs \
                 inside the repository and refer to it by its repository path"
            }
            Outside::Rulings => {
                "names a ruling page that is not in the repository: cite the ruling's section of \
                 docs/spec.md instead (e.g. `spec §4.3`), where every ruling is stated"
            }
            Outside::SpecText => {
                "names the original spec's text file, which is not in the repository: cite \
                 docs/spec.md (e.g. `spec §6.2`)"
            }
            Outside::Absolute => {
                "is an absolute path of one machine: use a path relative to the repository \
                 root, `target/`, or a temporary directory made at run time \
                 (`std::env::temp_dir()`, pytest's `tmp_path`). A system location every machine \
                 has goes in SYSTEM_PATHS, and a case that must stay goes in EXCEPTIONS (file, \
                 path, reason), both in xtask/src/standalone.rs"
            }
        }
    }
}

/// Whether the character before a path (if any) lets the path start there: the start of the
/// line, a space, a quote, an opening bracket, `=`, `,`, `:` or a shell redirection `>`.
fn starts_a_path(before: Option<char>) -> bool {
    before.is_none_or(|c| c.is_whitespace() || "\"'`([{=,:>".contains(c))
}

/// The path-like token starting at the beginning of `s`, without trailing sentence punctuation.
fn token(s: &str) -> &str {
    let end = s
        .find(|c: char| c.is_whitespace() || "\"'`()[]{}<>,;|*".contains(c))
        .unwrap_or(s.len());
    s[..end].trim_end_matches(['.', ':'])
}

/// Whether `text` occurs in `line` at `i` as a whole word (no letter, digit or `_` around it).
fn whole_word(line: &str, i: usize, text: &str) -> bool {
    let word = |c: char| c.is_alphanumeric() || c == '_';
    !line[..i].chars().next_back().is_some_and(word)
        && !line[i + text.len()..].chars().next().is_some_and(word)
}

/// Every place in `line` that refers outside the repository, with its text, before the system
/// paths and exceptions are applied.
fn outside_references(line: &str) -> Vec<(Outside, &str)> {
    let mut found = Vec::new();
    for (i, _) in line.match_indices("../shared") {
        found.push((Outside::Beside, token(&line[i..])));
    }
    for (i, _) in line.match_indices("shared/") {
        if starts_a_path(line[..i].chars().next_back()) {
            found.push((Outside::Beside, token(&line[i..])));
        }
    }
    for (i, text) in line.match_indices("RULINGS") {
        if whole_word(line, i, text) {
            found.push((Outside::Rulings, text));
        }
    }
    for (_, text) in line.match_indices("000_fed6b28d2b6c7065") {
        found.push((Outside::SpecText, text));
    }
    for (i, _) in line.match_indices('/') {
        let next = line[i + 1..].chars().next();
        if starts_a_path(line[..i].chars().next_back())
            && next.is_some_and(|c| c.is_ascii_alphabetic() || c == '_' || c == '.')
        {
            found.push((Outside::Absolute, token(&line[i..])));
        }
    }
    found
}

/// Whether an absolute `path` is a system location of [`SYSTEM_PATHS`].
fn is_system_path(path: &str) -> bool {
    SYSTEM_PATHS
        .iter()
        .any(|(prefix, _)| path.starts_with(prefix) || Some(path) == prefix.strip_suffix('/'))
}

/// Whether [`EXCEPTIONS`] allows `text` in `file`.
fn is_excepted(file: &str, text: &str) -> bool {
    EXCEPTIONS
        .iter()
        .any(|(f, prefix, _)| *f == file && text.starts_with(prefix))
}

/// The references of `file` to places outside the repository.
fn outside_findings(file: &TextFile) -> Vec<Finding> {
    let mut findings = Vec::new();
    for (index, line) in file.text.lines().enumerate() {
        for (kind, text) in outside_references(line) {
            if (kind == Outside::Absolute && is_system_path(text)) || is_excepted(&file.path, text)
            {
                continue;
            }
            findings.push(Finding {
                file: file.path.clone(),
                line: index + 1,
                message: format!("`{text}` {}", kind.advice()),
            });
        }
    }
    findings
}

fn file(path: &str, text: &str) -> TextFile {
    TextFile {
        path: path.into(),
        text: text.into(),
    }
}

#[test]
fn every_section_citation_names_a_heading_of_the_spec_page() {
    let root = workspace_root();
    let page = std::fs::read_to_string(root.join(SPEC_PAGE))
        .unwrap_or_else(|e| panic!("cannot read {SPEC_PAGE}: {e}"));
    let headings = spec_headings(&page);
    assert!(
        headings.len() >= 20,
        "{SPEC_PAGE} has only {} `## §N` headings: has its heading format changed?",
        headings.len()
    );
    let files = repository_text_files(&root);
    let cited: usize = files
        .iter()
        .map(|f| f.text.lines().map(|l| citations(l).len()).sum::<usize>())
        .sum();
    assert!(
        cited >= 100,
        "only {cited} `§` citations found in {} files: is the file list right?",
        files.len()
    );
    let findings: Vec<String> = files
        .iter()
        .flat_map(|f| unresolved_citations(f, &headings))
        .map(|f| f.to_string())
        .collect();
    let sections: Vec<String> = headings.iter().map(|h| format!("§{h}")).collect();
    assert!(
        findings.is_empty(),
        "{} `§` citation(s) do not resolve to a heading of {SPEC_PAGE}:\n{}\n\nThe sections of \
         {SPEC_PAGE}: {}",
        findings.len(),
        findings.join("\n"),
        sections.join(", ")
    );
}

#[test]
fn nothing_refers_outside_the_repository() {
    let root = workspace_root();
    let files = repository_text_files(&root);
    assert!(
        files.iter().any(|f| f.path == "Cargo.toml") && files.len() >= 100,
        "only {} text files listed: is the file list right?",
        files.len()
    );
    let findings: Vec<String> = files
        .iter()
        .flat_map(outside_findings)
        .map(|f| f.to_string())
        .collect();
    assert!(
        findings.is_empty(),
        "{} reference(s) outside the repository (a clone stands alone):\n{}",
        findings.len(),
        findings.join("\n")
    );
}

#[test]
fn section_numbers_and_citations_parse_as_written() {
    assert_eq!(section_number("4.3 Exponential"), "4.3");
    assert_eq!(section_number("5.1.2."), "5.1.2");
    assert_eq!(section_number("6, and"), "6");
    assert_eq!(section_number("x"), "");
    let line = "r (spec §4–§5, RULINGS §3) and eq. (1), §6.1–§6.4; see § 2 or §x.";
    let found: Vec<(&str, bool, &str)> = citations(line)
        .iter()
        .map(|c| (c.number, c.spaced, c.after_word))
        .collect();
    assert_eq!(
        found,
        [
            ("4", false, "spec"),
            ("5", false, ""),
            ("3", false, "RULINGS"),
            ("6.1", false, ""),
            ("6.4", false, ""),
            ("2", true, "see"),
        ]
    );
    let headings = spec_headings(
        "# Title\n## §4.3 Exponential reward r_e\n### §6 Termination\n##§7\n## §8x no\nText §9\n",
    );
    assert_eq!(headings.into_iter().collect::<Vec<_>>(), ["4.3", "6", "7"]);
}

#[test]
fn a_citation_that_does_not_resolve_is_named_with_its_file_line_and_fix() {
    let headings: BTreeSet<String> = ["4", "4.3", "6.2"].map(String::from).into();
    let text = "//! Spec §4.3 (the spec's §6.2)\n\
                //! see §4.4 and § 4\n\
                //! as RULINGS §4.3 and README.md §4 say, Apache §4(b), notes §4\n\
                //! the 2nd NOTE: §4 of PDF §4.3 holds\n";
    let findings = unresolved_citations(&file("crates/x/src/lib.rs", text), &headings);
    let places: Vec<(usize, &str)> = findings
        .iter()
        .map(|f| (f.line, f.message.split(':').next().unwrap_or_default()))
        .collect();
    assert_eq!(
        places,
        [
            (2, "`§4.4` is not a heading of docs/spec.md"),
            (2, "`§ 4`"),
            (3, "`RULINGS §4.3`"),
            (3, "`README.md §4`"),
            (3, "`Apache §4`"),
            (3, "`notes §4`"),
            (4, "`PDF §4.3`"),
        ]
    );
    assert_eq!(
        findings[0].to_string(),
        "crates/x/src/lib.rs:2: `§4.4` is not a heading of docs/spec.md: cite one of its \
         sections (listed below), or add a `## §4.4 <title>` heading there if the page should \
         have one"
    );
    assert!(
        findings[2].message.contains("`spec §4.3`"),
        "{}",
        findings[2]
    );
}

#[test]
fn places_outside_the_repository_are_found_and_system_paths_are_not() {
    let text = "see ../shared/spec/x.txt and `shared/bench/anchors/a.py` (not a/shared/b)\n\
                as RULINGS §3 says; RULINGSX is no word; 000_fed6b28d2b6c7065.txt\n\
                venv \"/tmp/anchor-venv\", --out /work/main/x, (/home/me/y), =/root/z.\n\
                /dev/null 2>/dev/null /proc/cpuinfo /usr/include/dart /nonexistent-dir/x\n\
                https://example.org/tmp/x a/tmp/b 1/2 x / y </robot> ~/cache $HOME/x\n";
    let findings = outside_findings(&file("docs/x.md", text));
    let found: Vec<(usize, String)> = findings
        .iter()
        .map(|f| {
            let quoted = f.message.split('`').nth(1).unwrap_or_default();
            (f.line, quoted.to_string())
        })
        .collect();
    let expected = [
        (1, "../shared/spec/x.txt"),
        (1, "shared/bench/anchors/a.py"),
        (2, "RULINGS"),
        (2, "000_fed6b28d2b6c7065"),
        (3, "/tmp/anchor-venv"),
        (3, "/work/main/x"),
        (3, "/home/me/y"),
        (3, "/root/z"),
    ];
    assert_eq!(
        found,
        expected.map(|(l, t)| (l, t.to_string())),
        "{findings:#?}"
    );
    assert!(
        findings[4].message.contains("EXCEPTIONS"),
        "{}",
        findings[4]
    );
}

#[test]
fn exceptions_apply_to_their_file_only() {
    let patterns = "/target\n/out/\n";
    assert!(outside_findings(&file(".gitignore", patterns)).is_empty());
    assert_eq!(outside_findings(&file("docs/x.md", patterns)).len(), 2);
    // The anchor harness lives in the repository: its old outside locations are findings in
    // the code that once needed them.
    let line = "PathBuf::from(\"/tmp/anchor-venv\") or \"../shared/bench/anchors\"\n";
    for path in ["xtask/src/bench.rs", "xtask/src/main.rs"] {
        let found: Vec<String> = outside_findings(&file(path, line))
            .iter()
            .map(ToString::to_string)
            .collect();
        assert_eq!(found.len(), 2, "{path}: {found:?}");
    }
}
