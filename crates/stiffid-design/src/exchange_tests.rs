//! The best group of a pool by enumeration or exchange (`crate::exchange`).

use crate::exchange::*;

#[test]
fn combinations_are_all_visited_once_in_order() {
    let mut g = vec![0, 1, 2];
    let mut count = 1;
    let mut last = g.clone();
    while next_combination(&mut g, 6) {
        assert!(g > last && g.windows(2).all(|w| w[0] < w[1]) && g[2] < 6);
        last = g.clone();
        count += 1;
    }
    assert_eq!(count, binomial(6, 3));
    assert_eq!(count, 20);
    assert_eq!(binomial(1000, 6), 1_368_173_298_991_500);
    assert_eq!(binomial(12, 6), 924);
    assert_eq!(binomial(5, 6), 0);
    assert_eq!(binomial(10_000, 60), u128::MAX);
}

#[test]
fn the_exchange_finds_what_enumeration_finds_on_a_separable_value() {
    // The sum of distinct weights: the best group is the n smallest, found by both.
    let weights: Vec<f64> = (0..40).map(|i| ((i * 37) % 41) as f64).collect();
    let value = |g: &[usize]| g.iter().map(|&k| weights[k]).sum::<f64>();
    let exact = PoolOptions {
        enumeration_limit: 1_000_000,
        ..PoolOptions::default()
    };
    let swapped = PoolOptions {
        enumeration_limit: 0,
        ..PoolOptions::default()
    };
    let a = best(40, 3, &exact, &value);
    let mut b = best(40, 3, &swapped, &value);
    b.group.sort_unstable();
    assert_eq!(a.method, PoolMethod::Enumeration);
    assert_eq!(b.method, PoolMethod::Exchange);
    assert_eq!(a.group, b.group);
    assert_eq!(value(&a.group), 0.0 + 1.0 + 2.0);
}
