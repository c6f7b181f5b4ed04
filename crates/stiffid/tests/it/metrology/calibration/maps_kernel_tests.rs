//! The maps' held-out errors on a split ([`Linear::errors`]: Eldén's bidiagonal ridge steps on the
//! split's QR factor) against the ridge least squares of the linearised model solved directly
//! (nalgebra's Householder QR of the whole augmented system), from a ridge of `1e-12` up, with
//! fewer training rows than candidate columns and with more, a choice with more columns than
//! training rows (the bidiagonalisation of its transpose) and with fewer; and the nested figure of
//! choices given back equal to the one that chose them.

use super::error_model::Observation;
use super::fit::{self, Fit};
use super::maps::{self, JointMaps, Linear, Spec};
use super::maps_tests::{identified, model, noisy, options, truth};
use super::tests::{postures, readings};
use super::ErrorModel;
use nalgebra::{DMatrix, DVector};
use stiffid_core::robot::error_map;

/// A UR10 campaign of `n` postures at one point with maps on joints 2 and 5: the geometric
/// model, the readings and the model's fit to them.
fn campaign(n: usize, seed: u64) -> (ErrorModel, Vec<Observation>, Fit) {
    let geometry = model();
    let qs = postures(geometry.robot(), n, 500 + seed);
    let kept = identified(&geometry, &qs);
    let mapped = geometry.clone().with_maps([0, 8, 0, 0, 4, 0]).unwrap();
    let truth = truth(&mapped, &kept, 2e-4, seed);
    let data = noisy(readings(&mapped, &truth, &qs), 2e-5, seed);
    let start = fit::start(&geometry, &data).unwrap();
    let fitted = fit::fit(&geometry, &data, &start, &options(0.0)).unwrap();
    (geometry, data, fitted)
}

/// [`campaign`] linearised at its geometric fit with every joint's 32 harmonics (384 columns) as
/// candidates.
fn linear(n: usize, seed: u64) -> Linear {
    let (geometry, data, fitted) = campaign(n, seed);
    Linear::at(&geometry, &fitted, &data, 1.0, Spec::Auto.candidates(false)).unwrap()
}

/// The columns of `choice` in `linear`: each chosen joint's `cos 1..h` then `sin 1..h`.
fn map_columns(linear: &Linear, choice: &JointMaps) -> DMatrix<f64> {
    let mut cols = Vec::new();
    for j in 0..6 {
        let h = choice.harmonics[j];
        for c in (0..h).chain(linear.harmonics..linear.harmonics + h) {
            cols.push(linear.maps[j].column(c).into_owned());
        }
    }
    DMatrix::from_columns(&cols)
}

