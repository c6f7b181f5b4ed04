//! The identify job's options checked together (crate::app::identify::Options): each refused
//! combination is one typed error naming the option and the ones it cannot go with or needs,
//! and every accepted combination passes.

use stiffid::app::identify::Options;
use stiffid::internal::identify::Loss;
use stiffid::{Error, JobOption as O};

fn refusal(options: Options) -> (O, Vec<O>, bool) {
    match options.check() {
        Err(Error::OptionCombination {
            option,
            with,
            needs,
            ..
        }) => (option, with, needs),
        other => panic!("{other:?}"),
    }
}

#[test]
fn each_combination_that_cannot_go_together_is_refused_naming_the_options() {
    let d = Options::default;
    let huber = Some(Loss::Huber);
    let cases = [
        (
            Options {
                robust: huber,
                nonnegative: true,
                ..d()
            },
            (O::Robust, vec![O::Nonnegative], false),
        ),
        (
            Options {
                offsets: true,
                robust: huber,
                ..d()
            },
            (O::Offsets, vec![O::Robust], false),
        ),
        (
            Options {
                offsets: true,
                nonnegative: true,
                ..d()
            },
            (O::Offsets, vec![O::Nonnegative], false),
        ),
        (
            Options {
                offsets: true,
                cross_validate: true,
                folds: Some(3),
                ..d()
            },
            (O::Offsets, vec![O::CrossValidate, O::Folds], false),
        ),
        (
            Options {
                compare_models: true,
                nonnegative: true,
                offsets: true,
                ..d()
            },
            (O::CompareModels, vec![O::Nonnegative, O::Offsets], false),
        ),
        (
            Options {
                candidates: Some(vec!["tilt".into()]),
                ..d()
            },
            (O::Candidates, vec![O::CompareModels], true),
        ),
        (
            Options {
                bootstrap: Some(5),
                ..d()
            },
            (O::Bootstrap, vec![O::CompareModels], true),
        ),
        (
            Options {
                compare_models: true,
                seed: Some(2),
                ..d()
            },
            (O::Seed, vec![O::Bootstrap], true),
        ),
    ];
    for (options, expected) in cases {
        assert_eq!(refusal(options), expected);
    }
    let text = Options {
        offsets: true,
        folds: Some(3),
        ..d()
    }
    .check()
    .unwrap_err()
    .to_string();
    assert!(
        text.starts_with("offsets: not with folds: a held-out posture's offsets"),
        "{text}"
    );
    let text = Options {
        seed: Some(2),
        ..d()
    }
    .check()
    .unwrap_err()
    .to_string();
    assert_eq!(text, "seed: only with bootstrap");
}

#[test]
fn the_combinations_that_go_together_pass() {
    let d = Options::default;
    for options in [
        d(),
        Options {
            robust: Some(Loss::Tukey),
            folds: Some(4),
            ..d()
        },
        Options {
            nonnegative: true,
            cross_validate: true,
            ..d()
        },
        Options {
            offsets: true,
            ..d()
        },
        Options {
            compare_models: true,
            candidates: Some(vec!["tilt3_x".into()]),
            bootstrap: Some(10),
            seed: Some(7),
            ..d()
        },
    ] {
        assert_eq!(options.check(), Ok(()), "{options:?}");
    }
}
