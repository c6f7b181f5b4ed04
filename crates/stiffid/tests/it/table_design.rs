//! The positioner's angles in a calibration design: `select --for calibration` on a cell with a
//! tilt-rotate positioner and reflectors on its table chooses, with the arm's postures, the
//! positioner's angles at which each posture also reads the table. A noise-free campaign at
//! the designed postures and angles recovers every identifiable parameter of the arm and the
//! positioner; at 0.02 mm of noise the designed angles beat as many random ones, by the
//! design's criterion and by the held-out error of the calibrated cell.

use nalgebra::{DVector, Isometry3, Point3, Translation3, UnitQuaternion, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::app::purpose::{self, CalibrationOptions, Purpose};
use stiffid::app::select::{self, Method, Request};
use stiffid::internal::design::observability::{CalibrationCriterion, CalibrationDesign, Placed};
use stiffid::internal::design::{Criterion, SearchOptions};
use stiffid::internal::metrology::calibration::error_model::{Observation, Target};
use stiffid::internal::metrology::calibration::fit::{self, Options};
use stiffid::internal::metrology::calibration::validation::validate;
use stiffid::internal::metrology::calibration::{ErrorModel, Estimate};
use stiffid::internal::robot::external::ExternalValues;
use stiffid::Setup;

/// A KUKA KR 210 on a fixed base, a tilt-rotate positioner beside it with three reflectors on
/// its table, the tracker in front of both.
pub(crate) const SETUP: &str = r#"
name = "table"
robot = "kuka-kr210-robond"
[[external_axis]]
name = "tilt"
role = "positioner"
direction = [1.0, 0.0, 0.0]
point_mm = [1800.0, 1500.0, 700.0]
limits_deg = [-95.0, 95.0]
[[external_axis]]
name = "rotate"
role = "positioner"
direction = [0.0, 0.0, 1.0]
point_mm = [1800.0, 1500.0, 900.0]
limits_deg = [-180.0, 180.0]
[tool]
loading_point_mm = [100, 0, 250]
measuring_points_mm = [[100, 0, 250], [-100, 0, 250], [0, 100, 250]]
[loading]
load_n = 500.0
anchor_mm = [2500, -1500, 0]
[noise]
reading_sd_mm = 0.02
level_multiples = [1.0]
[bounds]
lower_deg = [-120, -45, -150, -180, -110, -180]
upper_deg = [120, 60, 40, 180, 110, 180]
[test]
postures_deg = [[0, 30, 0, 0, 60, 0], [40, 10, -30, 20, 50, 10]]
[workpiece]
base_from_part = { xyz_mm = [1800, 1500, 900], rpy_deg = [0, 0, 0] }
reflectors_mm = [[300, 0, 40], [-200, 250, 40], [-100, -300, 60]]
"#;

/// Postures in the campaign (each reads the tool's three points and the table's three
/// reflectors).
const POSTURES: usize = 16;

/// The tracker's noise per coordinate, m.
const NOISE: f64 = 2e-5;

fn setup() -> Setup {
    stiffid::internal::setup::parse(SETUP, "table.toml", |name, _| {
        stiffid::internal::robot::presets::get(name)
    })
    .unwrap()
}

fn options() -> CalibrationOptions {
    CalibrationOptions::default()
}

/// The designed campaign: postures and where each is read.
pub(crate) fn designed(setup: &Setup) -> (select::Report, Vec<Placed>) {
    let report = select::run(&Request {
        setup,
        criterion: Criterion::RelativeA,
        purpose: Purpose::Calibration,
        calibration: options(),
        method: Method::Local,
        start: None,
        pool: None,
        postures: POSTURES,
        target_pct: None,
        options: SearchOptions {
            max_evals: 200,
            ..SearchOptions::default()
        },
        restarts: None,
        distinct: None,
        for_candidates: false,
        candidates: None,
        stations: vec![ExternalValues::new(&[0.0, 0.0]).unwrap()],
        progress: &(),
        out: None,
        report_dir: None,
    })
    .unwrap();
    let placed = (report.postures.iter().copied())
        .zip(report.placed.iter().copied())
        .collect();
    (report.report, placed)
}

/// Every tool point and every table reflector at each of `placed`.
fn campaign(model: &ErrorModel, placed: &[Placed]) -> Vec<Observation> {
    let mut out = Vec::new();
    for (i, (q, e)) in placed.iter().enumerate() {
        let read = |point, table| Observation {
            posture: i,
            point,
            q: *q,
            measured: Vector3::zeros(),
            wrench: Vector6::zeros(),
            e: *e,
            table,
            direction: Vector6::zeros(),
        };
        out.extend((0..model.points()).map(|k| read(k, false)));
        out.extend((0..model.tables()).map(|k| read(k, true)));
    }
    out
}

/// `observations` read on the true cell `truth` with noise `sigma` per coordinate (m).
fn read(
    model: &ErrorModel,
    truth: &Estimate,
    mut observations: Vec<Observation>,
    sigma: f64,
    rng: &mut ChaCha8Rng,
) -> Vec<Observation> {
    let normal = rand_distr::Normal::new(0.0, sigma.max(1e-300)).unwrap();
    let b = model.predict(&truth.values, &observations).unwrap();
    for (o, b) in observations.iter_mut().zip(b) {
        let noise = Vector3::from_fn(|_, _| match sigma > 0.0 {
            true => rng.sample(normal),
            false => 0.0,
        });
        o.measured = (truth.frame.inverse() * Point3::from(b)).coords + noise;
    }
    observations
}

/// The tracker's pose in the cell.
fn tracker() -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(1.5, -3.0, 1.2),
        UnitQuaternion::from_euler_angles(0.01, -0.02, 0.7),
    )
}

