//! The gravity terms on a heavy robot: a seeded simulation of a tracker campaign on the FANUC
//! R-2000iC/165F preset (36 postures, 3 reflectors, 24 fitted and 12 held out), the truth a robot
//! of about one tonne with its joints as compliant as the preset setup's nominal stiffness, and
//! the held-out position error of each gravity model.

use super::error_model::{MeasuredIn, Observation};
use super::fit::{self, Options};
use super::gravity::{self, LinkMass};
use super::tests::{points, postures};
use super::validation;
use super::*;
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid_core::robot::presets;
use stiffid_core::{Coordinates, Robot};

/// The preset setup's nominal stiffness, N m/rad (kinematic springs).
const STIFFNESS: [f64; 6] = [861581.0, 2856011.0, 1848331.0, 279352.0, 418673.0, 277720.0];

/// The tracker's noise per coordinate, m.
const NOISE: f64 = 2.5e-5;

/// Link masses of a 165 kg payload-class arm (about 0.95 t moving, the base besides), their
/// centres placed along the links at the zero posture: the turret, the upper arm (45 % of the
/// way to the elbow), the elbow housing with its motors behind the elbow, the forearm tube, the
/// wrist and the flange with the reflector tool.
fn masses(robot: &Robot) -> [LinkMass; 6] {
    let f = robot.frames(&Vector6::zeros());
    let o = |i: usize| f.joints[i].translation.vector;
    let axis4 = f.axis_directions[3];
    let centres = [
        o(0) + Vector3::new(0.12, 0.03, -0.25),
        o(1) + 0.45 * (o(2) - o(1)) + Vector3::new(0.0, 0.08, 0.0),
        o(2) - 0.12 * axis4 + Vector3::new(0.0, 0.0, 0.05),
        o(3) - 0.55 * axis4,
        o(4) + Vector3::new(0.0, 0.0, 0.02),
        (f.flange * Point3::new(0.0, 0.01, 0.12)).coords,
    ];
    let kg = [380.0, 210.0, 170.0, 95.0, 35.0, 60.0];
    std::array::from_fn(|l| LinkMass {
        mass: kg[l],
        centre: (f.joints[l].inverse() * Point3::from(centres[l])).coords,
        ..LinkMass::default()
    })
}

/// Held-out RMS (m) over `splits` campaigns with each gravity model of `models` fitted, and the
/// RMS of the gravity deflection alone at the held-out readings.
struct Study {
    held_out: Vec<f64>,
    sag: f64,
}

fn simulate(models: &[&str], splits: u64, gravity: Option<fit::GravityPrior>) -> Study {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    let masses = masses(&robot);
    let compliance = Vector6::from_fn(|i, _| 1.0 / STIFFNESS[i]);
    let truth_gravity =
        gravity::Terms::masses(&robot, masses, Coordinates::Kinematic, compliance).unwrap();
    let truth_model = ErrorModel::new(
        &robot,
        &points(),
        MeasuredIn::Tracker,
        Geometry::Full,
        truth_gravity,
    )
    .unwrap();
    let fitted: Vec<ErrorModel> = models
        .iter()
        .map(|m| {
            let g = match *m {
                "none" => gravity::Terms::none(&robot),
                "lumped" => gravity::Terms::of(
                    &robot,
                    gravity::Gravity::Lumped,
                    Coordinates::Kinematic,
                    Vector6::zeros(),
                )
                .unwrap(),
                "lumped-links" => gravity::Terms::lumped(&robot, Coordinates::Kinematic),
                _ => gravity::Terms::masses(&robot, masses, Coordinates::Kinematic, compliance)
                    .unwrap(),
            };
            ErrorModel::new(&robot, &points(), MeasuredIn::Tracker, Geometry::Full, g).unwrap()
        })
        .collect();
    let options = Options {
        length: 1.2,
        priors: None,
        ridge: 0.0,
        gravity,
    };
    let mut sums = vec![0.0; models.len()];
    let (mut sag, mut count) = (0.0, 0usize);
    for seed in 0..splits {
        let mut rng = ChaCha8Rng::seed_from_u64(1000 + seed);
        let length = Normal::new(0.0, 1e-4).unwrap();
        let angle = Normal::new(0.0, 0.01f64.to_radians()).unwrap();
        let noise = Normal::new(0.0, NOISE).unwrap();
        // The truth: every geometric error and the points off by a tenth of a millimetre or a
        // hundredth of a degree, the joints deflected by the weight at the nominal compliances.
        let mut values = truth_model.nominal();
        for (c, p) in truth_model.parameters().iter().enumerate() {
            values[c] += match p.target {
                Target::Joint { component, .. } if component.is_angle() => angle.sample(&mut rng),
                Target::Joint { .. } | Target::Point { .. } => length.sample(&mut rng),
                _ => 0.0,
            };
        }
        let truth = Estimate {
            frame: Isometry3::new(Vector3::new(3.1, -0.9, 0.3), Vector3::new(0.02, -0.01, 2.2)),
            values,
        };
        let qs = postures(&robot, 36, 2000 + seed);
        let read = |qs: &[Vector6<f64>], rng: &mut ChaCha8Rng| -> Vec<Observation> {
            let mut obs = Vec::new();
            for (i, q) in qs.iter().enumerate() {
                for k in 0..3 {
                    let b = truth_model.positions(&truth.values, &[(*q, k)]).unwrap()[0];
                    let t = truth.frame.inverse() * Point3::from(b);
                    obs.push(Observation {
                        posture: i,
                        point: k,
                        q: *q,
                        measured: t.coords + Vector3::from_fn(|_, _| noise.sample(rng)),
                        wrench: Vector6::zeros(),
                        e: stiffid_core::robot::external::ExternalValues::NONE,
                        table: false,
                        direction: Vector6::zeros(),
                    });
                }
            }
            obs
        };
        let fit_set = read(&qs[..24], &mut rng);
        let held = read(&qs[24..], &mut rng);
        let rigid = truth_model.gravity().len();
        let mut flat = truth.values.clone();
        flat.rows_mut(truth_model.gravity_start(), rigid).fill(0.0);
        for (q, k) in held.iter().map(|o| (o.q, o.point)) {
            let with = truth_model.positions(&truth.values, &[(q, k)]).unwrap()[0];
            let without = truth_model.positions(&flat, &[(q, k)]).unwrap()[0];
            sag += (with - without).norm_squared();
            count += 1;
        }
        for (m, model) in fitted.iter().enumerate() {
            let start = fit::start(model, &fit_set).unwrap();
            let f = fit::fit(model, &fit_set, &start, &options).unwrap();
            let v = validation::validate(model, &f.estimate, &held).unwrap();
            sums[m] += v.rms * v.rms;
        }
    }
    Study {
        held_out: sums.iter().map(|s| (s / splits as f64).sqrt()).collect(),
        sag: (sag / count as f64).sqrt(),
    }
}

