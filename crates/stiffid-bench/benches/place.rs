//! Placement of the shipped pocket (`examples/milling/pocket.nc`, 372 points, cut in aluminium)
//! on the FANUC R-2000iC/165F milling example with its identified stiffness, the guide's case:
//! the part's x, y and rotation about the base z axis over a 1500 mm x 2000 mm region, the
//! default search (a 5-value grid, 32 samples, 3 compass searches) and the reach-only search
//! beside it (the target: under 10 s on 2 cores).

use criterion::{criterion_group, criterion_main, Criterion};
use stiffid::app::place::{self, Region, Request, Work};
use stiffid::internal::machining::compensate::{Aggregate, Options};
use stiffid::internal::machining::{self, Language};
use stiffid::internal::robot::presets;

const SETUP: &str = include_str!("../../../examples/milling/fanuc-milling.toml");

fn benches(c: &mut Criterion) {
    let setup =
        stiffid::internal::setup::parse(SETUP, "fanuc-milling.toml", |n, _| presets::get(n))
            .unwrap();
    let compliance = stiffid::internal::io::stiffness::parse(include_str!(
        "../../../examples/milling/stiffness.json"
    ))
    .unwrap()
    .compliance(setup.model())
    .unwrap();
    let process = stiffid::internal::machining::process::file::parse(
        include_str!("../../../examples/milling/aluminium.toml"),
        "aluminium.toml",
    )
    .unwrap();
    let pocket = include_str!("../../../examples/milling/pocket.nc");
    let program = machining::read(pocket, Language::GCode, 1e-5).unwrap();
    let options = Options::for_setup(&setup);
    let request = Request {
        setup: &setup,
        setup_text: SETUP,
        compliance: &compliance,
        work: Work::Program {
            program: &program,
            process: &process,
        },
        options: &options,
        region: Region::from_mm_deg(
            [500.0, 2000.0, -1500.0, 500.0],
            [-180.0, 180.0],
            &[] as &[&str],
            0.4,
        )
        .unwrap(),
        objective: Aggregate::Max,
        margin: 5f64.to_radians(),
        max_condition: 1000.0,
        effort: Request::EFFORT,
    };
    let mut group = c.benchmark_group("place");
    group.sample_size(10);
    group.bench_function("the pocket, 372 points, default search", |b| {
        b.iter(|| place::run(&request).unwrap())
    });
    group.finish();
}

criterion_group!(place_bench, benches);
criterion_main!(place_bench);
