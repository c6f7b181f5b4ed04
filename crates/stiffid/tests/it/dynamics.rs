//! The robot's mass: the mass matrix and operational-space inertia against a reference built in
//! this file from finite-differenced body Jacobians, natural frequencies against the closed form
//! of a two-link arm, the surge's energy balance, and invariance to the robot file's units.

use nalgebra::{Isometry3, Matrix3, Matrix3x6, Matrix6, Point3, Translation3, UnitQuaternion};
use nalgebra::{Vector3, Vector6};
use stiffid::internal::observation::dynamics;
use stiffid::internal::robot::dynamics::{self as mass, modes, MassModel};
use stiffid::internal::robot::LinkMass;
use stiffid::{Coordinates, Robot};

/// The symmetric tensor of `[ixx, iyy, izz, ixy, ixz, iyz]` (kg m^2), a robot file's order.
fn tensor([xx, yy, zz, xy, xz, yz]: [f64; 6]) -> Matrix3<f64> {
    Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

/// The effective mass (kg) along the unit direction `u` of a point held in the other five
/// directions: `u^T Lambda_vv u` (the reference's held mass).
pub(crate) fn held_mass(lambda: &Matrix6<f64>, u: &Vector3<f64>) -> f64 {
    (u.transpose() * lambda.fixed_view::<3, 3>(0, 0) * u)[0]
}

/// A URDF 6R arm (`tests/data/pinocchio/arm.urdf`) with turned joint origins, axes along x, y and -z, full inertia tensors in
/// turned inertial frames, and a spindle link hung from the last joint by a fixed joint.
const ARM_URDF: &str = include_str!("../data/pinocchio/arm.urdf");

/// One rigid body of the reference: its link (0-based), its pose in the link frame, mass and
/// tensor in its own frame.
struct Body {
    link: usize,
    frame: Isometry3<f64>,
    mass: f64,
    inertia: Matrix3<f64>,
}

fn pose(xyz: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(xyz[0], xyz[1], xyz[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

/// The URDF's bodies as written above (the spindle on link 6 behind the fixed joint `mount`).
fn arm_bodies() -> Vec<Body> {
    let b = |link, xyz, rpy, mass, six| Body {
        link,
        frame: pose(xyz, rpy),
        mass,
        inertia: tensor(six),
    };
    let mount = pose([0.0, 0.0, 0.05], [0.0, 0.0, 0.3]);
    let mut spindle = b(
        5,
        [0.01, 0.0, 0.12],
        [0.0, 0.2, 0.0],
        18.0,
        [0.25, 0.24, 0.06, 0.0, 0.0, 0.0],
    );
    spindle.frame = mount * spindle.frame;
    vec![
        b(
            0,
            [0.02, -0.01, 0.25],
            [0.1, 0.0, 0.2],
            180.0,
            [9.0, 8.0, 6.0, 0.4, -0.3, 0.2],
        ),
        b(
            1,
            [0.45, 0.03, 0.1],
            [0.0, 0.3, 0.0],
            120.0,
            [2.0, 14.0, 13.0, 0.1, 0.2, -0.1],
        ),
        b(
            2,
            [0.1, 0.05, 0.02],
            [0.2, -0.1, 0.4],
            70.0,
            [3.0, 2.5, 1.5, 0.0, 0.1, 0.0],
        ),
        b(
            3,
            [0.3, 0.0, 0.01],
            [0.0; 3],
            25.0,
            [0.3, 1.1, 1.0, 0.01, 0.0, 0.0],
        ),
        b(
            4,
            [0.0, 0.02, 0.0],
            [0.5, 0.0, 0.0],
            9.0,
            [0.08, 0.07, 0.05, 0.0, 0.0, 0.005],
        ),
        b(
            5,
            [0.0, 0.0, 0.01],
            [0.0; 3],
            2.0,
            [0.004, 0.004, 0.006, 0.0, 0.0, 0.0],
        ),
        spindle,
    ]
}

fn arm() -> Robot {
    stiffid::internal::robot::urdf::parse(ARM_URDF, "mass-test.urdf", Some("tool0")).unwrap()
}

/// `d f / d q_k` by central differences with one Richardson step (error O(h^4)).
fn derivative<const R: usize>(
    f: &impl Fn(&Vector6<f64>) -> nalgebra::SVector<f64, R>,
    q: &Vector6<f64>,
    k: usize,
) -> nalgebra::SVector<f64, R> {
    let central = |h: f64| {
        let e = Vector6::ith(k, h);
        (f(&(q + e)) - f(&(q - e))) / (2.0 * h)
    };
    let h = 1e-3;
    (central(h / 2.0) * 4.0 - central(h)) / 3.0
}

/// The pose of body `b` in the base frame at `q`.
fn world(robot: &Robot, b: &Body, q: &Vector6<f64>) -> Isometry3<f64> {
    robot.frames(q).joints[b.link] * b.frame
}

/// The angular velocity Jacobian of link `link` at `q`: `vee(dR/dq_k R^T)`.
fn angular(robot: &Robot, link: usize, q: &Vector6<f64>) -> Matrix3x6<f64> {
    let r = |q: &Vector6<f64>| {
        let m = robot.frames(q).joints[link]
            .rotation
            .to_rotation_matrix()
            .into_inner();
        nalgebra::SVector::<f64, 9>::from_column_slice(m.as_slice())
    };
    let r0 = robot.frames(q).joints[link]
        .rotation
        .to_rotation_matrix()
        .into_inner();
    Matrix3x6::from_fn(|i, k| {
        let d = derivative(&r, q, k);
        let w = Matrix3::from_column_slice(d.as_slice()) * r0.transpose();
        let skew = [w[(2, 1)], w[(0, 2)], w[(1, 0)]];
        skew[i]
    })
}

/// `M = sum_b m_b J_vb^T J_vb + J_wb^T R_b I_b R_b^T J_wb` from finite-differenced Jacobians.
fn reference_mass_matrix(robot: &Robot, bodies: &[Body], q: &Vector6<f64>) -> Matrix6<f64> {
    let mut m = Matrix6::zeros();
    for b in bodies {
        let centre = |q: &Vector6<f64>| world(robot, b, q).translation.vector;
        let jv = Matrix3x6::from_columns(&std::array::from_fn::<_, 6, _>(|k| {
            derivative(&centre, q, k)
        }));
        let jw = angular(robot, b.link, q);
        let r = world(robot, b, q)
            .rotation
            .to_rotation_matrix()
            .into_inner();
        m += jv.transpose() * jv * b.mass + jw.transpose() * (r * b.inertia * r.transpose()) * jw;
    }
    m
}

/// The Jacobian (rows `[v; omega]`) of the flange point `tcp` from finite differences.
fn reference_jacobian(robot: &Robot, tcp: &Vector3<f64>, q: &Vector6<f64>) -> Matrix6<f64> {
    let p = |q: &Vector6<f64>| robot.frames(q).point(tcp);
    let w = angular(robot, 5, q);
    Matrix6::from_fn(|r, k| match r < 3 {
        true => derivative(&p, q, k)[r],
        false => w[(r - 3, k)],
    })
}

fn relative(a: &Matrix6<f64>, b: &Matrix6<f64>) -> f64 {
    (a - b).amax() / b.amax()
}

/// Pinocchio's `crba` and `Lambda` of tool0 for the arm, recorded by
/// `tests/data/pinocchio/record.py` (kept beside its output).
#[test]
fn the_mass_matrix_and_lambda_of_a_urdf_arm_equal_pinocchios() {
    let text = include_str!("../data/pinocchio/reference.json");
    let reference: serde_json::Value = serde_json::from_str(text).unwrap();
    let matrix =
        |v: &serde_json::Value| Matrix6::from_fn(|r, c| v[r][c].as_f64().expect("a number"));
    let robot = arm();
    let masses = MassModel::new(&robot, None).unwrap();
    let postures = reference["postures"].as_array().unwrap();
    assert_eq!(postures.len(), 3);
    for p in postures {
        let q = Vector6::from_fn(|i, _| p["q_rad"][i].as_f64().unwrap());
        let frames = robot.frames(&q);
        let m = masses.mass_matrix(&robot, &frames, Coordinates::Axis);
        let m_ref = matrix(&p["mass_matrix"]);
        assert!(relative(&m, &m_ref) < 1e-9, "{m}\n{m_ref}");
        let tcp = Vector3::zeros();
        let lambda =
            mass::operational_inertia(&m, &frames.jacobian(&tcp, Coordinates::Axis)).unwrap();
        let lambda_ref = matrix(&p["lambda"]);
        assert!(
            relative(&lambda, &lambda_ref) < 1e-9,
            "{lambda}\n{lambda_ref}"
        );
    }
}

#[test]
fn the_mass_matrix_and_lambda_of_a_urdf_arm_equal_the_body_jacobian_sums() {
    let robot = arm();
    let masses = MassModel::new(&robot, None).unwrap();
    let bodies = arm_bodies();
    let tcp = Vector3::new(0.0, 0.0, 0.0);
    for q in [
        Vector6::new(0.3, -0.4, 0.8, 0.5, -0.9, 1.2),
        Vector6::new(-1.1, 0.2, -0.5, -2.0, 0.7, -0.3),
    ] {
        let frames = robot.frames(&q);
        let m = masses.mass_matrix(&robot, &frames, Coordinates::Axis);
        let m_ref = reference_mass_matrix(&robot, &bodies, &q);
        assert!(relative(&m, &m_ref) < 1e-9, "{m}\n{m_ref}");
        let j = reference_jacobian(&robot, &tcp, &q);
        let lambda =
            mass::operational_inertia(&m, &frames.jacobian(&tcp, Coordinates::Axis)).unwrap();
        let mobility = j * m_ref.try_inverse().unwrap() * j.transpose();
        let lambda_ref = mobility.try_inverse().unwrap();
        assert!(
            relative(&lambda, &lambda_ref) < 1e-9,
            "{lambda}\n{lambda_ref}"
        );
        // Held and free effective masses along a direction, against their definitions.
        let u = Vector3::new(0.3, -0.5, 0.8).normalize();
        let held = held_mass(&lambda, &u);
        let block = lambda_ref.fixed_view::<3, 3>(0, 0);
        assert!(((u.transpose() * block * u)[0] - held).abs() < 1e-9 * held);
        let free = mass::free_mass(&lambda, &u).unwrap();
        let free_ref = 1.0 / (u.transpose() * mobility.fixed_view::<3, 3>(0, 0) * u)[0];
        assert!((free - free_ref).abs() < 1e-9 * free_ref);
        // Holding the other five directions adds mass: the held is never below the free.
        assert!(held >= free * (1.0 - 1e-12), "held {held} free {free}");
    }
}

/// A modified-DH arm (`a`, `alpha`, `d` per joint) as a robot file in mm and as a URDF in m,
/// with the same inertials; `axis_map` appended to the robot file.
fn dh_arm(axis_map: &str) -> (Robot, Robot) {
    let rows = [
        (0.0, 0.0, 0.6),
        (0.3, -90.0, 0.0),
        (1.1, 0.0, 0.0),
        (0.2, -90.0, 1.2),
        (0.0, 90.0, 0.0),
        (0.0, -90.0, 0.2),
    ];
    let masses = [
        (200.0, [0.0, -0.05, -0.1], [10.0, 9.0, 7.0, 0.2, 0.0, 0.1]),
        (110.0, [0.5, 0.0, 0.1], [2.0, 12.0, 11.5, 0.0, 0.3, 0.0]),
        (60.0, [0.05, 0.0, 0.05], [2.0, 1.8, 1.2, 0.05, 0.0, 0.0]),
        (30.0, [0.0, 0.1, 0.0], [1.0, 0.3, 0.9, 0.0, 0.0, 0.02]),
        (8.0, [0.0, 0.0, 0.02], [0.06, 0.05, 0.04, 0.0, 0.0, 0.0]),
        (20.0, [0.0, 0.0, 0.1], [0.3, 0.3, 0.08, 0.0, 0.0, 0.0]),
    ];
    let mut toml = String::from("name = \"dh-arm\"\nconvention = \"modified-dh\"\n");
    let mut urdf = String::from("<robot name=\"dh-arm\">\n<link name=\"base\"/>\n");
    for (i, ((a, alpha, d), (m, c, six))) in rows.iter().zip(&masses).enumerate() {
        let list = |v: &[f64]| v.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>();
        let com_mm: Vec<f64> = c.iter().map(|v| v * 1e3).collect();
        toml += &format!(
            "[[joint]]\na_mm = {:?}\nalpha_deg = {alpha:?}\nd_mm = {:?}\nlower_deg = -170.0\nupper_deg = 170.0\nmass_kg = {m:?}\ncom_mm = [{}]\ninertia_kg_m2 = [{}]\n",
            a * 1e3,
            d * 1e3,
            list(&com_mm).join(", "),
            list(six).join(", ")
        );
        let al = f64::to_radians(*alpha);
        let [xx, yy, zz, xy, xz, yz] = *six;
        urdf += &format!(
            "<link name=\"l{i}\"><inertial><origin xyz=\"{} {} {}\"/><mass value=\"{m}\"/><inertia ixx=\"{xx}\" iyy=\"{yy}\" izz=\"{zz}\" ixy=\"{xy}\" ixz=\"{xz}\" iyz=\"{yz}\"/></inertial></link>\n",
            c[0], c[1], c[2]
        );
        let parent = if i == 0 {
            "base".to_string()
        } else {
            format!("l{}", i - 1)
        };
        urdf += &format!(
            "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"{parent}\"/><child link=\"l{i}\"/><origin xyz=\"{a:?} {:?} {:?}\" rpy=\"{al:?} 0 0\"/><axis xyz=\"0 0 1\"/><limit lower=\"-2.9670597283903604\" upper=\"2.9670597283903604\" effort=\"1\" velocity=\"1\"/></joint>\n",
            -d * al.sin(),
            d * al.cos()
        );
    }
    urdf += "</robot>\n";
    let from_toml =
        stiffid::internal::robot::file::parse(&(toml + axis_map), "dh-arm.toml").unwrap();
    let from_urdf = stiffid::internal::robot::urdf::parse(&urdf, "dh-arm.urdf", None).unwrap();
    (from_toml, from_urdf)
}

#[test]
fn frequencies_do_not_depend_on_the_units_of_the_robot_file() {
    let (mm, m) = dh_arm("");
    let q = Vector6::new(0.2, -0.3, 0.5, 0.7, -0.6, 0.4);
    let compliance =
        Matrix6::from_diagonal(&Vector6::new(1.0, 0.3, 0.5, 3.0, 2.5, 8.0).map(|v| v * 1e-6));
    let modes_of = |robot: &Robot| {
        let masses = MassModel::new(robot, None).unwrap();
        let mq = masses.mass_matrix(robot, &robot.frames(&q), Coordinates::Axis);
        (mq, modes::modes(&mq, &compliance).unwrap())
    };
    let ((m_mm, modes_mm), (m_m, modes_m)) = (modes_of(&mm), modes_of(&m));
    assert!(relative(&m_mm, &m_m) < 1e-12, "{m_mm}\n{m_m}");
    for (a, b) in modes_mm.frequencies.iter().zip(&modes_m.frequencies) {
        assert!((a - b).abs() < 1e-10 * b, "{a} vs {b}");
    }
    // And the robot file's bodies give the reference's mass matrix too.
    let m_ref = reference_mass_matrix(&mm, &dh_bodies(&mm), &q);
    assert!(relative(&m_mm, &m_ref) < 1e-9);
}

/// A robot's bodies as the reference takes them (one per link, at its centre, link axes).
fn dh_bodies(robot: &Robot) -> Vec<Body> {
    robot
        .masses()
        .unwrap()
        .iter()
        .enumerate()
        .map(|(link, l)| Body {
            link,
            frame: Isometry3::translation(l.centre.x, l.centre.y, l.centre.z),
            mass: l.mass,
            inertia: l.inertia,
        })
        .collect()
}

#[test]
fn the_mass_matrix_in_axis_angles_is_a_t_m_a_with_a_coupled_axis_map() {
    let map = "[axis_map]\nmatrix = [[-1,0,0,0,0,0], [0,1,0,0,0,0], [0,-1,-1,0,0,0], [0,0,0,-1,0,0], [0,0,0,0,1,0], [0,0,0,0,0,-1]]\noffset_deg = [0, -90, -90, 0, 0, 180]\n";
    let (robot, _) = dh_arm(map);
    let masses = MassModel::new(&robot, None).unwrap();
    let q = Vector6::new(0.4, 0.1, -0.2, 1.0, 0.6, -0.8);
    let frames = robot.frames(&q);
    let m = masses.mass_matrix(&robot, &frames, Coordinates::Axis);
    // The reference differentiates in axis angles: the map is in it by construction.
    let m_ref = reference_mass_matrix(&robot, &dh_bodies(&robot), &q);
    assert!(relative(&m, &m_ref) < 1e-9, "{m}\n{m_ref}");
    let a = robot.axis_map().matrix;
    let theta = masses.mass_matrix(&robot, &frames, Coordinates::Kinematic);
    assert!(relative(&(a.transpose() * theta * a), &m) < 1e-14);
}

/// A planar two-link arm inside a 6R chain (standard DH: joint 1 vertical, joints 2 and 3
/// parallel and horizontal, a spherical wrist at the tip): a point mass `m1` with an isotropic
/// tensor `j1` at the elbow, everything beyond joint 3 at the tip with isotropic tensors.
fn two_link(l1: f64, l2: f64, bodies: [(f64, f64); 6]) -> Robot {
    let rows = [
        (0.0, 90.0),
        (l1, 0.0),
        (l2, 90.0),
        (0.0, -90.0),
        (0.0, 90.0),
        (0.0, 0.0),
    ];
    let mut toml = String::from("name = \"two-link\"\nconvention = \"standard-dh\"\n");
    for ((a, alpha), (m, j)) in rows.iter().zip(bodies) {
        toml += &format!(
            "[[joint]]\na_mm = {:?}\nalpha_deg = {alpha:?}\nd_mm = 0.0\nlower_deg = -170.0\nupper_deg = 170.0\nmass_kg = {m:?}\ncom_mm = [0, 0, 0]\ninertia_kg_m2 = [{j:?}, {j:?}, {j:?}, 0, 0, 0]\n",
            a * 1e3
        );
    }
    stiffid::internal::robot::file::parse(&toml, "two-link.toml").unwrap()
}

#[test]
fn a_two_link_arm_rings_at_the_closed_form_frequencies() {
    let (l1, l2) = (1.2, 0.9);
    let bodies = [
        (50.0, 3.0),
        (40.0, 0.7),
        (25.0, 0.4),
        (6.0, 0.05),
        (4.0, 0.03),
        (3.0, 0.02),
    ];
    let robot = two_link(l1, l2, bodies);
    let masses = MassModel::new(&robot, None).unwrap();
    let (k2, k3) = (2.0e6, 0.7e6);
    // Joints 1, 4, 5 and 6 rigid (1e10 times stiffer): the two-link arm of joints 2 and 3.
    let rigid = 1.0 / (k2 * 1e10);
    let c = Matrix6::from_diagonal(&Vector6::new(
        rigid,
        1.0 / k2,
        1.0 / k3,
        rigid,
        rigid,
        rigid,
    ));
    for theta3 in [0.3_f64, 1.1, -2.0] {
        let q = Vector6::new(0.4, -0.7, theta3, 0.3, -0.4, 0.9);
        let m = masses.mass_matrix(&robot, &robot.frames(&q), Coordinates::Axis);
        let modes = modes::modes(&m, &c).unwrap();
        // Closed form: the elbow mass m1 at l1 (its tensor j1 turns with joint 2), the tip mass m2
        // at l2 past the elbow with the tip's tensor J (turning with joints 2 and 3).
        let (m1, j1) = bodies[1];
        let m2: f64 = bodies[2..].iter().map(|b| b.0).sum();
        let jt: f64 = bodies[2..].iter().map(|b| b.1).sum();
        let cos = theta3.cos();
        let m11 = j1 + m1 * l1 * l1 + m2 * (l1 * l1 + l2 * l2 + 2.0 * l1 * l2 * cos) + jt;
        let m12 = m2 * (l2 * l2 + l1 * l2 * cos) + jt;
        let m22 = m2 * l2 * l2 + jt;
        // det(K - w^2 M) = 0: det(M) x^2 - (k2 m22 + k3 m11) x + k2 k3 = 0, x = w^2.
        let (a, b, cc) = (m11 * m22 - m12 * m12, -(k2 * m22 + k3 * m11), k2 * k3);
        let root = (b * b - 4.0 * a * cc).sqrt();
        let hz = |x: f64| x.sqrt() / std::f64::consts::TAU;
        let expected = [hz((-b - root) / (2.0 * a)), hz((-b + root) / (2.0 * a))];
        for (f, e) in modes.frequencies.iter().zip(expected) {
            assert!((f - e).abs() < 1e-8 * e, "theta3 {theta3}: {f} vs {e}");
        }
        // Their shapes move joints 2 and 3 only.
        for shape in &modes.shapes[..2] {
            let others = [shape[0], shape[3], shape[4], shape[5]];
            assert!(others.iter().all(|v| v.abs() < 1e-6), "{shape}");
        }
    }
}

#[test]
fn the_surge_gives_the_held_mass_the_stored_energy() {
    let (robot, _) = dh_arm("");
    let setup = crate::common::paper_with("").unwrap();
    let setup = (setup.to_builder())
        .with_bounds(*robot.limits())
        .with_test_postures(Vec::new())
        .with_robot(robot)
        .build()
        .unwrap();
    let compliance = setup.model_compliance("test").unwrap();
    let masses = dynamics::mass_model(setup.arm()).0.unwrap();
    let q = Vector6::new(0.2, -0.3, 0.5, 0.7, -0.6, 0.4);
    let frames = setup.robot().frames(&q);
    let tcp = setup.tool().tcp;
    let posture = dynamics::posture(&masses, setup.arm(), &frames, &tcp, &compliance.h);
    let lambda = posture.operational_inertia.unwrap();
    let force = Vector3::new(100.0, -250.0, -1800.0);
    let s = dynamics::surge(
        &masses,
        setup.arm(),
        &frames,
        &tcp,
        &lambda,
        &compliance,
        &force,
    );
    let s = s.unwrap();
    assert!((0.5 * s.mass * s.speed * s.speed - s.energy).abs() < 1e-12 * s.energy);
    // c is the Cartesian compliance along the thrust, m the held mass along it.
    let cx = stiffid::internal::observation::cartesian::compliance(
        setup.arm(),
        &frames,
        &tcp,
        &compliance.h,
    );
    let u = force.normalize();
    let c = (u.transpose() * cx.fixed_view::<3, 3>(0, 0) * u)[0];
    assert!((s.compliance - c).abs() < 1e-12 * c);
    assert!((s.energy - 0.5 * force.norm_squared() * c).abs() < 1e-12 * s.energy);
    assert_eq!(s.mass, held_mass(&lambda, &u));
}

/// The mass model's uncertainty: the held mass is exactly linear in the bodies (the scaled
/// robot's held mass equals the parts' sum to 1e-9), and its standard deviation and the surge's
/// agree with 4000 seeded draws of every body's mass and inertia (10 % each, independent).
#[test]
fn the_mass_models_uncertainty_matches_draws_of_the_masses() {
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    let (robot, _) = dh_arm("");
    let spindle = stiffid::internal::setup::Payload {
        mass: 40.0,
        centre: Vector3::new(0.05, 0.0, 0.12),
        inertia: tensor([0.4, 0.4, 0.1, 0.0, 0.0, 0.0]),
    };
    let setup = crate::common::paper_with("").unwrap();
    let build = |robot: Robot, spindle: stiffid::internal::setup::Payload| {
        (setup.to_builder())
            .with_bounds(*robot.limits())
            .with_test_postures(Vec::new())
            .with_robot(robot)
            .with_payload(spindle)
            .with_mass_sd(0.1)
            .build()
            .unwrap()
    };
    let nominal = build(robot.clone(), spindle);
    let compliance = nominal.model_compliance("test").unwrap();
    let q = Vector6::new(0.2, -0.3, 0.5, 0.7, -0.6, 0.4);
    let (frames, tcp) = (nominal.robot().frames(&q), nominal.tool().tcp);
    let force = Vector3::new(100.0, -250.0, -1800.0);
    let u = force.normalize();
    let surge = |s: &stiffid::internal::setup::Setup| {
        let masses = dynamics::mass_model(s.arm()).0.unwrap();
        dynamics::tcp_surge(&masses, s.arm(), &frames, &compliance, &force).unwrap()
    };
    let at = surge(&nominal);
    let masses = dynamics::mass_model(nominal.arm()).0.unwrap();
    let w = frames
        .jacobian(&tcp, Coordinates::Axis)
        .lu()
        .solve(&Vector6::new(u.x, u.y, u.z, 0.0, 0.0, 0.0))
        .unwrap();
    let parts: Vec<f64> = (masses.parts().iter())
        .map(|p| {
            (w.transpose() * p.mass_matrix(nominal.robot(), &frames, Coordinates::Axis) * w)[0]
        })
        .collect();
    assert_eq!(parts.len(), 7);
    let links = *robot.masses().unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let (mut masses_drawn, mut speeds) = (Vec::new(), Vec::new());
    for _ in 0..4000 {
        let s: Vec<f64> = (0..7)
            .map(|_| {
                let z: f64 = StandardNormal.sample(&mut rng);
                1.0 + 0.1 * z
            })
            .collect();
        let scale = |b: &LinkMass, f: f64| LinkMass {
            mass: b.mass * f,
            centre: b.centre,
            inertia: b.inertia * f,
        };
        let drawn_links: [LinkMass; 6] = std::array::from_fn(|k| scale(&links[k], s[k]));
        let drawn_spindle = stiffid::internal::setup::Payload {
            mass: spindle.mass * s[6],
            inertia: spindle.inertia * s[6],
            ..spindle
        };
        let drawn = surge(&build(
            robot.clone().with_masses(Some(drawn_links)),
            drawn_spindle,
        ));
        let linear: f64 = at.mass + (0..7).map(|k| (s[k] - 1.0) * parts[k]).sum::<f64>();
        assert!(
            (drawn.mass - linear).abs() < 1e-9 * at.mass,
            "{} {linear}",
            drawn.mass
        );
        masses_drawn.push(drawn.mass);
        speeds.push(drawn.speed);
    }
    let sd = |v: &[f64]| {
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
    };
    let (mass_sd, speed_sd) = (at.mass_std.unwrap(), at.speed_std.unwrap());
    assert!(
        (sd(&masses_drawn) / mass_sd - 1.0).abs() < 0.05,
        "{} vs {mass_sd}",
        sd(&masses_drawn)
    );
    assert!(
        (sd(&speeds) / speed_sd - 1.0).abs() < 0.06,
        "{} vs {speed_sd}",
        sd(&speeds)
    );
    // Without a stiffness covariance the speed's uncertainty is the mass's alone.
    assert!((speed_sd - at.speed * mass_sd / (2.0 * at.mass)).abs() < 1e-12 * speed_sd);
}

/// `[masses] sd_pct` is a percentage from 0 to 100, named with its value when it is not.
#[test]
fn the_masses_sd_is_read_as_a_percentage_and_range_checked() {
    let setup = crate::common::paper_with("[masses]\nsd_pct = 12.5\n").unwrap();
    assert_eq!(setup.arm().mass_sd(), 0.125);
    for bad in ["-1.0", "100.5", "nan", "inf"] {
        let e = crate::common::paper_with(&format!("[masses]\nsd_pct = {bad}\n"));
        let e = e.unwrap_err().to_string();
        assert!(e.contains("masses.sd_pct"), "{bad}: {e}");
    }
    // The key's former spelling still reads.
    let former = crate::common::paper_with("[masses]\nsd_percent = 12.5\n").unwrap();
    assert_eq!(former.arm().mass_sd(), 0.125);
    let e = crate::common::paper_with("[masses]\nsd = 1.0\n").unwrap_err();
    assert!(e.to_string().contains("sd"), "{e}");
}

#[test]
fn placeholder_inertials_are_refused_with_the_way_to_give_them() {
    let placeholder = ARM_URDF
        .split("<mass value=\"")
        .enumerate()
        .map(|(i, part)| match i {
            0 => part.to_string(),
            _ => format!("<mass value=\"1{}", &part[part.find('"').unwrap()..]),
        })
        .collect::<String>();
    let robot =
        stiffid::internal::robot::urdf::parse(&placeholder, "p.urdf", Some("tool0")).unwrap();
    // The spindle folds into link 6: link 6 weighs 2 kg, the others 1 kg: not all equal.
    assert_eq!(robot.masses().unwrap()[5].mass, 2.0);
    let equal = robot.masses().unwrap().map(|l| LinkMass { mass: 1.0, ..l });
    let robot = robot.with_masses(Some(equal));
    let message = MassModel::new(&robot, None).unwrap_err().to_string();
    assert!(
        message.contains("placeholders") && message.contains("inertia_kg_m2"),
        "{message}"
    );
    let points = robot.masses().unwrap().map(|l| LinkMass {
        mass: l.mass + l.centre.x,
        inertia: Matrix3::zeros(),
        ..l
    });
    let message = MassModel::new(&robot.with_masses(Some(points)), None)
        .unwrap_err()
        .to_string();
    assert!(message.contains("point masses"), "{message}");
}

#[test]
fn an_inertia_tensor_no_body_has_is_an_error_naming_the_field() {
    let (robot, _) = dh_arm("");
    let _ = robot;
    let bad = "name = \"x\"\nconvention = \"modified-dh\"\n".to_string()
        + &"[[joint]]\na_mm = 100.0\nalpha_deg = 90.0\nd_mm = 0.0\nlower_deg = -170.0\nupper_deg = 170.0\nmass_kg = 5.0\ncom_mm = [0, 0, 0]\ninertia_kg_m2 = [1, 1, 3, 0, 0, 0]\n".repeat(6);
    let message = stiffid::internal::robot::file::parse(&bad, "bad.toml")
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("joint[1].inertia_kg_m2") && message.contains("triangle"),
        "{message}"
    );
    let urdf = ARM_URDF.replacen("ixx=\"9\"", "ixx=\"-9\"", 1);
    let message = stiffid::internal::robot::urdf::parse(&urdf, "bad.urdf", None)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("link 'l1'") && message.contains("inertia"),
        "{message}"
    );
}

#[test]
fn urdf_inertials_in_turned_frames_fold_into_their_link() {
    let robot = arm();
    let links = robot.masses().unwrap();
    // Link 6 holds its own body and the spindle behind the fixed joint.
    let own = LinkMass {
        mass: 2.0,
        centre: Vector3::new(0.0, 0.0, 0.01),
        inertia: tensor([0.004, 0.004, 0.006, 0.0, 0.0, 0.0]),
    };
    let b = &arm_bodies()[6];
    let spindle = LinkMass {
        mass: b.mass,
        centre: Vector3::zeros(),
        inertia: b.inertia,
    }
    .moved(&b.frame);
    let sum = own.plus(&spindle);
    assert!((links[5].inertia - sum.inertia).amax() < 1e-15);
    assert!((links[5].centre - sum.centre).amax() < 1e-15);
    let _ = Point3::<f64>::origin();
}
