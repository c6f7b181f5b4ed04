//! Prediction over a model with virtual springs: the Cartesian compliance and a tool point's
//! deflection against `J K^-1 J^T` built by hand from the augmented Jacobian, the deflection's
//! covariance, the compensation's loaded pose, validation, and the stiffness file that carries
//! every parameter.

use approx::assert_relative_eq;
use nalgebra::{DMatrix, DVector, Matrix6, Vector3, Vector6};
use stiffid::internal::design::random_group;
use stiffid::internal::identify::compare::document::fit_doc;
use stiffid::internal::identify::svd::fit;
use stiffid::internal::io::stiffness;
use stiffid::internal::machining::compensate;
use stiffid::internal::model::{Compliance, Family, Kind};
use stiffid::internal::observation::deflection::Points;
use stiffid::internal::observation::{posture_block, Measurement, Observations};
use stiffid::internal::robot::ik::tool_pose;
use stiffid::internal::setup::Setup;
use stiffid::internal::{identify::validate, observation::cartesian};

/// The paper's cell with an elbow tilt spring (about x of joint 3's frame, 4e6 Nm/rad) and a
/// tool translation along the flange y axis (2e4 N/mm).
fn extended() -> Setup {
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let robot = paper.robot();
    let mut springs = Family::Tilt
        .springs(robot, &[3], Some(4e6), None, "test")
        .unwrap();
    springs.truncate(1);
    let tool = Family::Tool
        .springs(robot, &[], None, Some(2e7), "test")
        .unwrap();
    springs.extend(tool.into_iter().filter(|s| s.name == "tool_y"));
    paper
        .to_builder()
        .with_tcp(paper.tool().tcp)
        .with_virtual_springs(springs)
        .build()
        .unwrap()
}

/// The augmented Jacobian of a tool point (flange frame, m), built by hand: the drive columns,
/// then each spring's axis and point carried from its link frame into the base frame, `[u x (p -
/// o); u]` or `[u; 0]`.
fn jacobian_by_hand(s: &Setup, q: &Vector6<f64>, point: &Vector3<f64>) -> DMatrix<f64> {
    let frames = s.robot().frames(q);
    let n = s.model().len();
    let mut j = DMatrix::zeros(6, n);
    let drives = frames.jacobian(point, s.springs());
    j.view_mut((0, 0), (6, 6)).copy_from(&drives);
    let p = frames.flange * nalgebra::Point3::from(*point);
    for (k, spring) in s.model().springs().iter().enumerate() {
        let frame = match spring.link {
            0 => &frames.base,
            k => &frames.joints[k - 1],
        };
        let u = frame.rotation * spring.axis.into_inner();
        let o = frame * nalgebra::Point3::from(spring.point);
        let (v, w) = match spring.kind {
            Kind::Rotation => (u.cross(&(p - o)), u),
            Kind::Translation => (u, Vector3::zeros()),
        };
        j.view_mut((0, 6 + k), (3, 1)).copy_from(&v);
        j.view_mut((3, 6 + k), (3, 1)).copy_from(&w);
    }
    j
}

#[test]
fn cartesian_compliance_over_the_model_is_j_k_inverse_j_transposed_by_hand() {
    let s = extended();
    let h = s.model_compliance("test").unwrap().h;
    assert_eq!(h.len(), 8);
    let tcp = s.tool().tcp;
    for q in s.test_postures() {
        let frames = s.robot().frames(q);
        let j = jacobian_by_hand(&s, q, &tcp);
        let by_hand = &j * DMatrix::from_diagonal(&h) * j.transpose();
        let c = cartesian::compliance(s.arm(), &frames, &tcp, &h);
        let scale = by_hand.amax();
        for r in 0..6 {
            for col in 0..6 {
                assert!(
                    (c[(r, col)] - by_hand[(r, col)]).abs() <= 1e-12 * scale,
                    "C[{r},{col}]: {} vs {}",
                    c[(r, col)],
                    by_hand[(r, col)]
                );
            }
        }
        // The springs add compliance: C_x minus the drives' part is sum_s c_s J_s J_s^T.
        let drives = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
        let hd = h.rows(0, 6).into_owned();
        let c_drives = cartesian::compliance(drives.arm(), &frames, &tcp, &hd);
        let springs = j.columns(6, 2)
            * DMatrix::from_diagonal(&h.rows(6, 2).into_owned())
            * j.columns(6, 2).transpose();
        let extra = c - c_drives;
        for r in 0..6 {
            for col in 0..6 {
                assert!((extra[(r, col)] - springs[(r, col)]).abs() <= 1e-12 * scale);
            }
        }
        let kx = cartesian::stiffness(s.arm(), &frames, &tcp, &h).unwrap();
        assert_relative_eq!(kx * c, Matrix6::identity(), epsilon = 1e-8);
    }
}

