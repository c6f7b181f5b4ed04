//! Cartesian stiffness, tool-point deflection and its uncertainty, inverse kinematics and path
//! compensation, checked against the forward model, finite differences and Monte Carlo.

use approx::assert_relative_eq;
use nalgebra::{
    DMatrix, DVector, Isometry3, Matrix6, Translation3, UnitQuaternion, Vector3, Vector6,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use stiffid::internal::machining::compensate::{
    self, Free, FreeRange, FreeVariables, Objective, Options, PathPoint, Target, Variable,
};
use stiffid::internal::observation::deflection::{base_wrench, Frame, Points};
use stiffid::internal::robot::ik::{self, pose_error, tool_pose};
use stiffid::internal::robot::kinematics::Coordinates;
use stiffid::internal::robot::presets;
use stiffid::{
    internal::{observation::cartesian, observation::stiffness, setup},
    Error, Setup,
};

/// Six values as a vector of any length (the compliance of the drives alone).
fn dv(h: &Vector6<f64>) -> DVector<f64> {
    DVector::from_column_slice(h.as_slice())
}

/// The TCP pose of the robot at axis angles `q` whose springs deflect by `dq` (springs'
/// coordinates): forward kinematics of the deflected joints.
fn deflected_pose(s: &Setup, q: &Vector6<f64>, dq: &Vector6<f64>) -> Isometry3<f64> {
    let q_loaded = match s.springs() {
        Coordinates::Axis => q + dq,
        Coordinates::Kinematic => {
            let map = &s.robot().axis_map();
            map.axis(&(map.kinematic(q) + dq)).unwrap()
        }
    };
    tool_pose(&s.robot().frames(&q_loaded), &s.tool().tcp)
}

/// A setup whose loading point is its TCP, so `stiffness::deflection` loads the TCP.
fn loaded_at_tcp(name: &str) -> Setup {
    let s = setup::builtin(name).unwrap();
    let tcp = s.tool().tcp;
    s.to_builder().with_loading_point(tcp).build().unwrap()
}

#[test]
fn cartesian_compliance_matches_finite_differences_of_the_forward_model() {
    for name in ["zhang2021-comau-nj165", "fanuc-r2000ic-165f"] {
        let s = loaded_at_tcp(name);
        let h = s.nominal_compliance().unwrap();
        for q in s.test_postures() {
            let frames = s.robot().frames(q);
            let c = cartesian::compliance(s.arm(), &frames, &s.tool().tcp, &dv(&h));
            let unloaded = tool_pose(&frames, &s.tool().tcp);
            for k in 0..6 {
                let eps = if k < 3 { 50.0 } else { 20.0 };
                let at = |sign: f64| {
                    let w = Vector6::from_fn(|i, _| if i == k { sign * eps } else { 0.0 });
                    let dq =
                        stiffness::deflection(s.arm(), &frames, &w, s.nominal_stiffness().unwrap())
                            .joint_deflections;
                    -pose_error(&unloaded, &deflected_pose(&s, q, &dq))
                };
                let column = (at(1.0) - at(-1.0)) / (2.0 * eps);
                for r in 0..6 {
                    let scale = c.column(k).amax();
                    assert!(
                        (column[r] - c[(r, k)]).abs() <= 1e-6 * scale,
                        "{name} C[{r},{k}]: finite difference {} vs {}",
                        column[r],
                        c[(r, k)]
                    );
                }
            }
            let kx = cartesian::stiffness(s.arm(), &frames, &s.tool().tcp, &dv(&h)).unwrap();
            assert_relative_eq!(kx * c, Matrix6::identity(), epsilon = 1e-8);
        }
    }
}

#[test]
fn a_tool_frame_wrench_is_the_base_wrench_rotated_by_the_flange() {
    let s = setup::builtin("zhang2021-comau-nj165").unwrap();
    let q = s.test_postures()[0];
    let frames = s.robot().frames(&q);
    let tool = Vector6::new(30.0, -200.0, 50.0, 4.0, 0.0, -7.0);
    let r = frames.flange.rotation;
    let f = r * Vector3::new(30.0, -200.0, 50.0);
    let m = r * Vector3::new(4.0, 0.0, -7.0);
    let rotated = Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z);
    assert_relative_eq!(
        base_wrench(&frames, &tool, Frame::Tool),
        rotated,
        epsilon = 1e-12
    );
    assert_eq!(base_wrench(&frames, &tool, Frame::Base), tool);
    // The flange z axis in the base frame is where a tool-frame fz pushes.
    let push = base_wrench(
        &frames,
        &Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0),
        Frame::Tool,
    );
    assert_relative_eq!(
        push.fixed_rows::<3>(0).into_owned(),
        frames.flange.rotation * Vector3::z(),
        epsilon = 1e-12
    );
    // A wrench at another tool point: the deflection of the TCP equals J_tcp h .* J_a^T W.
    let points = Points {
        arm: s.arm(),
        frames: &frames,
        loaded: &s.tool().loading_point,
        observed: &s.tool().tcp,
    };
    let d = points.deflection(&rotated, &dv(&s.nominal_compliance().unwrap()));
    let expected = frames.jacobian(&s.tool().tcp, s.springs())
        * stiffness::deflection(s.arm(), &frames, &rotated, s.nominal_stiffness().unwrap())
            .joint_deflections;
    assert_relative_eq!(d.displacement, expected, max_relative = 1e-12);
}

