//! The cell: the exact feasibility check of one posture, one point of a constrained search, a
//! local search and the default constrained global search (`relative-a`, 6 postures, with each
//! SQP), on the paper
//! setup with a floor at z = 0, 50 mm clearance,
//! default radii and a tracker at (3000, -2000, 1500) mm; capsule against mesh bodies per
//! evaluation on a generated robot with collision meshes (`tests/support/mesh_robot.rs`).

#[path = "../../stiffid/tests/support/mesh_robot.rs"]
mod mesh_robot;

use criterion::{criterion_group, criterion_main, Criterion as Bench};
use std::hint::black_box;
use stiffid::internal::cell::Checker;
use stiffid::internal::design::{self, Criterion, SearchOptions, Solver};

/// The paper setup in the guide's cell (docs/guide.md, "The cell").
fn paper_cell() -> stiffid::Setup {
    let text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap().to_string()
        + "\n[cell]\nfloor_z_mm = 0.0\nclearance_mm = 50.0\n[tracker]\nposition_mm = [3000.0, -2000.0, 1500.0]\n";
    stiffid::internal::setup::parse(&text, "cell.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap()
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
        b.iter(|| {
            stiffid::internal::cell::capsules(setup.arm(), &setup.robot().frames(black_box(&q)))
        })
    });
    let group = design::random_group(&setup, 6, 1);
    let evaluator = design::Evaluator::new(&setup);
    // One constrained evaluation with its exact gradient, as a search point needs it: the
    // criterion with its gradient, and the cell's constraints of every posture with theirs; and a
    // local search stopped after its first point (that point, plus building the checker and the
    // final exact check).
    c.bench_function(
        "cell/evaluate/relative-a-and-constraints-with-gradients/6",
        |b| {
            b.iter(|| {
                let g = evaluator.value_and_gradient(Criterion::RelativeA, black_box(&group));
                let c: Vec<_> = group
                    .iter()
                    .map(|q| design::search::cell_constraints(&checker, q))
                    .collect();
                (g, c)
            })
        },
    );
    let first = SearchOptions {
        max_evals: 1,
        solver: Solver::ActiveSet,
        ..SearchOptions::default()
    };
    c.bench_function("cell/evaluate/search-first-point/6", |b| {
        b.iter(|| design::local(&setup, Criterion::RelativeA, black_box(&group), &first).unwrap())
    });
}

/// The mesh robot's cell setup with its hulls (48-sided prisms: 96 hull vertices a link).
fn mesh_cell() -> stiffid::Setup {
    use std::path::Path;
    let files: std::collections::HashMap<_, _> = mesh_robot::files(48)
        .into_iter()
        .map(|(p, b)| (Path::new("pkg").join(p), b))
        .collect();
    let text = |p: &Path| {
        Some(Ok::<_, stiffid::Error>(
            String::from_utf8(files.get(p)?.clone()).unwrap(),
        ))
    };
    let bytes = |p: &Path| files.get(p).cloned().map(Ok);
    let meshes = stiffid::internal::setup::reference::Meshes {
        read: &bytes,
        package_paths: &[],
    };
    let toml = mesh_robot::setup_toml();
    stiffid::internal::setup::reference::setup_text_with_meshes(
        &toml,
        "pkg/cell.toml",
        Path::new("pkg"),
        text,
        &meshes,
    )
    .unwrap()
}

/// One posture's margins (what a constrained search evaluates: the broad phase on) and its exact
/// feasibility, with the robot's hulls and with its default capsules, at 16 postures.
fn bodies(c: &mut Bench) {
    let hulls = mesh_cell();
    let radii = hulls.geometry().link_radii;
    let capsules = hulls.to_builder().with_link_radii(radii).build().unwrap();
    let postures = design::random_group(&hulls, 16, 3);
    for (name, setup) in [("capsules", &capsules), ("hulls", &hulls)] {
        let checker = Checker::new(setup);
        c.bench_function(&format!("cell/bodies/margins/{name}/16-postures"), |b| {
            b.iter(|| {
                postures
                    .iter()
                    .map(|q| checker.margins(black_box(q)).len())
                    .sum::<usize>()
            })
        });
        c.bench_function(
            &format!("cell/bodies/feasibility/{name}/16-postures"),
            |b| {
                b.iter(|| {
                    postures
                        .iter()
                        .filter(|q| checker.feasibility(black_box(q)).feasible())
                        .count()
                })
            },
        );
    }
}

/// The default constrained global search in the guide's cell (`examples/cell/zhang2021-tracker.toml`)
/// with each SQP.
fn search(c: &mut Bench) {
    let setup = paper_cell();
    let mut g = c.benchmark_group("cell/search");
    g.sample_size(10);
    for solver in Solver::CONCRETE {
        let options = SearchOptions {
            solver,
            ..SearchOptions::default()
        };
        g.bench_function(format!("global/relative-a/{solver}"), |b| {
            b.iter(|| design::global(&setup, Criterion::RelativeA, 6, &options, &|_| {}).unwrap())
        });
        // A local search from a seeded group: its time over its evaluations (135 with ours,
        // 1161 with SLSQP) is what one point of a constrained search costs, everything included
        // (the criterion and the constraints with their exact gradients, the QP, the line search).
        let start = design::random_group(&setup, 6, 1);
        g.bench_function(format!("local/relative-a/{solver}"), |b| {
            b.iter(|| design::local(&setup, Criterion::RelativeA, &start, &options).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, feasibility, bodies, search);
criterion_main!(benches);
