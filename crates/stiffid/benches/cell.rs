//! The cell: the exact feasibility check of one posture, and the default constrained global
//! search (`relative-a`, 6 postures), on the paper setup with a floor at z = 0, 50 mm clearance,
//! default radii and a tracker at (3000, -2000, 1500) mm.

use criterion::{criterion_group, criterion_main, Criterion as Bench};
use std::hint::black_box;
use stiffid::cell::Checker;
use stiffid::design::{self, Criterion, SearchOptions};

/// The paper setup in the guide's cell (docs/guide.md, "The cell").
fn paper_cell() -> stiffid::Setup {
    let text = stiffid::setup::builtin_text("zhang2021-comau-nj165").unwrap().to_string()
        + "\n[cell]\nfloor_z_mm = 0.0\nclearance_mm = 50.0\n[tracker]\nposition_mm = [3000.0, -2000.0, 1500.0]\n";
    stiffid::setup::parse(&text, "cell.toml", |r, _| stiffid::robot::presets::get(r)).unwrap()
}

fn feasibility(c: &mut Bench) {
    let setup = paper_cell();
    let checker = Checker::new(&setup);
    let q = design::random_group(&setup, 1, 1)[0];
    c.bench_function("cell/feasibility/one-posture", |b| {
        b.iter(|| checker.feasibility(black_box(&q)))
    });
    c.bench_function("cell/margins/one-posture", |b| {
        b.iter(|| checker.margins(black_box(&q)))
    });
    c.bench_function("cell/capsules/one-posture", |b| {
        b.iter(|| stiffid::cell::capsules(&setup, &setup.robot().frames(black_box(&q))))
    });
}

fn search(c: &mut Bench) {
    let setup = paper_cell();
    let options = SearchOptions::default();
    let mut g = c.benchmark_group("cell/search");
    g.sample_size(10);
    g.bench_function("global/relative-a/default", |b| {
        b.iter(|| design::global(&setup, Criterion::RelativeA, 6, &options, &|_| {}).unwrap())
    });
    g.finish();
}

criterion_group!(benches, feasibility, search);
criterion_main!(benches);