#[test]
fn covariance_propagation_agrees_with_monte_carlo() {
    let s = setup::builtin("zhang2021-comau-nj165").unwrap();
    let h = s.nominal_compliance().unwrap();
    // A correlated covariance with relative standard deviations of 2% to 12%.
    let rel = Vector6::new(0.02, 0.05, 0.03, 0.08, 0.12, 0.06);
    let sd = h.component_mul(&rel);
    let mut corr = Matrix6::identity();
    corr[(1, 2)] = 0.6;
    corr[(2, 1)] = 0.6;
    corr[(3, 5)] = -0.4;
    corr[(5, 3)] = -0.4;
    let cov = Matrix6::from_diagonal(&sd) * corr * Matrix6::from_diagonal(&sd);
    let chol = cov.cholesky().unwrap().l();
    let q = s.test_postures()[0];
    let frames = s.robot().frames(&q);
    let points = Points {
        arm: s.arm(),
        frames: &frames,
        loaded: &s.tool().loading_point,
        observed: &s.tool().tcp,
    };
    let w = Vector6::new(150.0, -80.0, -200.0, 10.0, 5.0, 0.0);
    let analytic = points
        .deflection(&w, &dv(&h))
        .std(&DMatrix::from_column_slice(6, 6, cov.as_slice()));
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let runs = 2000;
    let samples: Vec<Vector6<f64>> = (0..runs)
        .map(|_| {
            let z = Vector6::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal));
            points.deflection(&w, &dv(&(h + chol * z))).displacement
        })
        .collect();
    let mean = samples.iter().sum::<Vector6<f64>>() / runs as f64;
    for c in 0..6 {
        let var = samples
            .iter()
            .map(|d| (d[c] - mean[c]).powi(2))
            .sum::<f64>()
            / (runs - 1) as f64;
        let ratio = var.sqrt() / analytic[c];
        assert!(
            (ratio - 1.0).abs() < 0.10,
            "coordinate {c}: Monte Carlo {} vs first order {}",
            var.sqrt(),
            analytic[c]
        );
    }
}

