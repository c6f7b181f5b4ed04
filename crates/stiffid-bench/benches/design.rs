//! Posture design: one evaluation of each criterion (6 postures x 4 measuring points), one
//! evaluation with its exact gradient, local searches from a fixed seeded start group (exact and
//! finite-difference gradients), the default global search (and against the group size: 6, 12,
//! 24, 60 postures), and the best 6 of a pool of 1000
//! postures (`select --pool`: building the pool and the exchange), on the paper setup.

use criterion::{criterion_group, criterion_main, Criterion as Bench};
use std::hint::black_box;
use stiffid::internal::design::{
    self, Criterion, Evaluator, Gradient, Pool, PoolOptions, SearchOptions,
};

fn evaluation(c: &mut Bench) {
    let setup = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let group = design::random_group(&setup, 6, 1);
    let evaluator = Evaluator::new(&setup);
    for criterion in Criterion::ALL {
        c.bench_function(&format!("design/evaluate/{criterion}/6x4"), |b| {
            b.iter(|| evaluator.value(criterion, black_box(&group)))
        });
    }
    for criterion in Criterion::ALL {
        c.bench_function(&format!("design/gradient/{criterion}/6x4"), |b| {
            b.iter(|| evaluator.value_and_gradient(criterion, black_box(&group)))
        });
    }
    c.bench_function("design/evaluate/all/6x4", |b| {
        b.iter(|| design::evaluate(&setup, black_box(&group)))
    });
}

fn search(c: &mut Bench) {
    let setup = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let start = design::random_group(&setup, 6, 1);
    let options = SearchOptions::default();
    let mut g = c.benchmark_group("design/search");
    g.sample_size(10);
    g.bench_function("local/zhang2021", |b| {
        b.iter(|| design::local(&setup, Criterion::Zhang2021, black_box(&start), &options).unwrap())
    });
    g.bench_function("local/relative-a", |b| {
        b.iter(|| design::local(&setup, Criterion::RelativeA, black_box(&start), &options).unwrap())
    });
    let fd = SearchOptions {
        gradient: Gradient::FiniteDifference,
        ..options.clone()
    };
    g.bench_function("local-fd/zhang2021", |b| {
        b.iter(|| design::local(&setup, Criterion::Zhang2021, black_box(&start), &fd).unwrap())
    });
    g.bench_function("global/relative-a/default", |b| {
        b.iter(|| design::global(&setup, Criterion::RelativeA, 6, &options, &()).unwrap())
    });
    g.bench_function("global-fd/relative-a/default", |b| {
        b.iter(|| design::global(&setup, Criterion::RelativeA, 6, &fd, &()).unwrap())
    });
    // Every start run to convergence (no screening): what the screening saves.
    let every_start = SearchOptions {
        screen_steps: 0,
        ..options.clone()
    };
    g.bench_function("global-every-start/relative-a/default", |b| {
        b.iter(|| design::global(&setup, Criterion::RelativeA, 6, &every_start, &()).unwrap())
    });
    // The default global search against the group size (6 is `global/relative-a/default`: the
    // default runs our SQP on `relative-a`; SLSQP's cost grows about 10-fold per doubling:
    // docs/performance.md, "Large groups").
    for n in [12, 24, 60] {
        g.bench_function(format!("global/relative-a/default/{n}"), |b| {
            b.iter(|| design::global(&setup, Criterion::RelativeA, n, &options, &()).unwrap())
        });
    }
    g.finish();
}

fn pool(c: &mut Bench) {
    let setup = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let postures = design::random_group(&setup, 1000, 1);
    let options = PoolOptions::default();
    let mut g = c.benchmark_group("design/pool");
    g.sample_size(10);
    g.bench_function("relative-a/1000/6", |b| {
        b.iter(|| {
            let pool = Pool::new(&setup, black_box(&postures), &[]).unwrap();
            pool.best(Criterion::RelativeA, 6, &options).unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, evaluation, search, pool);
criterion_main!(benches);