/// At a wrist singularity (q5 = 0) `K_x` of the drives is no number (`None`), not the rounding
/// error an inverse returns there (entries of 1e68 N/m); 0.05 rad away it is the inverse of
/// `C_x`.
#[test]
fn the_cartesian_stiffness_at_a_wrist_singularity_is_none() {
    let drives = stiffid::internal::setup::builtin("fanuc-r2000ic-165f").unwrap();
    let h = drives.model_compliance("test").unwrap().h;
    let tcp = drives.tool().tcp;
    let singular = Vector6::new(0.0, 10f64.to_radians(), -10f64.to_radians(), 0.0, 0.0, 0.0);
    let frames = drives.robot().frames(&singular);
    assert!(cartesian::stiffness(drives.arm(), &frames, &tcp, &h).is_none());
    let near = drives
        .robot()
        .frames(&Vector6::new(0.0, 0.17, -0.17, 0.0, 0.05, 0.0));
    let kx = cartesian::stiffness(drives.arm(), &near, &tcp, &h).unwrap();
    let c = cartesian::compliance(drives.arm(), &near, &tcp, &h);
    assert_relative_eq!(kx * c, Matrix6::identity(), epsilon = 1e-6);
}

#[test]
fn a_tool_point_deflection_and_its_covariance_over_the_model_match_the_hand_built_jacobians() {
    let s = extended();
    let h = s.model_compliance("test").unwrap().h;
    let q = s.test_postures()[1];
    let frames = s.robot().frames(&q);
    let (a, b) = (s.tool().loading_point, s.tool().tcp);
    let w = Vector6::new(150.0, -80.0, -200.0, 10.0, 5.0, -3.0);
    let d = Points {
        arm: s.arm(),
        frames: &frames,
        loaded: &a,
        observed: &b,
    }
    .deflection(&w, &h);
    let (ja, jb) = (jacobian_by_hand(&s, &q, &a), jacobian_by_hand(&s, &q, &b));
    let wd = DVector::from_column_slice(w.as_slice());
    let tau = ja.transpose() * &wd;
    let expected = &jb * tau.component_mul(&h);
    for r in 0..6 {
        assert!(
            (d.displacement[r] - expected[r]).abs() <= 1e-12 * expected.amax(),
            "{r}: {} vs {}",
            d.displacement[r],
            expected[r]
        );
    }
    assert_relative_eq!(d.torques, tau, max_relative = 1e-12);
    // The covariance is exactly J_b diag(tau) Cov(h) diag(tau) J_b^T: a correlated Cov(h).
    let sd = h.map(|v| 0.05 * v);
    let mut cov = DMatrix::from_diagonal(&sd.component_mul(&sd));
    cov[(2, 6)] = 0.5 * sd[2] * sd[6];
    cov[(6, 2)] = cov[(2, 6)];
    let a_mat = &jb * DMatrix::from_diagonal(&tau);
    let by_hand = &a_mat * &cov * a_mat.transpose();
    let got = d.covariance(&cov);
    for r in 0..6 {
        for c in 0..6 {
            assert!((got[(r, c)] - by_hand[(r, c)]).abs() <= 1e-12 * by_hand.amax());
        }
    }
}

/// The compensation's loaded pose moves the TCP by the model's deflection (to second order), and
/// the compensated posture under load reaches the nominal pose.
#[test]
fn compensation_uses_the_virtual_springs() {
    let s = extended();
    let s = s
        .to_builder()
        .with_loading_point(s.tool().tcp)
        .build()
        .unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let model = compensate::Model::new(s.arm(), &compliance).unwrap();
    let q = s.test_postures()[0];
    let frames = s.robot().frames(&q);
    let tcp = s.tool().tcp;
    let w = Vector6::new(0.0, 300.0, -200.0, 0.0, 0.0, 0.0);
    let loaded = model.loaded_pose(&q, &w);
    let unloaded = tool_pose(&frames, &tcp);
    let moved = loaded.translation.vector - unloaded.translation.vector;
    let c = cartesian::compliance(s.arm(), &frames, &tcp, &compliance.h) * w;
    let first_order = c.fixed_rows::<3>(0).into_owned();
    assert!(
        (moved - first_order).norm() < 1e-3 * first_order.norm(),
        "{moved} vs {first_order}"
    );
    // The springs' share is visible: without them the TCP moves measurably less or otherwise.
    let drives = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let drives = drives.to_builder().with_loading_point(tcp).build().unwrap();
    let hd = Compliance::drives(compliance.drives_h(), None);
    let without = compensate::Model::new(drives.arm(), &hd)
        .unwrap()
        .loaded_pose(&q, &w);
    let spring_share = (loaded.translation.vector - without.translation.vector).norm();
    assert!(spring_share > 0.01 * first_order.norm(), "{spring_share}");
    let newton = model.compensate(&q, &w).unwrap();
    let (qc, residual) = (newton.q, newton.residual_position);
    let reached = model.loaded_pose(&qc, &w);
    assert!(
        (reached.translation.vector - unloaded.translation.vector).norm() < 1e-7,
        "{residual}"
    );
    // A drives-only compliance does not fit the extended model.
    assert!(compensate::Model::new(s.arm(), &hd).is_err());
}

