//! The field's URDF robots (`a1`, `go1_urdf`, `anymal_b`, `laikago`) are bundled: each resolves
//! by name to the shared model, which is the same model its profile's path gives, so the
//! compiled-in files are the committed ones.

use std::path::Path;
use std::sync::Arc;

use hyq_formats::robots;

#[test]
fn each_resolves_by_name_to_the_model_its_profile_path_gives() {
    for (name, _, _) in robots::FIELD {
        assert!(robots::NAMES.contains(&name), "{name} is not in NAMES");
        let by_name = robots::resolve(name).unwrap_or_else(|e| panic!("{e}"));
        assert!(Arc::ptr_eq(
            &by_name,
            &robots::by_name(name).expect("bundled")
        ));
        assert_eq!(by_name.name(), name);
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../assets")
            .join(name)
            .join("profile.toml");
        let from_path = robots::load_profile(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            *by_name, from_path,
            "{name}: bundled and committed files differ"
        );
    }
}

#[test]
fn an_unknown_name_lists_every_bundled_robot() {
    let e = robots::resolve("anymal").expect_err("not bundled");
    assert!(
        e.to_string()
            .contains("hyq, anymal_c, go1, a1, go1_urdf, anymal_b, laikago"),
        "{e}"
    );
    assert!(
        robots::load_field("hyq").is_none(),
        "hyq is not a field robot"
    );
}