#[test]
fn inverse_kinematics_round_trips_for_every_preset() {
    let tcp = Vector3::new(0.1, 0.05, 0.25);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for name in presets::names() {
        let robot = presets::get(name).unwrap();
        let mut iterations = 0;
        for _ in 0..40 {
            let q = Vector6::from_fn(|i, _| {
                let (lo, hi) = (
                    robot.limits().lower[i].max(-3.0),
                    robot.limits().upper[i].min(3.0),
                );
                lo + (hi - lo) * rng.random::<f64>()
            });
            let target = tool_pose(&robot.frames(&q), &tcp);
            let start = robot
                .limits()
                .clamp(&q.map(|v| v + rng.random_range(-0.3..0.3)));
            let sol = ik::solve(&robot, &tcp, &target, &start, &ik::Options::default())
                .unwrap_or_else(|e| panic!("{name}, q = {q:?}: {e}"));
            let reached = pose_error(&target, &tool_pose(&robot.frames(&sol.q), &tcp));
            assert!(reached.fixed_rows::<3>(0).norm() < 1e-9, "{name}");
            assert!(reached.fixed_rows::<3>(3).norm() < 1e-9, "{name}");
            assert!(robot.limits().contains(&sol.q), "{name}");
            iterations += sol.iterations;
        }
        assert!(
            iterations < 40 * 30,
            "{name}: {iterations} steps for 40 poses"
        );
        let far = Isometry3::translation(10.0, 0.0, 1.0);
        match ik::solve(
            &robot,
            &tcp,
            &far,
            &Vector6::zeros(),
            &ik::Options::default(),
        ) {
            Err(Error::Unreachable {
                position_error_mm, ..
            }) => assert!(position_error_mm > 5000.0, "{name}: {position_error_mm}"),
            other => panic!("{name}: {other:?}"),
        }
    }
}

/// A straight line of poses around the TCP of the setup's first test posture, 2 mm apart, with a
/// 200 N force in the tool frame.
pub(crate) fn line_path(s: &Setup, n: usize) -> Vec<PathPoint> {
    let start = tool_pose(&s.robot().frames(&s.test_postures()[0]), &s.tool().tcp);
    (0..n)
        .map(|i| {
            let shift = Translation3::new(0.002 * i as f64, -0.001 * i as f64, 0.0);
            PathPoint {
                line: i as u64 + 2,
                target: Target::Pose(shift * start),
                wrench: Vector6::new(200.0, 0.0, -100.0, 0.0, 0.0, 0.0),
                frame: Frame::Tool,
                external: stiffid::internal::robot::external::ExternalValues::NONE,
            }
        })
        .collect()
}

/// The free tool rotation within `+-range_deg` in steps of `step_deg`.
pub(crate) fn rotation(range_deg: f64, step_deg: f64) -> FreeRange {
    FreeRange::checked(&Variable::ToolRotation, range_deg, step_deg).unwrap()
}

/// The free track station within `+-range_mm` in steps of `step_mm`.
pub(crate) fn station(range_mm: f64, step_mm: f64) -> FreeRange {
    FreeRange::checked(&Variable::Station, range_mm, step_mm).unwrap()
}

/// The free positioner (its last axis) within `+-range_deg` in steps of `step_deg`.
pub(crate) fn positioner(range_deg: f64, step_deg: f64) -> FreeRange {
    FreeRange::checked(&Variable::Positioner, range_deg, step_deg).unwrap()
}

/// The options of `s` with the tool rotation free (`free`, minimising the deflection) or
/// nothing free.
pub(crate) fn options(s: &Setup, free: Option<FreeRange>) -> Options {
    Options {
        q0: s.test_postures()[0],
        ik: ik::Options::default(),
        free: FreeVariables {
            free: free.map(Free::ToolRotation).into_iter().collect(),
            minimise: Objective::Deflection,
            ..FreeVariables::default()
        },
        level: 0.95,
        max_iterations: compensate::MAX_ITERATIONS,
        force_tolerance: compensate::budget::DEFAULT_FORCE_TOLERANCE,
        max_error: None,
        feasible: compensate::Feasible::for_setup(s),
        map: false,
        map_over: compensate::MapVariable::Rotation,
        refine: 0,
    }
}

