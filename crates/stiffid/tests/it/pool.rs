//! Choosing groups from a pool of postures (exchange algorithm against enumeration and brute force)
//! and the smallest group size for a target accuracy.

use nalgebra::Vector6;
use stiffid::internal::design::target::smallest_group;
use stiffid::internal::design::{
    random_group, Criterion, Evaluator, Pool, PoolMethod, PoolOptions,
};
use stiffid::Setup;

fn paper() -> Setup {
    stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap()
}

/// The best group of `n` of `pool` by evaluating every group with the QR-based evaluator.
fn brute_force(setup: &Setup, criterion: Criterion, pool: &[Vector6<f64>], n: usize) -> Vec<usize> {
    let evaluator = Evaluator::new(setup);
    let mut best = (f64::INFINITY, Vec::new());
    for mask in 0u32..1 << pool.len() {
        if mask.count_ones() as usize != n {
            continue;
        }
        let group: Vec<usize> = (0..pool.len()).filter(|i| mask & (1 << i) != 0).collect();
        let postures: Vec<_> = group.iter().map(|&i| pool[i]).collect();
        let v = evaluator.value(criterion, &postures);
        if v < best.0 {
            best = (v, group);
        }
    }
    best.1
}

#[test]
fn exchange_finds_the_enumerated_optimum_of_a_12_posture_pool() {
    let setup = paper();
    for (seed, criterion) in [
        (5, Criterion::RelativeA),
        (6, Criterion::DOptimal),
        (7, Criterion::Zhang2021),
    ] {
        let postures = random_group(&setup, 12, seed);
        let pool = Pool::new(&setup, &postures, &[]).unwrap();
        let enumerated = pool.best(criterion, 6, &PoolOptions::default()).unwrap();
        assert_eq!(enumerated.method, PoolMethod::Enumeration);
        assert_eq!(enumerated.evaluations, 924, "C(12, 6)");
        assert_eq!(
            enumerated.indices,
            brute_force(&setup, criterion, &postures, 6),
            "{criterion}"
        );
        let exchanged = pool
            .best(
                criterion,
                6,
                &PoolOptions {
                    enumeration_limit: 0,
                    ..PoolOptions::default()
                },
            )
            .unwrap();
        assert_eq!(exchanged.method, PoolMethod::Exchange);
        assert_eq!(exchanged.indices, enumerated.indices, "{criterion}");
        assert!((exchanged.value - enumerated.value).abs() <= 1e-12 * enumerated.value);
        let group = pool.postures(&enumerated.indices);
        assert_eq!(
            enumerated.value,
            Evaluator::new(&setup).value(criterion, &group)
        );
    }
}

#[test]
fn unusable_postures_are_never_chosen_and_limits_are_errors() {
    let setup = paper();
    let postures = random_group(&setup, 12, 5);
    let all = Pool::new(&setup, &postures, &[]).unwrap();
    let best = all
        .best(Criterion::RelativeA, 6, &PoolOptions::default())
        .unwrap();
    let mut usable = vec![true; 12];
    usable[best.indices[0]] = false;
    usable[best.indices[3]] = false;
    let some = Pool::new(&setup, &postures, &usable).unwrap();
    assert_eq!(some.usable().len(), 10);
    let other = some
        .best(Criterion::RelativeA, 6, &PoolOptions::default())
        .unwrap();
    assert!(
        other.indices.iter().all(|&i| usable[i]),
        "{:?}",
        other.indices
    );
    assert!(other.value > best.value);

    let e = some
        .best(Criterion::RelativeA, 11, &PoolOptions::default())
        .unwrap_err();
    assert!(e.to_string().contains("10 usable"), "{e}");
    let e = Pool::new(&setup, &postures, &[true; 3]).unwrap_err();
    assert!(e.to_string().contains("pool"), "{e}");
    let e = all
        .best(Criterion::RelativeA, 1, &PoolOptions::default())
        .unwrap_err();
    assert!(e.to_string().contains("at least 2"), "{e}");
}

#[test]
fn exchange_is_seeded_and_independent_of_the_thread_count() {
    let setup = paper();
    let postures = random_group(&setup, 200, 9);
    let pool = Pool::new(&setup, &postures, &[]).unwrap();
    let options = PoolOptions {
        restarts: 4,
        seed: 11,
        ..PoolOptions::default()
    };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| pool.best(Criterion::RelativeA, 6, &options).unwrap())
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one, two);
    assert_eq!(one.method, PoolMethod::Exchange);
    // The exchange's group beats every random group of the pool it started from.
    let evaluator = Evaluator::new(&setup);
    for seed in 0..20 {
        let random = stiffid::internal::design::random_group(&setup, 6, seed);
        assert!(one.value < evaluator.value(Criterion::RelativeA, &random));
    }
}

