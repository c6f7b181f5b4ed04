//! The controllers' configuration flags (`stiffid_machining::program::cartesian::flags`).

use stiffid_machining::program::cartesian::flags::*;

#[test]
fn fanuc_config_is_read_in_its_variants_and_refused_when_unknown() {
    let want = Flags::Fanuc("N U T, 0, 0, 0".into());
    for text in ["N U T, 0, 0, 0", "NUT, 0, 0, 0", "N U T", "T U N, 0,0,0"] {
        assert_eq!(Flags::fanuc(text).as_ref(), Ok(&want), "{text}");
    }
    assert_eq!(
        Flags::fanuc("F D B, -1, 0, 1"),
        Ok(Flags::Fanuc("F D B, -1, 0, 1".into()))
    );
    for bad in [
        "N X T, 0, 0, 0",
        "N U, 0, 0, 0",
        "N U T, a, 0, 0",
        "N F U T",
    ] {
        assert!(Flags::fanuc(bad).is_err(), "{bad}");
    }
}

#[test]
fn kuka_parts_are_written_in_the_form_read() {
    let f = Flags::Kuka(0b110, 0b010101);
    assert_eq!(Part::Status { binary: true }.text(&f), "'B110'");
    assert_eq!(Part::Turn { binary: false }.text(&f), "21");
    assert_eq!(Part::Abb(3).text(&Flags::Abb([0, -1, 2, 5])), "5");
}
