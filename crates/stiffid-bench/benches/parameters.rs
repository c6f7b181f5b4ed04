//! The cost of a design evaluation against the number of parameters of the model: the paper
//! setup's six drives, with an elbow tilt spring and a tool translation (8), and with the tilt
//! springs of links 1, 2, 3 and 6 (14; links 1, 2, 3 and 5, or any other four, leave
//! inseparable combinations: every group's criterion is infinite, and the bench would time the
//! rank test only); one evaluation of `relative-a` and of `zhang2021` (with
//! the singular values), and `relative-a` with its exact gradient, 6 postures x 4 measuring points;
//! and the model comparison of `stiffid identify --compare-models` on the FANUC data (43 postures,
//! the default candidate pool, 39 candidates, with the nested estimate), the job from the file's
//! text, alone and with a posture bootstrap of 20 resamples (`--bootstrap 20`).

use criterion::{criterion_group, criterion_main, Criterion as Bench};
use std::hint::black_box;
use stiffid::internal::design::{self, Criterion, Evaluator};

const EIGHT: &str = r#"
[[model.spring]]
name = "elbow_x"
kind = "rotation"
link = 3
axis = [1, 0, 0]
nominal_stiffness_nm_per_rad = 4e6

[[model.spring]]
name = "tool_y"
kind = "translation"
link = 6
axis = [0, 1, 0]
nominal_stiffness_n_per_mm = 2e4
"#;

const FOURTEEN: &str = r#"
[[model.family]]
family = "tilt"
links = [1, 2, 3, 6]
nominal_stiffness_nm_per_rad = 4e6
"#;

fn setup(model: &str) -> stiffid::internal::setup::Setup {
    let text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .to_string()
        + model;
    stiffid::internal::setup::parse(&text, "model.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap()
}

fn parameters(c: &mut Bench) {
    for model in ["", EIGHT, FOURTEEN] {
        let setup = setup(model);
        let n = setup.model().len();
        let group = design::random_group(&setup, 6, 1);
        let evaluator = Evaluator::new(&setup);
        let value = evaluator.value(Criterion::RelativeA, &group);
        assert!(
            value.is_finite(),
            "{n} parameters: the group separates them"
        );
        for criterion in [Criterion::RelativeA, Criterion::Zhang2021] {
            c.bench_function(
                &format!("design/parameters/{n}/evaluate/{criterion}"),
                |b| b.iter(|| evaluator.value(criterion, black_box(&group))),
            );
        }
        c.bench_function(&format!("design/parameters/{n}/gradient/relative-a"), |b| {
            b.iter(|| evaluator.value_and_gradient(Criterion::RelativeA, black_box(&group)))
        });
    }
}

fn compare_models(c: &mut Bench) {
    use stiffid::app::identify::{run, Options, Request};
    use stiffid::app::measurements::Data;
    let setup = stiffid::internal::setup::builtin("fanuc-r2000ic-165f").unwrap();
    let text = include_str!("../../../examples/data/fanuc-r2000ic-165f/measurements.csv");
    let job = |bootstrap| {
        run(Request {
            setup: &setup,
            setup_name: "fanuc-r2000ic-165f".into(),
            progress: &(),
            data: Data::File {
                name: "measurements.csv".into(),
                reader: black_box(text.as_bytes()),
            },
            options: Options {
                compare_models: true,
                bootstrap,
                ..Options::default()
            },
        })
        .unwrap()
    };
    let mut group = c.benchmark_group("models");
    group.sample_size(10);
    group.bench_function("compare-models/fanuc", |b| b.iter(|| job(None)));
    group.bench_function("compare-models/fanuc-bootstrap-20", |b| {
        b.iter(|| job(Some(20)))
    });
    group.finish();
}

criterion_group!(benches, parameters, compare_models);
criterion_main!(benches);
