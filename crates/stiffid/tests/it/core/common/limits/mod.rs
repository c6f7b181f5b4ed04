mod joint_box;

use stiffid_core::common::limits::*;

#[test]
fn short_cuts_long_text_on_a_character_boundary() {
    assert_eq!(short("abc"), "abc");
    let long = "é".repeat(100);
    let s = short(&long);
    assert_eq!(s.chars().count(), 60 + 3);
    assert!(s.ends_with("..."));
}

#[test]
fn check_names_the_index_and_value() {
    let e = check("x_mm", &[1.0, f64::NAN], &LENGTH_MM).unwrap_err();
    assert_eq!(
        e.to_string(),
        "x_mm[2]: NaN is outside [-100000, 100000] mm"
    );
    let e = check("k", &[1e-320], &STIFFNESS_NM_PER_RAD).unwrap_err();
    assert!(e.to_string().contains("1e-320"), "{e}");
    assert!(check("k", &[1e6], &STIFFNESS_NM_PER_RAD).is_ok());
}
