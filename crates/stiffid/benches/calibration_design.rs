//! Design for calibration: one evaluation of the calibration criteria (O1, O3, O4, O5,
//! D-optimality and the predicted error at 20 test postures) of 12 postures x 3 measuring points
//! on the FANUC R-2000iC/165F preset with full geometry and lumped gravity terms (55 kept
//! parameters), without a gradient.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::design::calibration::CalibrationDesign;
use stiffid::metrology::calibration::error_model::MeasuredIn;
use stiffid::metrology::calibration::{gravity, ErrorModel, Geometry};
use stiffid::robot::presets;
use stiffid::study::calibration::postures;

fn bench(c: &mut Criterion) {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    let points = [
        Vector3::new(0.15, 0.0, 0.25),
        Vector3::new(-0.1, 0.12, 0.3),
        Vector3::new(0.0, -0.14, 0.2),
    ];
    let g = gravity::Model::lumped(&robot, stiffid::Coordinates::Axis);
    let model = ErrorModel::new(&robot, &points, MeasuredIn::Tracker, Geometry::Full, g).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let reference = postures(&robot, 60, &mut rng);
    let test = postures(&robot, 20, &mut rng);
    let group = postures(&robot, 12, &mut rng);
    let design = CalibrationDesign::new(model, 1.0, &reference, &test, 5e-5).unwrap();
    assert_eq!(design.kept().len(), 55);
    c.bench_function("calibration criteria 12 postures 55 parameters", |b| {
        b.iter(|| design.evaluate(&group).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
