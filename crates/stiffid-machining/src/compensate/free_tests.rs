//! The `--free` texts (`crate::compensate::free`).

use crate::compensate::free::*;
use crate::compensate::{Scope, Variable};
use stiffid_core::common::error::JobOption;
use stiffid_core::Error;

#[test]
fn the_texts_of_free_parse_to_their_variable_range_and_step() {
    let cases = [
        (
            "tool-rotation=-90..90/5",
            Variable::ToolRotation,
            Some(90.0),
            Some(5.0),
        ),
        ("tool-rotation", Variable::ToolRotation, None, None),
        ("station=-500..500", Variable::Station, Some(500.0), None),
        ("lead-tilt=/2.5", Variable::LeadTilt, None, Some(2.5)),
        ("tilt = -10..10/5", Variable::Tilt, Some(10.0), Some(5.0)),
        (
            "E2=-30..30/5",
            Variable::Axis("E2".into()),
            Some(30.0),
            Some(5.0),
        ),
        (
            "configuration=run",
            Variable::Configuration(Scope::Run),
            None,
            None,
        ),
        (
            "configuration",
            Variable::Configuration(Scope::Program),
            None,
            None,
        ),
    ];
    for (text, variable, range, step) in cases {
        let free = FreeOption::parse(text).unwrap();
        assert_eq!(
            (free.variable, free.range, free.step),
            (variable, range, step),
            "{text}"
        );
    }
}

#[test]
fn malformed_texts_are_refused_naming_free_and_the_text() {
    for text in [
        "tool-rotation=90",
        "tool-rotation=-90..80",
        "tool-rotation=90..-90",
        "tool-rotation=-0..0",
        "tool-rotation=-nan..nan",
        "tool-rotation=-90..90/",
        "tool-rotation=-90..90/x",
        "=-5..5",
        "configuration=each",
    ] {
        match FreeOption::parse(text) {
            Err(Error::InvalidOption {
                option: JobOption::Free,
                message,
            }) => {
                assert!(message.starts_with(text), "{message}")
            }
            other => panic!("{text}: {other:?}"),
        }
    }
    assert!(FreeOption::from_parts("station=-5..5", None, None).is_err());
    assert!(FreeOption::from_parts("station", Some(-5.0), None).is_err());
}

#[test]
fn every_retired_option_says_how_to_write_it() {
    for (name, option, value) in RETIRED {
        assert!(["free", "minimise"].contains(option), "{name}");
        if *option == "free" {
            let text = value.split([' ', '|']).next().unwrap();
            let text = text
                .replace("-R..R", "-1..1")
                .replace("-CONE..CONE", "-1..1");
            let text = text.replace("STEP", "1");
            FreeOption::parse(&text).unwrap_or_else(|e| panic!("{name}: {text}: {e}"));
        }
    }
    assert_eq!(
        retired("free-tool-axis"),
        Some(("free", "tool-rotation=-90..90/2"))
    );
    assert!(retired("free").is_none());
}
