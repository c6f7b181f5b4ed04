//! Loaded readings in the calibration: the compliances of the setup's stiffness model (drives and
//! virtual springs) fitted with the geometry and the gravity terms from the raw readings.

use super::error_model::{MeasuredIn, Observation, Target};
use super::fit::{self, Options};
use super::gravity;
use super::identifiability;
use super::tests::{masses, matches_central_differences, postures, tracker};
use super::*;
use nalgebra::{DVector, Isometry3, Point3, Vector6};
use stiffid_core::Setup;

/// The FANUC R-2000iC/165F preset setup (kinematic springs, the published nominal stiffness)
/// read at three measuring points, with the springs `springs` added to its model.
fn setup(springs: &str) -> Setup {
    let text = stiffid_core::setup::builtin_text("fanuc-r2000ic-165f")
        .unwrap()
        .replace(
        "measuring_points_mm = [[6.9, 245.3, 319.3]]",
        "measuring_points_mm = [[6.9, 245.3, 319.3], [150.0, 0.0, 250.0], [-100.0, 120.0, 300.0]]",
    ) + springs;
    stiffid_core::setup::parse(&text, "loaded.toml", |r, _| {
        stiffid_core::robot::presets::get(r)
    })
    .unwrap()
}

/// A rotational virtual spring in the forearm, about an axis across it.
const SPRING: &str = r#"
[[model.spring]]
name = "forearm_tilt"
kind = "rotation"
link = 3
axis = [1, 0, 0]
point_mm = [0, 0, 0]
nominal_stiffness_nm_per_rad = 4e6
"#;

/// Full geometry, the gravity model `g`, the compliances of `setup`'s model under the loads.
fn model(setup: &Setup, g: gravity::Terms) -> ErrorModel {
    let robot = setup.robot();
    ErrorModel::new(
        robot,
        &setup.tool().measuring_points,
        MeasuredIn::Tracker,
        Geometry::Full,
        g,
    )
    .unwrap()
    .with_loads(setup)
    .unwrap()
}

/// Every point of every posture unloaded and under two wrenches (base frame, at the loading
/// point), read by a tracker at `truth.frame` from the robot `truth.values`, noise-free.
fn readings(model: &ErrorModel, truth: &Estimate, qs: &[Vector6<f64>]) -> Vec<Observation> {
    let mut obs = Vec::new();
    for (i, q) in qs.iter().enumerate() {
        let s = 1.0 + 0.1 * (i % 5) as f64;
        let wrenches = [
            Vector6::zeros(),
            Vector6::new(800.0, -300.0, -1200.0, 0.0, 0.0, 0.0) * s,
            Vector6::new(-500.0, 900.0, 400.0, 50.0, -80.0, 30.0) * s,
        ];
        for wrench in wrenches {
            for point in 0..model.points() {
                obs.push(Observation {
                    posture: i,
                    point,
                    q: *q,
                    measured: nalgebra::Vector3::zeros(),
                    wrench,
                    e: stiffid_core::robot::external::ExternalValues::NONE,
                    table: false,
                    direction: Vector6::zeros(),
                });
            }
        }
    }
    let b = model.predict(&truth.values, &obs).unwrap();
    for (o, b) in obs.iter_mut().zip(b) {
        o.measured = (truth.frame.inverse() * Point3::from(b)).coords;
    }
    obs
}

/// The true values: 0.5 mm and 0.5 mrad on the joint errors (signs alternating), the gravity
/// terms `gravity` (SI), every compliance 1.25 times (odd) or 0.8 times (even) its nominal; with
/// `only`, those parameters alone.
fn truth(model: &ErrorModel, gravity: f64, only: Option<&[usize]>) -> DVector<f64> {
    let mut x = model.nominal();
    for (c, p) in model.parameters().iter().enumerate() {
        if only.is_some_and(|o| !o.contains(&c)) {
            continue;
        }
        let sign = if c % 2 == 0 { 1.0 } else { -1.0 };
        match p.target {
            Target::Joint { .. } => x[c] += 5e-4 * sign,
            Target::Gravity(gravity::Term::Lumped { .. }) => x[c] = gravity * sign,
            Target::Gravity(_) | Target::Compliance { .. } => {
                x[c] *= if c % 2 == 0 { 0.8 } else { 1.25 }
            }
            _ => {}
        }
    }
    x
}

