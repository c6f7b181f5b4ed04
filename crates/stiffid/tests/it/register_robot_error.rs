//! A registration from the nominal robot: its stated standard deviations hold the robot model's
//! own error (`[robot_accuracy]`), checked against registrations of simulated true robots whose
//! frames are off by the stated amounts.

use crate::common::{paper_with, PAPER_CELL};
use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::app::register::{run, Request};
use stiffid::internal::design::registration::{design, Options};
use stiffid::Setup;

/// The tracker frame in the base frame.
fn truth() -> Isometry3<f64> {
    Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.01, -0.02, 2.4))
}

/// Registration readings of the true robot: every frame of the model (joints 1-6, the flange)
/// turned by a finite rotation about its nominal origin and shifted, base frame first.
fn readings(setup: &Setup, postures: &[Vector6<f64>], rng: &mut ChaCha8Rng, sd: f64) -> String {
    let (sd_p, sd_r) = (
        Normal::new(0.0, 3e-4).unwrap(),
        Normal::new(0.0, 3e-4).unwrap(),
    );
    let errors: Vec<(Vector3<f64>, Vector3<f64>)> = (0..7)
        .map(|_| {
            let p = Vector3::from_fn(|_, _| sd_p.sample(rng));
            (p, Vector3::from_fn(|_, _| sd_r.sample(rng)))
        })
        .collect();
    let noise = Normal::new(0.0, sd).unwrap();
    let mut text = String::from(
        "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm\n",
    );
    for (i, q) in postures.iter().enumerate() {
        let frames = setup.robot().frames(q);
        let origins: Vec<Vector3<f64>> = (frames.joints.iter().chain([&frames.flange]))
            .map(|f| f.translation.vector)
            .collect();
        for (k, p) in setup.tool().measuring_points.iter().enumerate() {
            let mut b = frames.point(p);
            for (o, (shift, turn)) in origins.iter().zip(&errors).rev() {
                b = o + UnitQuaternion::from_scaled_axis(*turn) * (b - o) + shift;
            }
            let t = (truth().inverse() * Point3::from(b)).coords * 1e3;
            let t = t + Vector3::from_fn(|_, _| noise.sample(rng) * 1e3);
            let deg: Vec<String> = q.iter().map(|a| format!("{:?}", a.to_degrees())).collect();
            text += &format!(
                "R{i},{},{},{:?},{:?},{:?}\n",
                k + 1,
                deg.join(","),
                t.x,
                t.y,
                t.z
            );
        }
    }
    text
}

/// Over 300 simulated true robots, the transform's six errors fall within 1.96 stated standard
/// deviations 92-98 % of the time; with the robot model taken as exact (the tracker noise alone)
/// under a third of the time.
#[test]
fn the_stated_deviation_covers_the_robots_own_error() {
    let exact = "[robot_accuracy]\nframe_sd_mm = 0.0\nframe_sd_mrad = 0.0\n";
    let nominal = paper_with(PAPER_CELL).unwrap();
    let taken_exact = paper_with(&format!("{PAPER_CELL}{exact}")).unwrap();
    let postures = design(&nominal, 5, &Options::default()).unwrap().postures;
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let (mut covered, mut covered_exact, mut total) = (0, 0, 0);
    for _ in 0..300 {
        let text = readings(&nominal, &postures, &mut rng, nominal.noise().reading_sd());
        let fit = |setup: &Setup| {
            let request = Request {
                setup_name: "setup".into(),
                setup,
                name: "r.csv".into(),
                text: &text,
                force: false,
            };
            run(&request).unwrap().report.registration
        };
        for (setup, count) in [(&nominal, &mut covered), (&taken_exact, &mut covered_exact)] {
            let r = fit(setup);
            let dp = r.base_from_tracker.translation.vector - truth().translation.vector;
            let dr = (r.base_from_tracker.rotation * truth().rotation.inverse()).scaled_axis();
            let std = r.std();
            let x = [dp.x, dp.y, dp.z, dr.x, dr.y, dr.z];
            *count += (0..6).filter(|&k| x[k].abs() < 1.96 * std[k]).count();
        }
        total += 6;
    }
    let share = |n: usize| n as f64 / total as f64;
    assert!((0.92..0.98).contains(&share(covered)), "{}", share(covered));
    assert!(share(covered_exact) < 0.33, "{}", share(covered_exact));
}
