//! Identification at size: a measurement CSV of 1e5 rows, each its own posture with its own label
//! (the FANUC R-2000iC/165F rows cycled with shifted axis angles, as `bench/large_measurements.py`
//! writes them), identified with statistics by `identify::streamed::least_squares`: read once in
//! chunks (parsed in parallel), `Psi` (3e5 x 6) reduced by QR in blocks, never whole. Linear in
//! the rows: the 1e6-row target (under 1 s on 2 cores, issue 14) is 10x this. Peak memory is
//! measured on the command line (`/usr/bin/time -v`, docs/performance.md).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use stiffid::internal::identify::streamed;
use stiffid::internal::setup;

const FANUC: &str = include_str!("../../../examples/data/fanuc-r2000ic-165f/measurements.csv");

/// `rows` rows of the FANUC file cycled, row `i` labelled `p{i}` with its angles shifted by
/// `1e-4 (i / 43)` deg.
fn large_file(rows: usize) -> String {
    let mut lines = FANUC.lines();
    let header = lines.next().unwrap();
    let data: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let mut text = String::with_capacity(rows * 120);
    text += header;
    text.push('\n');
    for i in 0..rows {
        let src = &data[i % data.len()];
        let shift = 1e-4 * (i / data.len()) as f64;
        let q: Vec<String> = src[2..8]
            .iter()
            .map(|v| format!("{:.4}", v.parse::<f64>().unwrap() + shift))
            .collect();
        text += &format!("p{i},{},{},{}\n", src[1], q.join(","), src[8..].join(","));
    }
    text
}

fn bench(c: &mut Criterion) {
    let setup = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let text = large_file(100_000);
    let mut group = c.benchmark_group("identify_large");
    group.sample_size(10);
    group.bench_function(
        "1e5 rows, 1e5 postures: read once, Psi in blocks, identify",
        |b| b.iter(|| streamed::least_squares(&setup, black_box(text.as_bytes())).unwrap()),
    );
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
