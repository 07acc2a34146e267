//! Reading the commands' arguments: what `soak` and `bench-vs-anchors` share.

/// The value after the flag `name` of `cargo xtask command`, or an error naming both.
pub fn value<'a>(
    it: &mut impl Iterator<Item = &'a String>,
    command: &str,
    name: &str,
) -> Result<&'a String, String> {
    it.next()
        .ok_or_else(|| format!("`cargo xtask {command} {name}` needs a value"))
}

/// The value after the flag `name` of `cargo xtask command` as a whole number > 0, or an error
/// naming the flag and the value.
pub fn positive<'a>(
    it: &mut impl Iterator<Item = &'a String>,
    command: &str,
    name: &str,
) -> Result<u64, String> {
    let v = value(it, command, name)?;
    v.parse::<u64>()
        .ok()
        .filter(|n| *n > 0)
        .ok_or_else(|| format!("`{name} {v}`: expected a whole number > 0"))
}

/// Owned copies of `items` (arguments for a command).
pub fn strings(items: &[&str]) -> Vec<String> {
    items.iter().map(|s| s.to_string()).collect()
}