/// Fits the readings of a robot with errors (gravity terms `gravity`) in every identifiable
/// parameter and checks each but the frame's (re-centred) to 1e-9 relative, and that every
/// compliance under the loads is identified; returns the fit.
fn recovers(model: &ErrorModel, gravity: f64, qs: &[Vector6<f64>]) -> fit::Fit {
    let options = Options {
        length: 1.2,
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    let nominal = Estimate {
        frame: Isometry3::identity(),
        values: model.nominal(),
    };
    let probe = readings(model, &nominal, qs);
    let scales = model.column_scales_of(options.length, &probe);
    let priorities: Vec<u8> = model.parameters().iter().map(|p| p.priority).collect();
    let j = model.jacobian_of(&nominal.values, &probe).unwrap();
    let kept = identifiability::analyse(&j, &scales, &priorities)
        .unwrap()
        .identified;
    let x = truth(model, gravity, Some(&kept));
    let truth = Estimate {
        frame: tracker(),
        values: x.clone(),
    };
    let data = readings(model, &truth, qs);
    let start = fit::start(model, &data).unwrap();
    let result = fit::fit(model, &data, &start, &options).unwrap();
    assert!(result.rms < 1e-11, "rms {}", result.rms);
    let identified = &result.identifiability.identified;
    for &c in model.compliance_columns().unwrap() {
        assert!(
            identified.contains(&c),
            "{} merged",
            model.parameters()[c].name
        );
    }
    for &c in identified {
        let p = &model.parameters()[c];
        if matches!(p.target, Target::Frame(_)) {
            continue;
        }
        let (got, want) = (result.estimate.values[c], x[c]);
        // A length or angle that is zero: relative to a micrometre or microradian, as the
        // other recovery tests.
        let floor = match p.target {
            Target::Compliance { .. } | Target::Gravity(_) => 0.0,
            _ => 1e-6,
        };
        let size = (want - p.nominal).abs().max(want.abs()).max(floor);
        assert!(
            (got - want).abs() <= 1e-9 * size,
            "{}: {got:e} vs {want:e}",
            p.name
        );
    }
    result
}

/// The compliances' columns are the observation rows, the frame's rotation turns the deflected
/// point: the identification Jacobian of loaded readings against central differences.
#[test]
fn loaded_jacobian_matches_central_differences() {
    let setup = setup(SPRING);
    let robot = setup.robot();
    for g in [
        gravity::Terms::of(
            robot,
            gravity::Gravity::Lumped,
            setup.springs(),
            Vector6::zeros(),
        )
        .unwrap(),
        gravity::Terms::masses(
            robot,
            masses(),
            setup.springs(),
            setup.nominal_compliance().unwrap(),
        )
        .unwrap(),
    ] {
        let model = model(&setup, g);
        let mut x = truth(&model, 2e-6, None);
        x.rows_mut(0, 6).fill(0.0);
        let truth = Estimate {
            frame: Isometry3::identity(),
            values: x.clone(),
        };
        let obs = readings(&model, &truth, &postures(robot, 3, 9));
        let j = model.jacobian_of(&x, &obs).unwrap();
        matches_central_differences(&model, &x, &j, |v| model.predict(v, &obs).unwrap());
    }
}

/// Geometry, the three bodies' lumped gravity terms and the six drive compliances from one
/// noise-free campaign with loads on the FANUC preset.
#[test]
fn geometry_gravity_and_drive_compliances_recovered() {
    let setup = setup("");
    let g = gravity::Terms::of(
        setup.robot(),
        gravity::Gravity::Lumped,
        setup.springs(),
        Vector6::zeros(),
    )
    .unwrap();
    let model = model(&setup, g);
    let fit = recovers(&model, 5e-5, &postures(setup.robot(), 30, 4));
    let names: Vec<&str> = (model.compliance_columns().unwrap().iter())
        .map(|&c| model.parameters()[c].name.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "compliance.k1",
            "compliance.k2",
            "compliance.k3",
            "compliance.k4",
            "compliance.k5",
            "compliance.k6"
        ]
    );
    assert!(fit.sd.iter().flatten().all(|s| s.is_finite()));
}

/// With known masses a drive's compliance is one parameter under gravity and under the loads;
/// the virtual spring's compliance comes from the loads: all recovered with the geometry.
#[test]
fn known_masses_and_a_virtual_spring_recovered() {
    let setup = setup(SPRING);
    let g = gravity::Terms::masses(
        setup.robot(),
        masses(),
        setup.springs(),
        setup.nominal_compliance().unwrap(),
    )
    .unwrap();
    let model = model(&setup, g);
    let columns = model.compliance_columns().unwrap();
    assert_eq!(
        columns[..6],
        (0..6)
            .map(|j| model.gravity_start() + j)
            .collect::<Vec<_>>()[..]
    );
    assert_eq!(
        model.parameters()[columns[6]].name,
        "compliance.forearm_tilt"
    );
    assert_eq!(model.parameters()[columns[6]].unit(), "urad/(N m)");
    recovers(&model, 0.0, &postures(setup.robot(), 30, 5));
}
