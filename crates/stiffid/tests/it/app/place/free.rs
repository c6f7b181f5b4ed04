//! `place --free` (`stiffid::app::place::Free::parse`): the height and tilt in the
//! grammar of `compensate --free`, each from the part's own.

use stiffid::app::place::Free;
use stiffid_core::common::error::JobOption;
use stiffid_core::Error;

/// The part's own height, m.
const OWN_Z: f64 = 0.4;

fn parse(texts: &[&str]) -> Option<Free> {
    Free::parse(texts, OWN_Z).unwrap_or_else(|e| panic!("{texts:?}: {e}"))
}

#[test]
fn the_height_and_tilt_are_ranges_from_the_parts_own_and_a_variable_not_given_stays() {
    assert_eq!(parse(&[]), None);
    let close =
        |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12;
    let z = parse(&["z"]).unwrap();
    assert!(close(z.z, [0.3, 0.5]) && z.tilt == 0.0, "{z:?}");
    let z = parse(&["z = -50..150"]).unwrap();
    assert!(close(z.z, [0.35, 0.55]) && z.tilt == 0.0, "{z:?}");
    let t = parse(&["tilt"]).unwrap();
    assert!(close(t.z, [OWN_Z, OWN_Z]), "{t:?}");
    // The documented default: +-10 deg.
    assert!((t.tilt - 10f64.to_radians()).abs() < 1e-15);
    let both = parse(&["tilt=-5..5", "z=0..20"]).unwrap();
    assert!(close(both.z, [0.4, 0.42]), "{both:?}");
    assert!((both.tilt - 5f64.to_radians()).abs() < 1e-15);
    let most = parse(&["tilt=-45..45"]).unwrap();
    assert!((most.tilt - 45f64.to_radians()).abs() < 1e-15);
}

#[test]
fn other_names_steps_asymmetric_tilts_and_repeats_are_refused_naming_the_text() {
    for (text, why) in [
        (&["x=-5..5"][..], "expected z"),
        (&["rotation"], "expected z"),
        (&["z=-5..5/1"], "no step"),
        (&["tilt=-2..5"], "-T..T"),
        (&["tilt=-45.5..45.5"], "0 < T <= 45"),
        (&["tilt=0..0"], "0 < T <= 45"),
        (&["z=5..-5"], "LO <= HI"),
        (&["z=-30000..0"], "within -20000..20000 mm"),
        (&["z", "z=-1..1"], "given twice"),
        (&["=1..2"], "expected a variable"),
    ] {
        match Free::parse(text, OWN_Z) {
            Err(Error::InvalidOption {
                option: JobOption::Free,
                message,
            }) => assert!(message.contains(why), "{text:?}: {message}"),
            other => panic!("{text:?}: {other:?}"),
        }
    }
}