fn noise_free(s: &Setup, h: &DVector<f64>, postures: usize, seed: u64) -> Vec<Measurement> {
    let mut out = Vec::new();
    for (posture, q) in random_group(s, postures, seed).into_iter().enumerate() {
        let frames = s.robot().frames(&q);
        let wrench = s.rope_wrench(&frames);
        let d = posture_block(s.arm(), &frames, &wrench) * h;
        for point in 0..s.tool().measuring_points.len() {
            out.push(Measurement {
                posture,
                point,
                q,
                e: Default::default(),
                wrench,
                displacement: d.fixed_rows::<3>(3 * point).into_owned(),
            });
        }
    }
    out
}

/// A model fit's document is a stiffness file: read back, it gives the fit's compliance and
/// covariance over every parameter, validates the data it came from to the noise-free zero, and
/// is refused by the setup of the drives alone, naming the parameters.
#[test]
fn the_stiffness_file_carries_every_parameter_of_the_model() {
    let s = extended();
    let truth = s.model_compliance("test").unwrap().h;
    let mut data = noise_free(&s, &truth, 10, 3);
    // A little structure in the residuals so that the covariance is not zero.
    for (i, m) in data.iter_mut().enumerate() {
        m.displacement.x += 1e-6 * ((i % 7) as f64 - 3.0);
    }
    let obs = Observations::from_measurements(s.arm(), &data).unwrap();
    let f = fit(&obs, &s.model().parameters()).unwrap();
    let text = serde_json::to_string(&fit_doc(&f, s.noise().displacement_variance())).unwrap();
    let file = stiffness::parse(&text).unwrap();
    let c = file.compliance(s.model()).unwrap();
    for j in 0..8 {
        assert!((c.h[j] / f.compliance[j] - 1.0).abs() < 1e-12, "{j}");
    }
    let cov = c.covariance.clone().unwrap();
    let expected = f.covariance.unwrap();
    assert!((cov - &expected).amax() <= 1e-15 * expected.amax());
    // The covariance's diagonal gives the intervals the fit reports.
    let se = expected[(6, 6)].sqrt();
    let interval = f.intervals[6].unwrap();
    assert!((se / interval.compliance_std_error - 1.0).abs() < 1e-12);
    // Validation with the truth on noise-free data is exact; with the file, near the noise added.
    let exact = validate::compare(
        s.arm(),
        &Compliance {
            h: truth,
            covariance: None,
            prediction: None,
            own_weight: None,
            region: Default::default(),
            model_form: None,
        },
        &noise_free(&s, &s.model_compliance("t").unwrap().h, 4, 9),
    )
    .unwrap();
    assert!(exact.rms < 1e-12, "{}", exact.rms);
    let v = validate::compare(s.arm(), &c, &data).unwrap();
    assert!(v.rms < 1e-5, "{}", v.rms);
    let drives = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let e = file.compliance(drives.model()).unwrap_err().to_string();
    assert!(
        e.contains("8 parameters") && e.contains("tilt3_x, tool_y"),
        "{e}"
    );
}

/// The compensate document names every parameter of the model with its kind, unit and the
/// stiffness used, as the stiffness file does: 1/h in Nm/rad for the drives and the rotational
/// spring, in N/mm for the translational one.
#[test]
fn the_compensate_document_lists_every_parameter_of_the_model() {
    use stiffid::app::compensate::{run, Input, Request};
    let s = extended();
    let compliance = s.model_compliance("test").unwrap();
    let h = compliance.h.clone();
    let text =
        "q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n\n10,20,-80,5,30,0,100,0,-500\n";
    let request = Request {
        names: Default::default(),
        setup: &s,
        compliance,
        input: Input::Path {
            name: "path.csv".into(),
            text,
            frame: stiffid::internal::observation::deflection::Frame::Base,
        },
        options: compensate::Options::for_setup(&s),
    };
    let report = run(request, |_, _, _, _| Ok::<(), stiffid::Error>(())).unwrap();
    let doc = report.document();
    let json = serde_json::to_value(&doc).unwrap();
    let parameters = json["parameters"].as_array().unwrap();
    let names: Vec<&str> = parameters
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["k1", "k2", "k3", "k4", "k5", "k6", "tilt3_x", "tool_y"]
    );
    for (j, p) in parameters.iter().enumerate() {
        let (kind, unit, per_si) = match j {
            0..6 => ("drive", "Nm/rad", 1.0),
            6 => ("rotation", "Nm/rad", 1.0),
            _ => ("translation", "N/mm", 1e-3),
        };
        assert_eq!(
            (p["kind"].as_str(), p["unit"].as_str()),
            (Some(kind), Some(unit))
        );
        let k = p["stiffness"].as_f64().unwrap();
        assert_relative_eq!(k, per_si / h[j], max_relative = 1e-12);
    }
    assert_relative_eq!(
        parameters[6]["stiffness"].as_f64().unwrap(),
        4e6,
        max_relative = 1e-12
    );
    assert_relative_eq!(
        parameters[7]["stiffness"].as_f64().unwrap(),
        2e4,
        max_relative = 1e-12
    );
}
