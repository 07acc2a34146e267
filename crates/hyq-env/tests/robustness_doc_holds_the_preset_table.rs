//! `docs/robustness.md` shows the presets' ranges and their sources exactly as the code holds
//! them (`hyq_env::randomize::PRESET_RANGES`), so the page cannot drift from the presets.

#[test]
fn the_page_holds_the_table_of_every_preset_range() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/robustness.md");
    let path = path.display();
    let page = std::fs::read_to_string(path.to_string()).unwrap_or_else(|e| panic!("{path}: {e}"));
    let table = hyq_env::randomize::preset_table();
    assert!(
        page.contains(&table),
        "docs/robustness.md must hold the preset table as the code prints it:\n{table}"
    );
}