/// Per test posture, the sum of squared errors of the linearised model's ridge least squares
/// (`min |r_T + G_T dx + M_T y|^2 + lambda |y|^2`) solved as one system, the test posture's map
/// columns tapered beyond the training postures' range of their joint's angle as a calibrated
/// robot's maps taper beyond the fitted range.
fn direct(
    linear: &Linear,
    choice: &JointMaps,
    train: &[usize],
    test: &[usize],
    lambda: f64,
) -> Vec<f64> {
    let rows =
        |ps: &[usize]| -> Vec<usize> { ps.iter().flat_map(|&p| linear.rows[p].clone()).collect() };
    let tr = rows(train);
    let m = map_columns(linear, choice);
    let (g, s) = (linear.geometry.ncols(), m.ncols());
    let mut a = DMatrix::zeros(tr.len() + s, g + s);
    let mut b = DVector::zeros(tr.len() + s);
    for (i, &r) in tr.iter().enumerate() {
        a.view_mut((i, 0), (1, g))
            .copy_from(&linear.geometry.row(r));
        a.view_mut((i, g), (1, s)).copy_from(&m.row(r));
        b[i] = -linear.residuals[r];
    }
    for k in 0..s {
        a[(tr.len() + k, g + k)] = lambda.sqrt();
    }
    // Householder QR of the whole augmented system (full column rank: the ridge rows).
    let qr = a.qr();
    let mut qtb = b;
    qr.q_tr_mul(&mut qtb);
    let x = (qr.r())
        .solve_upper_triangular(&qtb.rows(0, g + s).into_owned())
        .unwrap();
    let joints: Vec<usize> = (0..6)
        .flat_map(|j| std::iter::repeat_n(j, 2 * choice.harmonics[j]))
        .collect();
    let range: Vec<(f64, f64)> = (0..6)
        .map(|j| {
            let angles = train.iter().map(|&p| linear.angles[p][j]);
            (
                angles.clone().fold(f64::INFINITY, f64::min),
                angles.fold(f64::NEG_INFINITY, f64::max),
            )
        })
        .collect();
    let mut out = vec![0.0; test.len()];
    for (t, &p) in test.iter().enumerate() {
        let taper: Vec<f64> = (0..s)
            .map(|c| error_map::taper(linear.angles[p][joints[c]], range[joints[c]]))
            .collect();
        for &r in &linear.rows[p] {
            let maps: f64 = (0..s).map(|c| taper[c] * m[(r, c)] * x[g + c]).sum();
            let e =
                linear.residuals[r] + linear.geometry.row(r).dot(&x.rows(0, g).transpose()) + maps;
            out[t] += e * e;
        }
    }
    out
}

/// The choice of `h2` harmonics on joint 2 and `h5` on joint 5.
fn choice(h2: usize, h5: usize) -> JointMaps {
    let mut choice = JointMaps::NONE;
    choice.harmonics[1] = h2;
    choice.harmonics[4] = h5;
    choice
}

/// The split's errors of [`linear`]'s postures with the maps of `choice` (with `restricted`,
/// from the linearisation restricted to the choice's columns) against [`direct`] on every
/// candidate column's linearisation.
fn assert_split_matches(linear: &Linear, restricted: bool, choice: &JointMaps) {
    let n = linear.rows.len();
    let (train, test): (Vec<usize>, Vec<usize>) = (0..n).partition(|p| p % 5 != 0);
    let narrow = linear.restricted(choice);
    let used = if restricted { &narrow } else { linear };
    if restricted {
        let columns = 2 * choice.harmonics.iter().sum::<usize>();
        assert_eq!(
            narrow.maps.iter().map(|m| m.ncols()).sum::<usize>(),
            columns
        );
    }
    let split = used.split(&train, &test).unwrap();
    // From far below the least ridge a calibration takes on these training readings (one per
    // posture).
    let least = 1e-6 * train.len() as f64;
    for lambda in [1e-12, least, 1e-2, 1.0] {
        let got = used
            .errors(&split, choice, &[lambda])
            .unwrap()
            .swap_remove(0);
        let want = direct(linear, choice, &train, &test, lambda);
        // At 1e-12 the augmented system's condition bounds any two stable solutions' agreement:
        // its SVD and its Householder QR differ by up to 1e-8 of the errors there, and by up to
        // 2e-7 where held-out postures beyond the training range have their maps tapered.
        let tolerance = if lambda < least { 5e-7 } else { 1e-9 };
        for (g, w) in got.iter().zip(&want) {
            assert!(
                (g - w).abs() <= tolerance * w.max(1e-12),
                "{n} postures, lambda {lambda}: {g:e} vs {w:e}"
            );
        }
    }
}

#[test]
fn a_splits_errors_are_the_ridge_least_squares_with_fewer_rows_than_columns() {
    // 40 training postures at one point: 120 rows, 384 candidate columns; the choice's 48.
    assert_split_matches(&linear(50, 7), false, &choice(16, 8));
}

#[test]
fn a_choice_with_more_columns_than_training_rows_is_the_ridge_least_squares() {
    // 120 training rows, the choice's 128 columns (both joints at 32 harmonics).
    let fifty = linear(50, 7);
    assert_split_matches(&fifty, false, &choice(32, 32));
    assert_split_matches(&fifty, true, &choice(32, 32));
}

