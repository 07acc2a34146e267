//! `TerrainKind::ALL` is the one list of the ground kinds that the ledger and `hyq compare
//! --terrain` read: it must hold every kind, each under the name the configuration accepts.

use hyq_env::{EnvConfig, TerrainKind};

#[test]
fn the_kind_list_holds_every_kind_once_under_its_configuration_name() {
    // Exhaustive on purpose: a new kind does not compile here until it is placed in the list.
    let position = |kind: TerrainKind| match kind {
        TerrainKind::Flat
        | TerrainKind::Rough
        | TerrainKind::Slope
        | TerrainKind::Stairs
        | TerrainKind::Heightfield => TerrainKind::ALL.iter().position(|k| *k == kind),
    };
    for (i, kind) in TerrainKind::ALL.into_iter().enumerate() {
        assert_eq!(position(kind), Some(i), "{kind:?} is listed twice");
        let text = format!("[terrain]\nkind = \"{}\"", kind.as_str());
        match EnvConfig::from_toml_str(&text, "test") {
            Ok(config) => assert_eq!(config.terrain.kind, kind),
            // A height file's kind is read, then refused for want of its file.
            Err(e) => assert!(
                !kind.is_generated() && e.to_string().contains("terrain.file"),
                "{:?} is not read back: {e}",
                kind.as_str()
            ),
        }
    }
}

#[test]
fn only_a_height_file_is_not_generated_from_the_table() {
    let generated: Vec<&str> = TerrainKind::ALL
        .into_iter()
        .filter(|k| k.is_generated())
        .map(TerrainKind::as_str)
        .collect();
    assert_eq!(generated, ["flat", "rough", "slope", "stairs"]);
}
