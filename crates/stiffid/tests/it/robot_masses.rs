//! A robot file's masses: a link without mass carries no inertia tensor.

/// Six equal joints of a robot file, each with `mass` (kg) and `inertia` (the six components).
fn robot(mass: &str, inertia: &str) -> String {
    let joint = format!(
        "[[joint]]\na_mm = 100.0\nalpha_deg = 90.0\nd_mm = 0.0\nlower_deg = -170.0\nupper_deg = 170.0\nmass_kg = {mass}\ncom_mm = [0, 0, 0]\ninertia_kg_m2 = {inertia}\n"
    );
    "name = \"x\"\nconvention = \"modified-dh\"\n".to_string() + &joint.repeat(6)
}

#[test]
fn a_massless_link_with_an_inertia_tensor_is_an_error_naming_the_field() {
    let message =
        stiffid::internal::robot::file::parse(&robot("0", "[1, 1, 1, 0, 0, 0]"), "m.toml")
            .unwrap_err()
            .to_string();
    assert!(
        message.contains("m.toml")
            && message.contains("joint[1].inertia_kg_m2")
            && message.contains("mass_kg = 0"),
        "{message}"
    );
    // A product of inertia alone is an inertia too.
    let message =
        stiffid::internal::robot::file::parse(&robot("0.0", "[0, 0, 0, 0, 0, 1e-9]"), "m.toml")
            .unwrap_err()
            .to_string();
    assert!(message.contains("joint[1].inertia_kg_m2"), "{message}");
    // A massless link without a tensor, and a light link with one, are bodies.
    let massless =
        stiffid::internal::robot::file::parse(&robot("0", "[0, 0, 0, 0, 0, 0]"), "m.toml");
    assert_eq!(massless.unwrap().masses().unwrap()[2].mass, 0.0);
    let light =
        stiffid::internal::robot::file::parse(&robot("1e-6", "[1, 1, 1, 0, 0, 0]"), "m.toml");
    assert_eq!(light.unwrap().masses().unwrap()[2].inertia[(0, 0)], 1.0);
}
