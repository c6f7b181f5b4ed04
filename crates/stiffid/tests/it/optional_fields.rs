//! A setup may leave out the nominal stiffness and the characteristic length: the criteria and
//! computations that do not use them work as with them, the others fail naming the field and what
//! needs it.

use stiffid::internal::design::{self, target, Criterion, Evaluator, SearchOptions};
use stiffid::{
    internal::{study, study::simulate},
    Error, Setup,
};

/// The paper setup without the line of `field`.
fn paper_without(field: &str) -> Setup {
    let text: String = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with(field))
        .map(|l| format!("{l}\n"))
        .collect();
    stiffid::internal::setup::parse(&text, "cell.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap()
}

fn paper() -> Setup {
    stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap()
}

/// The field and what needed it, of a [`Error::MissingField`].
fn missing(e: Error) -> (&'static str, String) {
    match e {
        Error::MissingField { field, needed_by } => (field, needed_by),
        other => panic!("expected MissingField, got {other}"),
    }
}

fn small() -> SearchOptions {
    SearchOptions {
        max_evals: 200,
        ..SearchOptions::default()
    }
}

#[test]
fn without_a_characteristic_length_only_classical_and_zhang2021_are_missing() {
    let (full, setup) = (paper(), paper_without("characteristic_length_mm"));
    assert_eq!(setup.characteristic_length(), None);
    assert_eq!(setup.nominal_stiffness(), full.nominal_stiffness());
    let group = design::random_group(&full, 6, 1);
    let (e, f) = (
        design::evaluate(&setup, &group),
        design::evaluate(&full, &group),
    );
    assert!(e.classical.is_nan() && e.zhang2021.is_nan());
    assert!(f.classical.is_finite() && f.zhang2021.is_finite());
    for c in [
        Criterion::ScaledCond,
        Criterion::DOptimal,
        Criterion::RelativeA,
    ] {
        assert_eq!(e.value(c), f.value(c), "{c}");
    }
    assert_eq!(e.predicted_deviation_pct, f.predicted_deviation_pct);
    assert!(Evaluator::new(&setup)
        .value(Criterion::Zhang2021, &group)
        .is_nan());
    for c in [Criterion::Classical, Criterion::Zhang2021] {
        let err = design::local(&setup, c, &group, &small()).unwrap_err();
        assert_eq!(err.to_string(), format!("the setup has no characteristic_length_mm: criterion {c} needs it (the length that minimises the robot's median dexterity will do (the robot's own characteristic length: Python's Robot.characteristic_length_mm, or the one `stiffid setups new` writes))"));
    }
    // relative-a needs no characteristic length: the same search, the same group.
    let without = design::local(&setup, Criterion::RelativeA, &group, &small()).unwrap();
    let with = design::local(&full, Criterion::RelativeA, &group, &small()).unwrap();
    assert_eq!(without.postures, with.postures);
    assert!(without.value < without.start_value);
    let options = study::Options {
        runs: 5,
        seed: 1,
        starts: 1,
        trials: 0,
        ..Default::default()
    };
    let (field, by) = missing(study::run(&setup, &options, &()).unwrap_err());
    assert_eq!(
        (field, by.as_str()),
        (
            "characteristic_length_mm",
            "the study (criteria classical and zhang2021)"
        )
    );
}

#[test]
fn without_a_nominal_stiffness_the_scaled_criteria_and_the_simulation_are_missing() {
    let (full, setup) = (paper(), paper_without("nominal_stiffness_nm_per_rad"));
    assert_eq!(setup.nominal_stiffness(), None);
    assert_eq!(setup.nominal_compliance(), None);
    let group = design::random_group(&full, 6, 2);
    let (e, f) = (
        design::evaluate(&setup, &group),
        design::evaluate(&full, &group),
    );
    for c in [
        Criterion::ScaledCond,
        Criterion::DOptimal,
        Criterion::RelativeA,
    ] {
        assert!(e.value(c).is_nan() && f.value(c).is_finite(), "{c}");
        let (field, by) = missing(c.check(&setup).unwrap_err());
        assert_eq!(
            (field, by),
            ("nominal_stiffness_nm_per_rad", format!("criterion {c}"))
        );
        assert!(!c.serves(&setup) && c.serves(&full));
    }
    assert!(e.relative_std.iter().all(|v| v.is_nan()));
    assert!(e
        .predicted_deviation_pct
        .iter()
        .flatten()
        .all(|v| v.is_nan()));
    for c in [
        Criterion::Classical,
        Criterion::Zhang2021,
        Criterion::TestPose,
    ] {
        assert_eq!(e.value(c), f.value(c), "{c}");
        assert!(e.value(c).is_finite() && c.check(&setup).is_ok(), "{c}");
    }
    assert_eq!(e.cond_psi, f.cond_psi);
    // The default criterion needs it.
    let err = design::local(&setup, Criterion::RelativeA, &group, &small()).unwrap_err();
    assert!(err.to_string().starts_with("the setup has no nominal_stiffness_nm_per_rad: criterion relative-a needs it (a rough prior will do: one scaled from the robot's payload class"), "{err}");
    assert!(
        !err.to_string().contains("stiffid setups"),
        "no command in a library message: {err}"
    );
    // zhang2021 does not: the same search, the same group.
    let without = design::local(&setup, Criterion::Zhang2021, &group, &small()).unwrap();
    let with = design::local(&full, Criterion::Zhang2021, &group, &small()).unwrap();
    assert_eq!(without.postures, with.postures);
    let options = simulate::Options { runs: 5, seed: 1 };
    let (field, by) =
        missing(simulate::monte_carlo(&setup, std::slice::from_ref(&group), &options).unwrap_err());
    assert_eq!(
        (field, by.as_str()),
        (
            "nominal_stiffness_nm_per_rad",
            "the simulation (the true stiffness)"
        )
    );
    let choose = |n: usize| Ok::<_, Error>(design::random_group(&full, n, 1));
    let (field, _) = missing(target::smallest_group(&setup, 5.0, 8, choose).unwrap_err());
    assert_eq!(field, "nominal_stiffness_nm_per_rad");
}

#[test]
fn the_fields_given_are_still_checked() {
    let text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .replace(
            "characteristic_length_mm = 1200.0",
            "characteristic_length_mm = 0.0",
        );
    let e = stiffid::internal::setup::parse(&text, "cell.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap_err();
    assert!(e.to_string().contains("characteristic_length_mm"), "{e}");
    let built = paper()
        .to_builder()
        .with_nominal_stiffness(nalgebra::Vector6::repeat(0.5))
        .build()
        .unwrap_err();
    assert!(
        built.to_string().contains("nominal_stiffness_nm_per_rad"),
        "{built}"
    );
}

/// A setup used only to identify and compensate may leave out the simulations' noise levels:
/// it has the one level of the reading noise as given, and everything else as with them.
#[test]
fn without_noise_levels_a_setup_has_the_reading_noise_as_given() {
    let (full, setup) = (paper(), paper_without("level_multiples"));
    assert_eq!(setup.noise().levels, vec![1.0]);
    assert!(full.noise().levels.len() > 1);
    assert_eq!(
        setup.noise().reading_variance,
        full.noise().reading_variance
    );
    assert_eq!(setup.robot(), full.robot());
}