/// The true cell: the design's nominal values with each of `only` moved by a typical error
/// (1 mm or 1 mrad; the table's reflectors by 5 mm).
fn truth(design: &CalibrationDesign, only: &[usize], seed: u64) -> Estimate {
    let model = design.model();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut x = nominal(design);
    for &c in only.iter().filter(|&&c| c >= 6) {
        let size = match model.parameters()[c].target {
            Target::Table { .. } => 5e-3,
            _ => 1e-3,
        };
        x[c] += size * (2.0 * rng.random::<f64>() - 1.0);
    }
    Estimate {
        frame: tracker(),
        values: x,
    }
}

/// The model's nominal values with the table's reflectors where the setup puts them.
fn nominal(design: &CalibrationDesign) -> DVector<f64> {
    let model = design.model();
    let reflectors = setup().table_reflectors();
    let mut x = model.nominal();
    for (c, p) in model.parameters().iter().enumerate() {
        if let Target::Table { point, axis } = p.target {
            x[c] = reflectors[point][axis];
        }
    }
    x
}

fn fit_options() -> Options {
    Options {
        length: 1.0,
        priors: None,
        ridge: 0.0,
        gravity: None,
    }
}

fn fitted(model: &ErrorModel, data: &[Observation]) -> fit::Fit {
    let start = fit::start(model, data).unwrap();
    fit::fit(model, data, &start, &fit_options()).unwrap()
}

fn names(model: &ErrorModel, of: &[usize]) -> Vec<String> {
    of.iter()
        .map(|&c| model.parameters()[c].name.clone())
        .collect()
}

/// The designed campaign carries the positioner's angles; a noise-free campaign at them
/// recovers every identified parameter (arm, positioner, reflectors) to 1e-9 relative, and the
/// identifiability QR says what merges: the angular offsets into the reflectors' positions.
#[test]
fn designed_angles_recover_the_positioner_and_the_arm() {
    let setup = setup();
    let (report, placed) = designed(&setup);
    assert_eq!(report.placed.len(), POSTURES);
    let travel = [95f64.to_radians(), 180f64.to_radians()];
    for e in &report.placed {
        for (v, t) in e.as_slice().iter().zip(travel) {
            assert!(v.abs() < t, "{v} outside the travel");
        }
    }
    // The angles differ from posture to posture: the design spreads them.
    let first = report.placed[0];
    assert!(report.placed.iter().any(|e| *e != first));
    let design = purpose::design(&setup, &options()).unwrap();
    let model = design.model();
    assert_eq!(model.tables(), 3);
    let probe = read(
        model,
        &truth(&design, &[], 1),
        campaign(model, &placed),
        0.0,
        &mut ChaCha8Rng::seed_from_u64(1),
    );
    let identified = fitted(model, &probe).identifiability.identified;
    let truth = truth(&design, &identified, 5);
    let data = read(
        model,
        &truth,
        campaign(model, &placed),
        0.0,
        &mut ChaCha8Rng::seed_from_u64(2),
    );
    let result = fitted(model, &data);
    assert!(result.rms < 1e-11, "rms {}", result.rms);
    for &c in identified.iter().filter(|&&c| c >= 6) {
        let p = &model.parameters()[c];
        let (got, want) = (result.estimate.values[c], truth.values[c]);
        let size = (want - p.nominal).abs().max(want.abs()).max(1e-6);
        assert!(
            (got - want).abs() <= 1e-9 * size,
            "{}: {got:e} vs {want:e}",
            p.name
        );
    }
    let kept = names(model, &identified);
    for axis in ["tilt", "rotate"] {
        for p in ["location.y", "location.z", "direction.ry", "direction.rz"] {
            let name = format!("{axis}.{p}");
            assert!(kept.contains(&name), "{name} not in {kept:?}");
        }
    }
    let merged = &result.identifiability.merged;
    let merged_names = names(
        model,
        &merged.iter().map(|m| m.parameter).collect::<Vec<_>>(),
    );
    eprintln!("merged: {merged_names:?}");
    let at = merged_names
        .iter()
        .position(|n| n == "rotate.offset")
        .unwrap();
    let into = names(
        model,
        &merged[at].into.iter().map(|(c, _)| *c).collect::<Vec<_>>(),
    );
    eprintln!("rotate.offset merges into {into:?}");
    assert!(into.iter().any(|n| n.starts_with("table")), "{into:?}");
}