#[test]
fn a_compensated_posture_loaded_reaches_the_nominal_pose() {
    for name in ["zhang2021-comau-nj165", "fanuc-r2000ic-165f"] {
        let s = loaded_at_tcp(name);
        let compliance = s.model_compliance("test").unwrap();
        let path = line_path(&s, 25);
        let out = compensate::path(s.arm(), &compliance, &path, &options(&s, None)).unwrap();
        for (p, c) in path.iter().zip(&out) {
            let Target::Pose(nominal) = &p.target else {
                unreachable!()
            };
            let frames = s.robot().frames(&c.q_compensated);
            let dq =
                stiffness::deflection(s.arm(), &frames, &c.wrench, s.nominal_stiffness().unwrap())
                    .joint_deflections;
            let e = pose_error(nominal, &deflected_pose(&s, &c.q_compensated, &dq));
            assert!(e.fixed_rows::<3>(0).norm() < 1e-7, "{name}: {e}");
            assert!(e.fixed_rows::<3>(3).norm() < 1e-6, "{name}: {e}");
            // It compensated something: the deflection is of the order of 0.1 mm.
            assert!(c.deflection.fixed_rows::<3>(0).norm() > 1e-5, "{name}");
            assert!(c.iterations <= 6, "{name}: {} steps", c.iterations);
            assert_relative_eq!(
                c.wrench,
                base_wrench(&s.robot().frames(&c.q), &p.wrench, Frame::Tool),
                epsilon = 1e-9
            );
        }
    }
}

#[test]
fn the_free_tool_axis_never_raises_the_deflection_and_keeps_the_constraints() {
    let s = loaded_at_tcp("fanuc-r2000ic-165f");
    let compliance = s.model_compliance("test").unwrap();
    let path = line_path(&s, 30);
    let free = crate::compensate::rotation(60.0, 3.0);
    let out = compensate::path(s.arm(), &compliance, &path, &options(&s, Some(free))).unwrap();
    let norm = |d: &Vector6<f64>| d.fixed_rows::<3>(0).norm();
    let (mut before, mut after) = (0.0, 0.0);
    for (i, (p, c)) in path.iter().zip(&out).enumerate() {
        let d0 = norm(c.deflection_before.as_ref().unwrap());
        assert!(norm(&c.deflection) <= d0 * (1.0 + 1e-12), "point {i}");
        assert!(s.robot().limits().contains(&c.q), "point {i}");
        assert!(c.tool_rotation.abs() <= free.range + 1e-12);
        if i > 0 {
            let step = (c.tool_rotation - out[i - 1].tool_rotation).abs();
            assert!(step <= free.step + 1e-12, "point {i}: step {step}");
        }
        // The pose is the path's, turned about tool z.
        let Target::Pose(t) = &p.target else {
            unreachable!()
        };
        let turned = t * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), c.tool_rotation);
        let e = pose_error(&turned, &tool_pose(&s.robot().frames(&c.q), &s.tool().tcp));
        assert!(e.norm() < 1e-9, "point {i}: {e}");
        before += d0;
        after += norm(&c.deflection);
    }
    assert!(after < 0.95 * before, "{after} vs {before}");
}

/// With the TCP on the spindle (tool z) axis every angle ties: the tie-breaking cost keeps the
/// path's own angle at every point instead of turning the tool for nothing; and the grid of a tiny
/// step is refused, not allocated.
#[test]
fn the_free_tool_axis_keeps_the_path_angle_when_every_angle_ties() {
    let base = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let on_axis = Vector3::new(0.0, 0.0, 0.25);
    let s = base
        .to_builder()
        .with_tcp(on_axis)
        .with_loading_point(on_axis)
        .build()
        .unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let path = line_path(&s, 12);
    let free = crate::compensate::rotation(90.0, 2.0);
    let out = compensate::path(s.arm(), &compliance, &path, &options(&s, Some(free))).unwrap();
    for (i, c) in out.iter().enumerate() {
        assert_eq!(c.tool_rotation, 0.0, "point {i}");
    }
    for step in [1e-300, 1e-9, 1e-4] {
        let tiny = crate::compensate::rotation(90.0, step);
        let e =
            compensate::path(s.arm(), &compliance, &path, &options(&s, Some(tiny))).unwrap_err();
        assert!(e.to_string().contains("free tool-rotation step"), "{e}");
    }
}