#[test]
fn the_smallest_group_for_a_target_is_monotone_and_fails_when_out_of_reach() {
    let setup = paper();
    let postures = random_group(&setup, 40, 2);
    let pool = Pool::new(&setup, &postures, &[]).unwrap();
    let choose = |n| -> stiffid::Result<_> {
        let c = pool.best(Criterion::RelativeA, n, &PoolOptions::default())?;
        Ok(pool.postures(&c.indices))
    };
    let mut last_n = 0;
    for target in [8.0, 4.0, 3.0, 2.5, 2.0] {
        let outcome = smallest_group(&setup, target, pool.usable().len(), choose).unwrap();
        assert!(outcome.reached, "{target}%");
        let chosen = outcome.chosen().unwrap();
        let n = chosen.postures.len();
        assert_eq!(n, outcome.steps.len() + 1, "steps from 2 postures");
        assert!(chosen.worst_joint().1 <= target);
        for step in &outcome.steps[..outcome.steps.len() - 1] {
            assert!(
                step.worst_joint().1 > target,
                "{target}%: a smaller group was enough"
            );
        }
        assert!(n >= last_n, "{target}%: {n} postures < {last_n}");
        last_n = n;
    }
    assert!(
        last_n > 6,
        "2% on every joint needs more than 6 postures: {last_n}"
    );

    let out_of_reach = smallest_group(&setup, 0.01, 12, choose).unwrap();
    assert!(!out_of_reach.reached);
    assert!(out_of_reach.chosen().is_none());
    // Far out of reach: seen after two sizes (2 and 3 postures), not after all eleven.
    assert_eq!(out_of_reach.steps.len(), 2, "stopped early");
    let last = &out_of_reach.steps[1];
    let extrapolated = out_of_reach.extrapolated_pct.unwrap();
    assert_eq!(
        extrapolated,
        (last.spring_deviation_pct.iter().copied()).fold(last.worst_joint().1, f64::max)
            * (3.0f64 / 12.0).sqrt()
    );
    assert!(extrapolated > 0.01 * 1.25);
    let e = smallest_group(&setup, f64::NAN, 12, choose).unwrap_err();
    assert!(e.to_string().contains("target_pct"), "{e}");
}

#[test]
fn stopping_early_keeps_the_smallest_size_of_a_reachable_target() {
    let setup = paper();
    let postures = random_group(&setup, 40, 2);
    let pool = Pool::new(&setup, &postures, &[]).unwrap();
    let choose = |n| -> stiffid::Result<_> {
        let c = pool.best(Criterion::RelativeA, n, &PoolOptions::default())?;
        Ok(pool.postures(&c.indices))
    };
    // Every size's worst rate, without any stopping rule.
    let evaluator = Evaluator::new(&setup);
    let worst: Vec<f64> = (2..=40)
        .map(|n| {
            let e = evaluator.evaluation(&choose(n).unwrap());
            let rates =
                stiffid::internal::design::criteria::predicted_deviation_pct(&e.relative_std, 1.0);
            rates.iter().copied().fold(f64::NEG_INFINITY, f64::max)
        })
        .collect();
    // Targets reached late (near the largest size) are still found at the first size that
    // reaches them.
    for n in [30, 36, 40] {
        let target = worst[n - 2];
        let first = 2 + worst.iter().position(|&w| w <= target).unwrap();
        let outcome = smallest_group(&setup, target, 40, choose).unwrap();
        assert!(outcome.reached, "{target}%");
        assert_eq!(outcome.chosen().unwrap().postures.len(), first, "{target}%");
    }
    // Just out of reach (below the best rate of 40 postures): every size is tried; far out of
    // reach: stopped after two sizes.
    let best = worst.iter().copied().fold(f64::INFINITY, f64::min);
    let near = smallest_group(&setup, 0.95 * best, 40, choose).unwrap();
    assert!(
        !near.reached && near.steps.len() > 20,
        "{}",
        near.steps.len()
    );
    let far = smallest_group(&setup, 0.3 * best, 40, choose).unwrap();
    assert!(!far.reached);
    assert_eq!(far.steps.len(), 2);
}
