//! What the XML writers share: attribute escaping and the number form, so the MJCF and the URDF
//! text quote names and write numbers alike.

use std::fmt::Write as _;

/// Escapes text for an XML attribute value in double quotes.
pub(crate) fn attr(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// Numbers separated by spaces, each in Rust's shortest round-trip form, so a reader parses
/// back exactly the `f64` values written.
pub(crate) fn nums(values: &[f64]) -> String {
    let mut out = String::new();
    for (i, v) in values.iter().enumerate() {
        if i > 0 {
            out.push(' ');
        }
        // Writing to a String cannot fail.
        let _ = write!(out, "{v}");
    }
    out
}