/// The documented size of the neglected complementary stiffness: on the paper's setup, the guide's
/// `predict` example (2 mm at measuring point 1) moves by about 2 micrometres when the torques are
/// those of the deflected posture (a fixed point `dq = h .* J_f(q + dq)^T W`) instead of the
/// unloaded one.
#[test]
fn the_complementary_stiffness_is_about_a_thousandth_of_the_deflection() {
    let s = setup::builtin("zhang2021-comau-nj165").unwrap();
    let q = s.test_postures()[0];
    let w = Vector6::new(300.0, -200.0, -400.0, 0.0, 0.0, 0.0);
    let h = s.nominal_compliance().unwrap();
    let torques_at = |dq: &Vector6<f64>| {
        s.robot()
            .frames(&(q + dq))
            .jacobian(&s.tool().loading_point, s.springs())
            .tr_mul(&w)
    };
    let dq0 = torques_at(&Vector6::zeros()).component_mul(&h);
    let mut dq = dq0;
    for _ in 0..20 {
        dq = torques_at(&dq).component_mul(&h);
    }
    let p = |dq: &Vector6<f64>| {
        s.robot()
            .frames(&(q + dq))
            .point(&s.tool().measuring_points[0])
    };
    let deflection = (p(&dq0) - p(&Vector6::zeros())).norm();
    let change = (p(&dq) - p(&dq0)).norm();
    assert!((1.9e-3..2.1e-3).contains(&deflection), "{deflection}");
    assert!((0.5e-6..5e-6).contains(&change), "{change} m");
}

