//! Empty: cargo resolves a package's build-dependencies only when it has a build script, and the
//! `[build-dependencies]` here set the features the proc macros are compiled with.

fn main() {}