/// On a heavy robot the gravity terms pay off held out: the three bodies' lumped terms (unknown
/// masses) cut the geometry-only error by more than a third, as the known masses do, to near the
/// tracker's noise; the per-link lumped terms (30 products from 72 readings) do worse.
#[test]
fn heavy_robot_gravity_terms_cut_held_out_error() {
    let models = ["none", "lumped", "lumped-links", "masses"];
    let s = simulate(&models, 20, None);
    for (m, e) in models.iter().zip(&s.held_out) {
        eprintln!("gravity {m}: held-out RMS {:.4} mm", e * 1e3);
    }
    eprintln!("deflection under the weight: RMS {:.4} mm", s.sag * 1e3);
    let [none, lumped, links, masses] = s.held_out[..] else {
        unreachable!()
    };
    assert!(lumped < none * 2.0 / 3.0, "{lumped} vs {none}");
    assert!(masses < none * 2.0 / 3.0, "{masses} vs {none}");
    assert!(lumped < links, "{lumped} vs {links}");
    // Near the tracker's noise (3D RMS sqrt(3) sigma): known masses within 25 %, the three
    // bodies' terms within 50 %.
    let noise = 3f64.sqrt() * NOISE;
    assert!(masses < 1.25 * noise, "{masses}");
    assert!(lumped < 1.5 * noise, "{lumped}");
}

/// The bound on the gravity terms (as `calibrate` fits them: its default, weighed against the
/// tracker's noise, `fit::Options::for_campaign`) leaves what a campaign over the joint ranges determines: every model predicts
/// the held-out readings as it does without it, within 2 %.
#[test]
fn the_bound_leaves_determined_gravity_terms() {
    let models = ["none", "lumped", "lumped-links", "masses"];
    let prior = Options::for_campaign(1.2, None, NOISE, None)
        .gravity
        .unwrap();
    let (free, bound) = (
        simulate(&models, 5, None),
        simulate(&models, 5, Some(prior)),
    );
    for ((m, a), b) in models.iter().zip(&free.held_out).zip(&bound.held_out) {
        eprintln!(
            "gravity {m}: held-out RMS {:.5} mm free, {:.5} mm bound",
            a * 1e3,
            b * 1e3
        );
        assert!((b - a).abs() < 0.02 * a, "{m}: {b} against {a}");
    }
}

/// The postures the bound and the spread are taken over fill the joint limits: every one inside,
/// each axis's range covered to 1 % of its ends, an unbounded axis over one turn.
#[test]
fn the_spanning_postures_fill_the_joint_limits() {
    use stiffid_core::common::limits::JointBox;
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    let mut limits = *robot.limits();
    limits.lower[5] = f64::NEG_INFINITY;
    let qs = gravity::spanning(&limits);
    assert_eq!(qs.len(), 512);
    // The unbounded axis spans one turn about 0, the others their limits.
    let pi = std::f64::consts::PI;
    let mut turn = JointBox::new(limits.lower, limits.upper);
    (turn.lower[5], turn.upper[5]) = (-pi, pi);
    for axis in 0..6 {
        let (lo, hi) = (turn.lower[axis], turn.upper[axis]);
        let seen = |f: fn(f64, f64) -> f64, from: f64| qs.iter().map(|q| q[axis]).fold(from, f);
        let (min, max) = (
            seen(f64::min, f64::INFINITY),
            seen(f64::max, f64::NEG_INFINITY),
        );
        assert!(
            min >= lo && max <= hi,
            "axis {axis}: {min}..{max} in {lo}..{hi}"
        );
        assert!(
            min - lo < 0.01 * (hi - lo) && hi - max < 0.01 * (hi - lo),
            "axis {axis}"
        );
    }
}