/// Limits of axis 2 within 1e-12 rad of the nominal posture: any compensation that moves axis 2
/// leaves them.
#[test]
fn every_point_that_cannot_be_compensated_is_named() {
    let s = loaded_at_tcp("fanuc-r2000ic-165f");
    let q = s.test_postures()[0];
    let mut limits = *s.robot().limits();
    limits.upper[1] = q[1] + 1e-12;
    limits.lower[1] = q[1] - 1e-12;
    let robot = s.robot().clone().with_limits(limits).unwrap();
    let s = s
        .to_builder()
        .with_bounds(limits)
        .with_robot(robot)
        .with_test_postures(vec![q])
        .build()
        .unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let point = |line: u64, fz: f64| PathPoint {
        line,
        target: Target::Posture(q),
        wrench: Vector6::new(fz.abs(), fz.abs(), fz, 0.0, 0.0, 0.0),
        frame: Frame::Base,
        external: stiffid::internal::robot::external::ExternalValues::NONE,
    };
    // A zero wrench needs no compensation; the others leave axis 2.
    let path = [
        point(4, -300.0),
        point(5, 0.0),
        point(6, -300.0),
        point(7, 300.0),
    ];
    match compensate::path(s.arm(), &compliance, &path, &options(&s, None)) {
        Err(Error::Column {
            line: 4,
            name,
            problem,
            ..
        }) => {
            let message = problem.to_string();
            assert_eq!(name, "q_compensated");
            assert!(message.contains("axis 2"), "{message}");
            assert!(message.ends_with("lines 6, 7"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

/// Inverse kinematics keeps the start posture's configuration or refuses naming the point: with
/// axes 4 and 6 held within +-30 deg, the pose of a posture with axis 5 at +40 deg has no solution
/// with axis 5 negative (its wrist twin turns axes 4 and 6 by 180 deg), so a path starting with
/// axis 5 at -40 deg is refused, never flipped silently; started with axis 5 positive it passes.
#[test]
fn inverse_kinematics_refuses_a_configuration_change_naming_the_point() {
    let base = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let mut limits = *base.robot().limits();
    for k in [3, 5] {
        limits.lower[k] = -30f64.to_radians();
        limits.upper[k] = 30f64.to_radians();
    }
    let robot = base.robot().clone().with_limits(limits).unwrap();
    let s = base
        .to_builder()
        .with_robot(robot)
        .with_bounds(limits)
        .with_test_postures(Vec::new())
        .with_tcp(base.tool().tcp)
        .build()
        .unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let deg = |q: [f64; 6]| Vector6::from(q).map(f64::to_radians);
    let target = tool_pose(
        &s.robot().frames(&deg([-60.0, 0.0, -20.0, 0.0, 40.0, 0.0])),
        &s.tool().tcp,
    );
    let path = vec![PathPoint {
        line: 7,
        target: Target::Pose(target),
        wrench: Vector6::zeros(),
        frame: Frame::Base,
        external: stiffid::internal::robot::external::ExternalValues::NONE,
    }];
    let mut o = Options::for_setup(&s);
    o.q0 = deg([-60.0, 0.0, -20.0, 0.0, -40.0, 0.0]);
    let e = compensate::path(s.arm(), &compliance, &path, &o)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line 7") && e.contains("another configuration") && e.contains("wrist"),
        "{e}"
    );
    o.q0 = deg([-55.0, 5.0, -25.0, 5.0, 30.0, 5.0]);
    let q = compensate::path(s.arm(), &compliance, &path, &o).unwrap()[0].q;
    assert!(q[4] > 0.0, "{q}");
}

/// The compensate document written with its points streamed from storage is, byte for byte, the
/// document holding them written whole (the rows kept in memory, as Python's are); storage that
/// ends inside a point is an error.
#[test]
fn the_streamed_compensate_document_is_the_whole_one() {
    use stiffid::app::compensate::document::values;
    use stiffid::app::compensate::stream::{Points as Stored, Rows};
    use stiffid::app::compensate::{run, Input, Request};
    use stiffid::internal::machining::dynamics::Dynamics;
    let paper = setup::builtin("zhang2021-comau-nj165").unwrap();
    let s = paper
        .to_builder()
        .with_tcp(paper.tool().tcp)
        .build()
        .unwrap();
    let q = s.test_postures();
    let mut text = String::from("q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n\n");
    for (i, q) in q.iter().take(4).enumerate() {
        let deg: Vec<String> = q.iter().map(|a| a.to_degrees().to_string()).collect();
        text += &format!("{},{},0,{}\n", deg.join(","), 50.0 * i as f64, -300.0);
    }
    let request = Request {
        names: Default::default(),
        setup: &s,
        compliance: s.model_compliance("test").unwrap(),
        input: Input::Path {
            name: "path.csv".into(),
            text: &text,
            frame: Frame::Base,
        },
        options: Options::for_setup(&s),
    };
    let mut rows = Rows::default();
    let mut stored = Stored::new(Vec::new());
    let mut report = run(
        request,
        |first, p: &[PathPoint], r: &[compensate::Compensated], d: &[Dynamics]| {
            for (k, ((p, r), d)) in p.iter().zip(r).zip(d).enumerate() {
                let v = values(first + k, p.line, r, d);
                rows.push(&v);
                stored.push(&v).unwrap();
            }
            Ok::<(), Error>(())
        },
    )
    .unwrap();
    let rows = rows.into_points();
    assert_eq!(rows.len(), q.len().min(4));
    assert!(rows.len() >= 2);
    // The report holding the rows is the whole document; without them, its head.
    let head = report.report.clone();
    report.report.points = rows;
    let whole = serde_json::to_string_pretty(&serde_json::to_value(&report.report).unwrap())
        .unwrap()
        + "\n";
    // Empty cells (no covariance: the standard deviations) are null in both.
    assert!(whole.contains("\"dx_std_mm\": null"), "{whole}");
    let bytes = stored.into_inner();
    let head = head.document();
    let mut streamed = Vec::new();
    head.write_json(&bytes[..], &mut streamed).unwrap();
    // `kind` first, then the keys in the order of the whole document's `Value`.
    let kind = "  \"kind\": \"compensate\",\n";
    let streamed = String::from_utf8(streamed).unwrap();
    assert!(streamed.starts_with(&format!("{{\n{kind}")), "{streamed}");
    assert_eq!(streamed.replacen(kind, "", 1), whole.replacen(kind, "", 1));
    let cut = head.write_json(&bytes[..bytes.len() - 3], &mut Vec::new());
    assert!(cut.unwrap_err().to_string().contains("inside a point"));
}

/// A compensation on the calibrated robot: the robot file `calibrate --out` writes (a robot TOML
/// with the fitted DH errors), loaded into the setup, reproduces the calibrated model's positions
/// to 1e-9 mm, and the compensated axis angles, deflected, bring the calibrated (true) robot's
/// TCP onto the path's nominal targets to 0.1 um; the nominal robot's compensation misses them
/// through the true robot by the geometric errors (over 0.1 mm).
#[test]
fn a_compensation_on_the_calibrated_robot_lands_on_the_target() {
    use stiffid::internal::metrology::calibration::error_model::{
        Component, MeasuredIn, Target as Moved,
    };
    use stiffid::internal::metrology::calibration::{
        gravity, robot_file, ErrorModel, Estimate, Geometry,
    };
    let s = loaded_at_tcp("fanuc-r2000ic-165f");
    let points = &s.tool().measuring_points;
    let model = ErrorModel::new(
        s.robot(),
        points,
        MeasuredIn::Base,
        Geometry::Full,
        gravity::Terms::none(s.robot()),
    )
    .unwrap();
    // Known errors in every (M)DH parameter class: up to 1 mm and 1 mrad.
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut values = model.nominal();
    for (i, p) in model.parameters().iter().enumerate() {
        if let Moved::Joint { component, .. } = p.target
            && matches!(
                component,
                Component::Theta | Component::D | Component::A | Component::Alpha
            )
        {
            values[i] += 1e-3 * (2.0 * rng.random::<f64>() - 1.0);
        }
    }
    let estimate = Estimate {
        frame: Isometry3::identity(),
        values,
    };
    let text = robot_file::robot_toml(&model, &estimate).unwrap();
    let calibrated = stiffid::internal::robot::file::parse(&text, "calibrated.toml").unwrap();
    // The robot file reproduces the calibrated positions.
    for q in s.test_postures() {
        for (k, point) in points.iter().enumerate() {
            let want = model.positions(&estimate.values, &[(*q, k)]).unwrap()[0];
            let got = calibrated.frames(q).point(point);
            assert!((want - got).norm() < 1e-12, "{}", (want - got).norm());
        }
    }
    let true_setup = s.to_builder().with_robot(calibrated).build().unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let path = line_path(&s, 10); // targets on the nominal robot's path
    let on_true =
        compensate::path(true_setup.arm(), &compliance, &path, &options(&s, None)).unwrap();
    let on_nominal = compensate::path(s.arm(), &compliance, &path, &options(&s, None)).unwrap();
    let h = s.nominal_stiffness().unwrap();
    let miss = |c: &compensate::Compensated, p: &PathPoint| {
        let Target::Pose(target) = &p.target else {
            unreachable!()
        };
        let frames = true_setup.robot().frames(&c.q_compensated);
        let dq = stiffness::deflection(true_setup.arm(), &frames, &c.wrench, h).joint_deflections;
        pose_error(target, &deflected_pose(&true_setup, &c.q_compensated, &dq))
    };
    for ((t, n), p) in on_true.iter().zip(&on_nominal).zip(&path) {
        let e = miss(t, p);
        assert!(e.fixed_rows::<3>(0).norm() < 1e-7, "{e}");
        assert!(e.fixed_rows::<3>(3).norm() < 1e-6, "{e}");
        assert!(miss(n, p).fixed_rows::<3>(0).norm() > 1e-4);
    }
}