#[test]
fn a_restricted_linearisations_errors_are_the_ridge_least_squares() {
    // The choice's 48 columns alone, from 120 training rows and from 432 (both more rows than
    // columns).
    assert_split_matches(&linear(50, 7), true, &choice(16, 8));
    assert_split_matches(&linear(180, 7), true, &choice(16, 8));
}

#[test]
fn a_splits_errors_are_the_ridge_least_squares_with_more_rows_than_columns() {
    // 144 training postures: 432 rows, 384 candidate columns; the choices' 48 and 128.
    let many = linear(180, 7);
    assert_split_matches(&many, false, &choice(16, 8));
    assert_split_matches(&many, false, &choice(32, 32));
}

#[test]
fn the_nested_figure_of_the_choices_given_is_the_nested_figure() {
    let linear = linear(60, 3);
    let all: Vec<usize> = (0..60).collect();
    let nested = maps::nested(&linear, &all, Spec::Auto).unwrap();
    assert!(nested.choices.iter().any(|c| !c.is_none()), "{nested:?}");
    let given = maps::nested_given(&linear, &all, &nested).unwrap();
    assert_eq!(given.choices, nested.choices);
    assert_eq!(given.ridges, nested.ridges);
    for (g, w) in given.errors.iter().zip(&nested.errors) {
        assert!((g - w).abs() <= 1e-12 * w.max(1e-30), "{g:e} vs {w:e}");
    }
    let short = maps::Nested {
        ridges: nested.ridges[1..].to_vec(),
        ..nested.clone()
    };
    assert!(maps::nested_given(&linear, &all, &short).is_err());
}

/// The maps fitted after an assessment made at another fit (a ladder's later gravity model) have
/// their ridge chosen again at the fit they are fitted at; an assessment made at that fit keeps
/// its own.
#[test]
fn maps_chosen_at_another_fit_have_their_ridge_chosen_again() {
    use stiffid::internal::metrology::calibration::judgement::maps::{fit_maps, Assessed, Maps};
    let (geometry, data, fitted) = campaign(60, 3);
    let linear = Linear::at(&geometry, &fitted, &data, 1.0, Spec::Auto.candidates(false)).unwrap();
    let all: Vec<usize> = (0..60).collect();
    let choice = maps::choose(&linear, &all, Spec::Auto).unwrap();
    assert!(!choice.maps.is_none(), "{choice:?}");
    // A ridge no cross-validation chooses, as if chosen elsewhere.
    let elsewhere = maps::Choice {
        ridge: 123.0,
        ..choice.clone()
    };
    let ridge_after = |own_fit: bool| {
        let assessed = Assessed {
            maps: Maps {
                spec: Spec::Auto,
                postures: 60,
                choice: Some(elsewhere.clone()),
                nested: None,
                skipped: None,
            },
            own_fit,
            nested: None,
        };
        let fitted_maps = fit_maps(
            assessed,
            Ok(()),
            (geometry.clone(), fitted.clone()),
            &data,
            options(0.0),
        );
        let (_, _, options, report) = fitted_maps.unwrap();
        assert_eq!(report.choice.unwrap().ridge, options.ridge);
        options.ridge
    };
    assert_eq!(ridge_after(true), 123.0);
    assert_eq!(ridge_after(false), choice.ridge);
}

/// The nested figure (its outer folds' choices in parallel, sharing their inner splits and each
/// candidate's steps on them) is the same whatever the thread count.
#[test]
fn the_nested_figure_is_the_same_on_one_thread_and_on_four() {
    let linear = linear(60, 4);
    let all: Vec<usize> = (0..60).collect();
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| maps::nested(&linear, &all, Spec::Auto).unwrap())
    };
    let one = on(1);
    assert!(one.choices.iter().any(|c| !c.is_none()), "{one:?}");
    assert_eq!(one, on(4));
}
