//! The compass search of a box ([`super::compass`]).

use super::compass::*;

fn space() -> Space {
    Space {
        lower: vec![-1.0, -1.0, -1.0],
        upper: vec![1.0, 1.0, 1.0],
        tolerance: vec![1e-4; 3],
        gridded: 2,
    }
}

#[test]
fn the_search_finds_the_least_of_two_minima_and_skips_undefined_points() {
    // Two wells, the deeper one at (0.6, -0.4, 0.3); undefined where x0 < -0.8.
    let f = |x: &[f64]| {
        let d = |c: [f64; 3]| (0..3).map(|k| (x[k] - c[k]).powi(2)).sum::<f64>();
        (x[0] >= -0.8).then(|| (d([-0.5, 0.5, 0.0]) - 0.5).min(d([0.6, -0.4, 0.3]) - 1.0))
    };
    let effort = Effort {
        grid: 5,
        samples: 16,
        starts: 3,
        seed: 7,
    };
    let (found, evaluations) = minimise(&space(), &effort, f);
    let found = found.unwrap();
    assert!(evaluations > 25 + 16);
    for (x, c) in found.x.iter().zip([0.6, -0.4, 0.3]) {
        assert!((x - c).abs() < 1e-3, "{:?}", found.x);
    }
    assert!((found.value + 1.0).abs() < 1e-6);
}

#[test]
fn nothing_defined_finds_nothing_and_the_seed_fixes_the_samples() {
    let effort = Effort {
        grid: 3,
        samples: 4,
        starts: 2,
        seed: 1,
    };
    assert_eq!(minimise(&space(), &effort, |_| None), (None, 13));
    assert_eq!(
        first_points(&space(), &effort),
        first_points(&space(), &effort)
    );
    let other = Effort { seed: 2, ..effort };
    assert_ne!(
        first_points(&space(), &effort),
        first_points(&space(), &other)
    );
}