/// At 0.02 mm of noise, the designed angles beat as many random angles within the travel (the
/// same arm postures): the design's predicted error, and the held-out error of the calibrated
/// cell at the table's reflectors (40 random angles), over ten noise draws. Measured: see the
/// CHANGELOG.
#[test]
fn designed_angles_beat_random_angles() {
    let setup = setup();
    let (_, placed) = designed(&setup);
    let design = purpose::design(&setup, &options()).unwrap();
    let model = design.model();
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let random_angle = |rng: &mut ChaCha8Rng| {
        let tilt = (2.0 * rng.random::<f64>() - 1.0) * 95f64.to_radians();
        let turn = (2.0 * rng.random::<f64>() - 1.0) * 180f64.to_radians();
        ExternalValues::new(&[tilt, turn]).unwrap()
    };
    let random: Vec<Placed> = placed
        .iter()
        .map(|(q, _)| (*q, random_angle(&mut rng)))
        .collect();
    let criterion = CalibrationCriterion::TestPose;
    let value = |p: &[Placed]| {
        let angles: Vec<ExternalValues> = p.iter().map(|p| p.1).collect();
        design
            .with_table_angles(&angles)
            .unwrap()
            .value_placed(criterion, p)
    };
    let (designed_value, random_value) = (value(&placed), value(&random));
    let probe = read(
        model,
        &truth(&design, &[], 1),
        campaign(model, &placed),
        0.0,
        &mut rng,
    );
    let identified = fitted(model, &probe).identifiability.identified;
    let truth = truth(&design, &identified, 7);
    // Held out: the table's reflectors at 40 random angles (points of the part where the
    // positioner puts them). Each campaign is read with the same noise draws (the arm's readings
    // alike), over ten draws.
    let held_q = stiffid::internal::design::random_group(&setup, 40, 11);
    let held: Vec<Placed> = held_q
        .iter()
        .map(|q| (*q, random_angle(&mut rng)))
        .collect();
    let held: Vec<Observation> = (read(model, &truth, campaign(model, &held), NOISE, &mut rng))
        .into_iter()
        .filter(|o| o.table)
        .collect();
    let held_out = |p: &[Placed]| {
        let draws: Vec<f64> = (0..10)
            .map(|draw| {
                let mut noise = ChaCha8Rng::seed_from_u64(100 + draw);
                let data = read(model, &truth, campaign(model, p), NOISE, &mut noise);
                let result = fitted(model, &data);
                validate(model, &result.estimate, &held).unwrap().rms
            })
            .collect();
        draws.iter().map(|r| r * r).sum::<f64>().sqrt() / (draws.len() as f64).sqrt()
    };
    let (designed_rms, random_rms) = (held_out(&placed), held_out(&random));
    eprintln!(
        "predicted: designed {:.4} mm, random {:.4} mm; held out on the table: designed {:.4} mm, random {:.4} mm",
        designed_value * 1e3,
        random_value * 1e3,
        designed_rms * 1e3,
        random_rms * 1e3
    );
    assert!(designed_value < random_value);
    assert!(designed_rms < random_rms);
}

/// Without a positioner the reflectors are on a fixed part (fixed points of the cell): the
/// setup takes them in the part's frame; without the part's frame it refuses them naming the
/// field.
#[test]
fn reflectors_without_a_positioner_are_on_a_fixed_part() {
    let without = SETUP
        .split("[tool]")
        .enumerate()
        .map(|(i, part)| match i {
            0 => "name = \"table\"\nrobot = \"kuka-kr210-robond\"\n".to_string(),
            _ => format!("[tool]{part}"),
        })
        .collect::<String>();
    let parse = |text: &str| {
        stiffid::internal::setup::parse(text, "table.toml", |name, _| {
            stiffid::internal::robot::presets::get(name)
        })
    };
    let setup = parse(&without).unwrap();
    let first = setup.table_reflectors()[0] * 1e3;
    assert!((first - nalgebra::Vector3::new(2100.0, 1500.0, 940.0)).norm() < 1e-9);
    assert_eq!(setup.table_reflectors().len(), 3);
    let unplaced = without.replace(
        "base_from_part = { xyz_mm = [1800, 1500, 900], rpy_deg = [0, 0, 0] }\n",
        "",
    );
    let e = parse(&unplaced).unwrap_err().to_string();
    assert!(e.contains("workpiece.reflectors_mm"), "{e}");
    assert!(e.contains("give [workpiece] base_from_part"), "{e}");
}
