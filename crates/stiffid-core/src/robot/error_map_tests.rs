use crate::robot::error_map::*;
use nalgebra::Vector6;

#[test]
fn the_recurrence_is_the_series() {
    let map = ErrorMap::new(
        (1..=40).map(|h| 1e-4 / h as f64).collect(),
        (1..=40).map(|h| -2e-4 / (h * h) as f64).collect(),
    )
    .unwrap();
    for q in [-3.0, -0.7, 0.0, 1.3, 6.0] {
        let direct: f64 = (1..=40)
            .map(|h| {
                let x = h as f64 * q;
                1e-4 / h as f64 * x.cos() - 2e-4 / (h * h) as f64 * x.sin()
            })
            .sum();
        assert!((map.angle(q) - direct).abs() < 1e-15, "{q}");
    }
    let odd = ErrorMap::new(vec![1e-3, 0.0, 2e-4], vec![0.0, -5e-4, 1e-4]).unwrap();
    let q: f64 = 0.9;
    let direct =
        1e-3 * q.cos() + 2e-4 * (3.0 * q).cos() - 5e-4 * (2.0 * q).sin() + 1e-4 * (3.0 * q).sin();
    assert!((odd.angle(q) - direct).abs() < 1e-18);
    assert!(ErrorMap::new(vec![0.0], vec![]).is_err());
    assert!(ErrorMap::new(vec![f64::NAN], vec![0.0]).is_err());
    let sum = map.plus(&ErrorMap::new(vec![1e-3], vec![0.0]).unwrap());
    assert_eq!(sum.harmonics(), 40);
    assert_eq!(sum.cos()[0], 1e-4 + 1e-3);
}

#[test]
fn the_recurrence_is_the_series_at_random_angles() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    for harmonics in [1, 2, 3, 5, 16, 33, MAX_HARMONICS] {
        let mut coefficient = || MAX_COEFFICIENT * (2.0 * rng.random::<f64>() - 1.0);
        let cos: Vec<f64> = (0..harmonics).map(|_| coefficient()).collect();
        let sin: Vec<f64> = (0..harmonics).map(|_| coefficient()).collect();
        let scale: f64 = cos.iter().chain(&sin).map(|v| v.abs()).sum();
        let map = ErrorMap::new(cos.clone(), sin.clone()).unwrap();
        for _ in 0..200 {
            let q = 4.0 * std::f64::consts::PI * (rng.random::<f64>() - 0.5);
            let direct: f64 = (0..harmonics)
                .map(|h| {
                    let (s, c) = ((h + 1) as f64 * q).sin_cos();
                    cos[h] * c + sin[h] * s
                })
                .sum();
            let got = map.angle(q);
            assert!(got.is_finite());
            assert!((got - direct).abs() <= 1e-12 * scale, "{harmonics} {q}");
        }
    }
    assert_eq!(ErrorMap::default().angle(0.3), 0.0);
    let maps: [ErrorMap; 6] = std::array::from_fn(|i| match i % 2 {
        0 => ErrorMap::default(),
        _ => ErrorMap::new(vec![1e-4; i + 1], vec![-2e-4; i + 1]).unwrap(),
    });
    let q = Vector6::new(0.3, -1.2, 2.5, 0.0, -3.0, 1.0);
    let each: [f64; 6] = std::array::from_fn(|i| maps[i].angle(q[i]));
    assert_eq!(angles(&maps, &q), each);
}

#[test]
fn backlash_adds_half_the_lost_motion_by_direction() {
    let map = ErrorMap::new(vec![1e-3], vec![2e-4])
        .unwrap()
        .with_backlash(5e-4)
        .unwrap();
    let q: f64 = 0.4;
    let mean = 1e-3 * q.cos() + 2e-4 * q.sin();
    assert_eq!(map.angle(q), mean);
    assert!((map.angle_from(q, 1.0) - (mean + 5e-4)).abs() < 1e-18);
    assert!((map.angle_from(q, -1.0) - (mean - 5e-4)).abs() < 1e-18);
    let only = ErrorMap::default().with_backlash(1e-4).unwrap();
    assert!(!only.is_empty());
    assert!((only.plus(&map).backlash() - 6e-4).abs() < 1e-18);
    assert!(ErrorMap::default().with_backlash(f64::NAN).is_err());
    assert!(ErrorMap::default().with_backlash(0.2).is_err());
}

