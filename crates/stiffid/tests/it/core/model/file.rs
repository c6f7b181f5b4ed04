use stiffid_core::model::parse_fragment;
use stiffid_core::robot::presets;

#[test]
fn a_spring_axis_or_point_of_another_length_is_refused() {
    let robot = presets::get("comau-smart5-nj165-3.0").unwrap();
    let spring = |axis: &str, point: &str| {
        let text = format!(
            "[model]\n[[model.spring]]\nname = \"bend\"\nkind = \"rotation\"\nlink = 3\naxis = {axis}\n{point}"
        );
        parse_fragment(&text, "model.toml", &robot).map_err(|e| e.to_string())
    };
    assert!(spring("[1, 0, 0]", "point_mm = [0, 0, 10]").is_ok());
    for (axis, point) in [
        ("[1, 0, 0, 0]", ""),
        ("[1, 0]", ""),
        ("[1, 0, 0]", "point_mm = [0, 0, 10, 5]"),
    ] {
        let e = spring(axis, point).unwrap_err();
        assert!(e.contains("an array of length 3"), "{axis} {point}: {e}");
    }
}
