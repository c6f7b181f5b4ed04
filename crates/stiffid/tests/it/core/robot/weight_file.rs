//! The `[gravity]` table of a robot's own weight: written and read back exactly, a bad table or
//! tool centre refused naming its field.

use serde::Deserialize;
use stiffid_core::robot::weight_file::*;
use stiffid_core::Result;

fn own() -> OwnWeight {
    OwnWeight {
        gravity: "lumped".into(),
        terms: vec![
            ("gravity.c2.link2.m".into(), 6.1e-7),
            ("gravity.c3.link3.mx".into(), -1.25e-8),
        ],
        tool_mass: Some(12.5),
        tool_centre: Some(nalgebra::Vector3::new(0.0, -0.05, 0.125)),
    }
}

#[derive(Deserialize)]
struct F {
    gravity: Option<GravityFile>,
}

fn read(text: &str) -> Result<Option<OwnWeight>> {
    let f: F = toml::from_str(text).expect("TOML");
    build(f.gravity, "robot.toml")
}

#[test]
fn round_trip_is_exact() {
    assert_eq!(read(&toml(&own())).unwrap(), Some(own()));
    assert!(toml(&own()).contains("tool_centre_of_mass_mm = [0.0, -50.0, 125.0]\n"));
}

#[test]
fn bad_tables_name_the_field() {
    let bad = toml(&own()).replace("lumped\"", "none\"");
    let e = read(&bad).unwrap_err().to_string();
    assert!(e.contains("robot.toml: gravity.model"), "{e}");
    let bad = toml(&own()).replace("12.5", "-1.0");
    let e = read(&bad).unwrap_err().to_string();
    assert!(e.contains("gravity.tool_mass_kg"), "{e}");
    let bad = toml(&own()).replace("6.1e-7", "nan");
    let e = read(&bad).unwrap_err().to_string();
    assert!(e.contains("gravity.terms[1].value_si"), "{e}");
}

/// A tool's centre of mass in the table: three numbers, finite, within the lengths' range, only
/// with its mass.
#[test]
fn a_bad_tool_centre_names_the_field() {
    for bad in ["nan", "1e9"] {
        let text = toml(&own()).replace("125.0]", &format!("{bad}]"));
        let e = read(&text).unwrap_err().to_string();
        assert!(e.contains("gravity.tool_centre_of_mass_mm"), "{e}");
    }
    for bad in ["125.0, 7.0]", "]"] {
        let text = toml(&own()).replace("125.0]", bad).replace(", ]", "]");
        let e = toml::from_str::<F>(&text).err().expect(&text).to_string();
        assert!(
            e.contains("tool_centre_of_mass_mm") && e.contains("an array of length 3"),
            "{e}"
        );
    }
    let alone = toml(&own()).replace("tool_mass_kg = 12.5\n", "");
    let e = read(&alone).unwrap_err().to_string();
    assert!(
        e.contains("gravity.tool_centre_of_mass_mm") && e.contains("needs tool_mass_kg"),
        "{e}"
    );
}