/// A map fitted over -30..50 deg: within it the series to the last bit, beyond the
/// ramp exactly 0, across the ramp the cosine taper (half at mid-ramp), continuous with its
/// slope by central differences.
#[test]
fn a_map_tapers_to_zero_beyond_its_fitted_range() {
    let (lo, hi) = (-30f64.to_radians(), 50f64.to_radians());
    let free = ErrorMap::new(vec![1e-3, -4e-4, 2e-4], vec![5e-4, 3e-4, -1e-4])
        .unwrap()
        .with_backlash(2e-4)
        .unwrap();
    let map = free.clone().with_range(lo, hi).unwrap();
    assert_eq!(map.range(), Some((lo, hi)));
    for deg in [-30.0, -29.999, 0.0, 17.3, 49.99, 50.0] {
        let q = f64::to_radians(deg);
        assert_eq!(map.angle(q).to_bits(), free.angle(q).to_bits(), "{deg}");
    }
    let ramp = TAPER_DEG;
    for deg in [
        -30.0 - ramp,
        -30.001 - ramp,
        -100.0,
        50.0 + ramp,
        50.5 + ramp,
        170.0,
    ] {
        let q = f64::to_radians(deg);
        assert_eq!(map.angle(q), 0.0, "{deg}");
        // The backlash is the gear's, kept everywhere.
        assert!((map.angle_from(q, -1.0) + 2e-4).abs() < 1e-18, "{deg}");
    }
    let mid = (50.0 + ramp / 2.0).to_radians();
    assert!((map.angle(mid) - 0.5 * free.angle(mid)).abs() < 1e-18);
    let quarter = (50.0 + ramp / 4.0).to_radians();
    let w = 0.5 * (1.0 + (std::f64::consts::PI / 4.0).cos());
    assert!((map.angle(quarter) - w * free.angle(quarter)).abs() < 1e-18);
    // The slope of e(q) w(q) by central differences is continuous across both ends of each
    // ramp (w' = 0 there) and equals the product rule within it.
    let h = 1e-7;
    let slope = |m: &ErrorMap, q: f64| (m.angle(q + h) - m.angle(q - h)) / (2.0 * h);
    for edge in [lo, hi] {
        let s = edge.signum();
        for q in [edge, edge + s * TAPER_DEG.to_radians()] {
            // A linear ramp's slope would jump by e / W, about 5e-3 here.
            let (left, right) = (slope(&map, q - 1e-6), slope(&map, q + 1e-6));
            assert!((left - right).abs() < 1e-6, "{q}: {left} {right}");
        }
    }
    let q = (50.0 + 0.7 * ramp).to_radians();
    let d = q - hi;
    let width = TAPER_DEG.to_radians();
    let dw = -0.5 * std::f64::consts::PI / width * (std::f64::consts::PI * d / width).sin();
    let product = slope(&free, q) * map.taper(q) + free.angle(q) * dw;
    assert!((slope(&map, q) - product).abs() < 1e-8, "{}", product);
    let maps: [ErrorMap; 6] = std::array::from_fn(|_| map.clone());
    // Past the ramp below, within the range, past the ramp above.
    let beyond = |i: usize| match i {
        0 => -40.0 - ramp,
        5 => 60.0 + ramp,
        _ => -35.0 + 20.0 * i as f64,
    };
    let q = Vector6::from_fn(|i, _| beyond(i).to_radians());
    let each: [f64; 6] = std::array::from_fn(|i| map.angle(q[i]));
    assert_eq!(angles(&maps, &q), each);
    assert!(each[0] == 0.0 && each[1] != 0.0 && each[5] == 0.0);
    assert!(free.clone().with_range(hi, lo).is_err());
    assert!(free.with_range(f64::NAN, hi).is_err());
}
