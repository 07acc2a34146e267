//! Puts the env card into the crate docs: the `## Env card` section of the workspace README
//! (which xtask keeps true against the code) is written to `env_card.md` in `OUT_DIR`, whose
//! path `HYQ_ENV_CARD` gives `lib.rs` to include, so the card is written once. Links to the
//! repository's files become their text, since they do not resolve from the crate docs.

use std::path::PathBuf;

const HEADING: &str = "\n## Env card\n";

fn main() {
    let manifest = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default());
    let readme = manifest.join("../../README.md");
    println!("cargo::rerun-if-changed={}", readme.display());
    let text = std::fs::read_to_string(&readme)
        .unwrap_or_else(|e| panic!("{}: {e} (the env card is its section)", readme.display()));
    let start = text
        .find(HEADING)
        .unwrap_or_else(|| panic!("{} has no `## Env card` section", readme.display()))
        + HEADING.len();
    let body = &text[start..];
    let card = &body[..body.find("\n## ").unwrap_or(body.len())];
    let out = PathBuf::from(std::env::var_os("OUT_DIR").unwrap_or_default()).join("env_card.md");
    std::fs::write(&out, format!("# Env card\n{}\n", unlink_relative(card)))
        .unwrap_or_else(|e| panic!("{}: {e}", out.display()));
    println!("cargo::rustc-env=HYQ_ENV_CARD={}", out.display());
}

/// `text` with every Markdown link to a relative path, `[label](path)`, replaced by its label.
fn unlink_relative(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(mid) = rest.find("](") {
        let open = rest[..mid].rfind('[');
        let close = rest[mid + 2..].find(')').map(|c| mid + 2 + c);
        match (open, close) {
            (Some(open), Some(close)) if !rest[mid + 2..close].contains("://") => {
                out.push_str(&rest[..open]);
                out.push_str(&rest[open + 1..mid]);
                rest = &rest[close + 1..];
            }
            _ => {
                out.push_str(&rest[..mid + 2]);
                rest = &rest[mid + 2..];
            }
        }
    }
    out.push_str(rest);
    out
}
