//! No items. Its dependency list sets features on crates the workspace already uses, so that every
//! cargo command builds them alike (see Cargo.toml).
