//! The program lands where it should on the robot that was calibrated, proven end to end on a
//! simulated true robot: a DH robot (the COMAU preset with link masses, calibrated with the
//! masses) and a URDF robot (the same arm as a URDF without masses, calibrated with lumped
//! gravity terms), each with geometric errors in every joint, the weight of its links, joints
//! 30 % more compliant than nominal and a tracker with 0.015 mm of noise. The whole campaign
//! runs through the library's jobs (calibrate with gravity and loads, held out; compensate a
//! milled rectangle to KRL), the program's targets through a simulated controller (its nominal
//! kinematics, its inverse kinematics and configuration bits for Cartesian targets), and the
//! TCP error is measured on the true robot, in the tracker's frame (where the part is
//! registered).

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal, Uniform};
use stiffid::app::calibrate::{self, document::Document};
use stiffid::app::compensate::{self as compensate, Input};
use stiffid::internal::machining::compensate::{Compensated, Options};
use stiffid::internal::machining::program::cartesian::flags::ConfigurationData;
use stiffid::internal::machining::program::generate::{Settings, Targets};
use stiffid::internal::machining::program::krl::StatusTurn;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::metrology::calibration::error_model::{MeasuredIn, Observation, Target};
use stiffid::internal::metrology::calibration::gravity::{self, Gravity, LinkMass};
use stiffid::internal::metrology::calibration::{robot_file, ErrorModel, Estimate, Geometry};
use stiffid::internal::robot::configuration::Configuration;
use stiffid::internal::robot::ik;
use stiffid::internal::setup::{Controller, Kinematics};
use stiffid::{Robot, Setup};

/// The tracker's noise per coordinate, m.
const NOISE: f64 = 1.5e-5;

/// The setup of the campaign: the COMAU cell with a TCP 300 mm out of the flange and the
/// tracker's noise, on `robot` (a robot file's name) within `bounds` (deg).
pub(crate) fn setup_text(robot: &str, bounds: &str) -> String {
    format!(
        r#"name = "true-robot"
robot = "{robot}"
springs = "axis"
characteristic_length_mm = 1200.0
nominal_stiffness_nm_per_rad = [950000.0, 3000000.0, 900000.0, 250000.0, 200000.0, 150000.0]

[tool]
loading_point_mm = [150.0, 0.0, 200.0]
measuring_points_mm = [[80.0, 80.0, 260.0], [-80.0, 80.0, 260.0], [-80.0, -80.0, 260.0], [80.0, -80.0, 260.0]]
tcp_mm = [0.0, 0.0, 300.0]

[loading]
load_n = 500.0
anchor_mm = [2000.0, 1500.0, 0.0]

[noise]
reading_sd_mm = 0.015
level_multiples = [1.0]

{bounds}
"#
    )
}

/// Link masses of the arm (kg) with their centres in the link frames (m).
pub(crate) fn masses() -> [LinkMass; 6] {
    let kg = [250.0, 180.0, 120.0, 60.0, 20.0, 40.0];
    std::array::from_fn(|i| LinkMass {
        mass: kg[i],
        centre: Vector3::new(0.1 + 0.05 * i as f64, 0.03, -0.02 * i as f64),
        ..LinkMass::default()
    })
}

/// The COMAU preset with [`masses`] in its robot file.
pub(crate) fn dh_robot_text() -> String {
    let mut text = String::new();
    let m = masses();
    for (i, part) in include_str!("../../../stiffid-core/presets/comau-smart5-nj165-3.0.toml")
        .split("[[joint]]\n")
        .enumerate()
    {
        text += part;
        if i < 6 {
            let c = m[i].centre * 1e3;
            text += &format!(
                "[[joint]]\nmass_kg = {:?}\ncom_mm = [{:?}, {:?}, {:?}]\n",
                m[i].mass, c.x, c.y, c.z
            );
        }
    }
    text
}

/// One robot's campaign.
pub(crate) struct Case {
    /// The nominal setup.
    pub(crate) setup: Setup,
    /// The gravity model the calibration fits.
    pub(crate) gravity: Gravity,
    /// Axis angles of the robot from the preset's axis angles (the URDF takes the kinematic
    /// angles).
    pub(crate) angles: fn(&Vector6<f64>) -> Vector6<f64>,
}

pub(crate) fn preset_angles(q: &Vector6<f64>) -> Vector6<f64> {
    *q
}

fn kinematic_angles(q: &Vector6<f64>) -> Vector6<f64> {
    let preset = stiffid::internal::robot::presets::get("comau-smart5-nj165-3.0").unwrap();
    let map = preset.axis_map();
    map.matrix * q + map.offset
}

pub(crate) fn dh_case() -> Case {
    let text = setup_text(
        "robot.toml",
        "[bounds]\nlower_deg = [-90.0, -60.0, -180.0, -180.0, -90.0, -180.0]\nupper_deg = [90.0, 40.0, -40.0, 180.0, 90.0, 180.0]",
    );
    let robot = dh_robot_text();
    let setup = stiffid::internal::setup::parse(&text, "setup.toml", |_, _| {
        stiffid::internal::robot::file::parse(&robot, "robot.toml")
    })
    .unwrap();
    Case {
        setup,
        gravity: Gravity::Masses,
        angles: preset_angles,
    }
}

fn urdf_case() -> Case {
    let text = setup_text(
        "comau-nj165.urdf",
        "[bounds]\nlower_deg = [-180.0, -180.0, -180.0, -180.0, -180.0, -180.0]\nupper_deg = [180.0, 180.0, 180.0, 180.0, 180.0, 180.0]",
    );
    let urdf = include_str!("../data/comau-nj165.urdf");
    let setup = stiffid::internal::setup::parse(&text, "setup.toml", |name, tip| {
        stiffid::internal::robot::urdf::parse(urdf, name, tip)
    })
    .unwrap();
    Case {
        setup,
        gravity: Gravity::LumpedLinks,
        angles: kinematic_angles,
    }
}

/// The true robot: its error model (geometry, the weight of [`masses`], the load compliances)
/// and values, the tracker's frame.
pub(crate) struct Truth {
    pub(crate) model: ErrorModel,
    pub(crate) estimate: Estimate,
    /// The true robot's rigid chain.
    robot: Robot,
    /// The true drive compliances, rad/(N m).
    compliance: Vector6<f64>,
    /// The true TCP, true flange frame, m.
    tcp: Vector3<f64>,
}

impl Truth {
    pub(crate) fn new(setup: &Setup, rng: &mut ChaCha8Rng) -> Self {
        let robot = setup.robot();
        let compliance = setup.nominal_compliance().unwrap() * 1.3;
        let g = gravity::Terms::masses(robot, masses(), setup.springs(), compliance).unwrap();
        let points = &setup.tool().measuring_points;
        let model = ErrorModel::new(robot, points, MeasuredIn::Tracker, Geometry::Full, g)
            .unwrap()
            .with_loads(setup)
            .unwrap();
        let length = Uniform::new(1e-4, 5e-4).unwrap();
        let angle = Uniform::new(1e-4, 5e-4).unwrap();
        let point = Normal::new(0.0, 5e-6).unwrap();
        let sign = |rng: &mut ChaCha8Rng| {
            if rand::Rng::random_bool(rng, 0.5) {
                1.0
            } else {
                -1.0
            }
        };
        let mut values = model.nominal();
        for (c, p) in model.parameters().iter().enumerate() {
            values[c] += match p.target {
                Target::Joint { component, .. } if component.is_angle() => {
                    sign(rng) * angle.sample(rng)
                }
                Target::Joint { .. } => sign(rng) * length.sample(rng),
                Target::Point { .. } => point.sample(rng),
                _ => 0.0,
            };
        }
        // The drives 30 % more compliant than nominal, under the weight and the loads alike.
        for (j, &c) in model
            .compliance_columns()
            .unwrap()
            .iter()
            .enumerate()
            .take(6)
        {
            values[c] = compliance[j];
        }
        let estimate = Estimate {
            frame: Isometry3::new(Vector3::new(3.1, -0.9, 0.3), Vector3::new(0.02, -0.01, 2.2)),
            values,
        };
        let robot = robot_file::calibrated(&model, &estimate).unwrap();
        Truth {
            model,
            estimate,
            robot,
            compliance,
            tcp: setup.tool().tcp,
        }
    }

    /// The same robot on another day: joint `j`'s angle offset moved by `drift[j]` (rad).
    pub(crate) fn drifted(&self, drift: &[f64; 6]) -> Self {
        let mut estimate = self.estimate.clone();
        for (c, p) in self.model.parameters().iter().enumerate() {
            if let Target::Joint {
                joint,
                component: stiffid::internal::metrology::calibration::error_model::Component::Theta,
            } = p.target
            {
                estimate.values[c] += drift[joint];
            }
        }
        Truth {
            model: self.model.clone(),
            robot: robot_file::calibrated(&self.model, &estimate).unwrap(),
            estimate,
            compliance: self.compliance,
            tcp: self.tcp,
        }
    }

    /// Readings of every measuring point at `qs` (axis angles, rad), unloaded and under
    /// `wrenches` (base frame, at the loading point), with the tracker's noise.
    pub(crate) fn readings(
        &self,
        qs: &[Vector6<f64>],
        wrenches: &[Vector6<f64>],
        rng: &mut ChaCha8Rng,
    ) -> String {
        let noise = Normal::new(0.0, NOISE).unwrap();
        let mut text = stiffid::internal::io::readings::header_with_loads() + "\n";
        for (i, q) in qs.iter().enumerate() {
            for (step, w) in wrenches.iter().enumerate() {
                for k in 0..self.model.points() {
                    let o = Observation {
                        posture: i,
                        point: k,
                        q: *q,
                        measured: Vector3::zeros(),
                        wrench: *w,
                        e: stiffid::internal::robot::external::ExternalValues::NONE,
                        table: false,
                        direction: Vector6::zeros(),
                    };
                    let b = self.model.predict(&self.estimate.values, &[o]).unwrap()[0];
                    let t = self.estimate.frame.inverse() * Point3::from(b);
                    let t = t.coords + Vector3::from_fn(|_, _| noise.sample(rng));
                    let q: Vec<String> =
                        q.iter().map(|v| format!("{:?}", v.to_degrees())).collect();
                    text += &format!(
                        "P{},{},{},{step},{:?},{:?},{:?},{:?},{:?},{:?}\n",
                        i + 1,
                        k + 1,
                        q.join(","),
                        w[0],
                        w[1],
                        w[2],
                        t.x * 1e3,
                        t.y * 1e3,
                        t.z * 1e3
                    );
                }
            }
        }
        text
    }

    /// Where the true robot commanded to `q` (rad) puts its TCP under `wrench` (base frame, at
    /// the TCP), in the tracker's frame: the joints deflected by its weight and by the wrench
    /// through the Jacobian of its own forward kinematics (central differences), the rigid
    /// chain at the deflected angles.
    pub(crate) fn tcp_at(&self, q: &Vector6<f64>, wrench: &Vector6<f64>) -> Vector3<f64> {
        let values = &self.estimate.values;
        let g = self.model.gravity();
        let sag = g.deflection(&values.rows(self.model.gravity_start(), g.len()), q);
        let pose = |q: &Vector6<f64>| {
            let f = self.robot.frames(q).flange;
            (f, f * Point3::from(self.tcp))
        };
        let h = 1e-7;
        let mut tau = Vector6::zeros();
        for j in 0..6 {
            let e = Vector6::ith(j, h);
            let (fa, a) = pose(&(q + e));
            let (fb, b) = pose(&(q - e));
            let dp = (a - b) / (2.0 * h);
            let dr = (fa.rotation * fb.rotation.inverse()).scaled_axis() / (2.0 * h);
            tau[j] = dp.dot(&wrench.fixed_rows::<3>(0)) + dr.dot(&wrench.fixed_rows::<3>(3));
        }
        let dq = sag + tau.component_mul(&self.compliance);
        let p = pose(&(q + dq)).1;
        (self.estimate.frame.inverse() * p).coords
    }
}

/// Postures spread over the arm's range (the preset's axis angles, rad).
pub(crate) fn postures(
    n: usize,
    rng: &mut ChaCha8Rng,
    angles: fn(&Vector6<f64>) -> Vector6<f64>,
) -> Vec<Vector6<f64>> {
    let lo: [f64; 6] = [-60.0, -40.0, -150.0, -120.0, -80.0, 10.0];
    let hi: [f64; 6] = [60.0, 30.0, -60.0, 120.0, 80.0, 150.0];
    (0..n)
        .map(|_| {
            let q = Vector6::from_fn(|i, _| {
                Uniform::new(lo[i], hi[i]).unwrap().sample(rng).to_radians()
            });
            angles(&q)
        })
        .collect()
}

/// A rectangle of 60 x 40 mm milled around the tool's position at `q0` (the part frame there,
/// its z along the tool's -z), in 10 mm steps.
pub(crate) fn rectangle() -> String {
    let mut g = String::from(
        "(stiffid: tool_rpy_deg = 180 0 0)\n(operation: wall)\nG21 G90 G17\nT1 M06\nS6000 M03\nG0 X0 Y0 Z5\nG1 Z0 F300\nF1800\n",
    );
    let corners = [(60.0, 0.0), (60.0, 40.0), (0.0, 40.0), (0.0, 0.0)];
    let mut at = (0.0f64, 0.0f64);
    for (x, y) in corners {
        let n = ((x - at.0).abs().max((y - at.1).abs()) / 10.0).round();
        for s in 1..=n as usize {
            let f = s as f64 / n;
            g += &format!(
                "G1 X{:.3} Y{:.3}\n",
                at.0 + f * (x - at.0),
                at.1 + f * (y - at.1)
            );
        }
        at = (x, y);
    }
    g
}

/// What a program does on the true robot: the TCP error's mean and largest, m.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Row {
    pub(crate) mean: f64,
    pub(crate) max: f64,
}

pub(crate) fn row(errors: &[f64]) -> Row {
    Row {
        mean: errors.iter().sum::<f64>() / errors.len() as f64,
        max: errors.iter().copied().fold(0.0, f64::max),
    }
}

/// The axis angles of a KRL program's motions (joint targets, `PTP {A1 ..}`), deg to rad.
pub(crate) fn joint_targets(krl: &str) -> Vec<Vector6<f64>> {
    krl.lines()
        .filter(|l| l.starts_with("PTP {A1"))
        .map(|l| {
            let inner = &l[l.find('{').unwrap() + 1..l.find('}').unwrap()];
            let v: Vec<f64> = inner
                .split(',')
                .map(|p| p.split_whitespace().nth(1).unwrap().parse::<f64>().unwrap())
                .collect();
            Vector6::from_fn(|i, _| v[i].to_radians())
        })
        .collect()
}

/// A KRL program's Cartesian targets: the pose (part frame, m) and the status and turn bits.
fn cartesian_targets(krl: &str) -> Vec<(Isometry3<f64>, u8, u8)> {
    krl.lines()
        .filter(|l| l.contains("{E6POS:"))
        .map(|l| {
            let inner = &l[l.find(':').unwrap() + 1..l.find('}').unwrap()];
            let field = |name: &str| -> &str {
                inner
                    .split(',')
                    .map(str::trim)
                    .find_map(|p| p.strip_prefix(&format!("{name} ")))
                    .unwrap()
            };
            let n = |name: &str| field(name).parse::<f64>().unwrap();
            let bits = |name: &str| {
                let b = field(name).trim_matches('\'').trim_start_matches('B');
                u8::from_str_radix(b, 2).unwrap()
            };
            let r = UnitQuaternion::from_euler_angles(
                n("C").to_radians(),
                n("B").to_radians(),
                n("A").to_radians(),
            );
            let p = Vector3::new(n("X"), n("Y"), n("Z")) * 1e-3;
            (
                Isometry3::from_parts(Translation3::from(p), r),
                bits("S"),
                bits("T"),
            )
        })
        .collect()
}

/// The load steps of the campaign's readings (base frame, at the loading point, N): none, then
/// two.
pub(crate) const WRENCHES: [Vector6<f64>; 3] = [
    Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    Vector6::new(800.0, -300.0, -1200.0, 0.0, 0.0, 0.0),
    Vector6::new(-500.0, 900.0, 400.0, 0.0, 0.0, 0.0),
];

/// The campaign on one robot and the table of what each program does on the true robot.
struct Outcome {
    nominal: Row,
    joint: Row,
    cartesian: Row,
    /// A RAPID module as its controller stores it, compensated and run by the nominal
    /// controller from its text ([`crate::machining::program::rapid::stored`]).
    stored: Row,
    geometry_only: Row,
    /// The held-out calibration error (RMS, m) plus the mean predicted standard deviation of the
    /// deflection's length (m).
    expected: f64,
}

/// The (posture, point) of every row of the readings `text` (unloaded), sorted: the points as the
/// readings name them (`1`, `2`, ... on the tool, `T1`, `T2`, ... on the positioner's table).
fn read_points(text: &str) -> Vec<(String, String)> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let step = header.iter().position(|h| *h == "load_step");
    let mut out: Vec<(String, String)> = lines
        .map(|l| l.split(',').collect::<Vec<&str>>())
        .filter(|cells| step.is_none_or(|k| cells[k].parse::<f64>() == Ok(0.0)))
        .map(|cells| (cells[0].to_string(), cells[1].to_string()))
        .collect();
    out.sort();
    out
}

/// The (posture, point name) of the calibrate document's held-out readings, sorted.
fn held_points(document: &Document) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = (document.errors.iter())
        .filter(|e| e.set == "validation")
        .map(|e| (e.posture.to_string(), e.point_name.clone()))
        .collect();
    out.sort();
    out
}

/// Calibrates with `gravity`, returns the calibrated setup (the nominal controller named), the
/// compliance (from loaded readings), the registration, the held-out RMS and the registration on
/// the nominal robot.
pub(crate) fn calibrated(
    case: &Case,
    gravity: Gravity,
    data: &str,
    held: &str,
) -> (
    Setup,
    Option<stiffid::internal::model::Compliance>,
    Isometry3<f64>,
    f64,
    Isometry3<f64>,
) {
    let setup = &case.setup;
    let report = calibrate::run(&calibrate::Request {
        readings: stiffid::app::readings::Request {
            setup_name: "setup".into(),
            setup,
            name: "fit.csv".into(),
            text: data,
            force: false,
        },
        geometry: Geometry::Full,
        gravity: stiffid::app::calibrate::GravitySpec::Fixed(gravity),
        gravity_bound: None,
        validate: Some(("held.csv".into(), held)),
        reregister: false,
        cross_validate: false,
        priors: None,
        progress: &(),
        maps: stiffid::internal::metrology::calibration::maps::Spec::None,
        error_motions: Default::default(),
        level: None,
        update: false,
        refit: Default::default(),
        weight: None,
        urdf: false,
    })
    .unwrap();
    let document = report.document();
    assert_eq!(held_points(&document), read_points(held), "held-out points");
    let compliance = document.stiffness_file.as_ref().map(|file| {
        let file = serde_json::to_string(file).unwrap();
        let compliance = stiffid::internal::io::stiffness::parse(&file)
            .unwrap()
            .compliance(setup.model())
            .unwrap();
        // The calibrated robot file carries the sag, the stiffness file only the compliance.
        assert!(compliance.own_weight.is_none());
        compliance
    });
    // The calibrated robot as its file gives it: the one model of the robot.
    let robot = stiffid::internal::robot::file::parse(
        report.robot_toml.as_ref().unwrap(),
        "calibrated.toml",
    )
    .unwrap();
    assert_eq!(robot.own_weight().is_some(), gravity != Gravity::None);
    // It records the mount it was calibrated on.
    assert_eq!(robot.mount(), Some(&setup.workcell().controller().mount));
    let controller = Controller {
        kinematics: Kinematics::Nominal,
        robot: Some(setup.robot().clone()),
        ..Default::default()
    };
    // The fragment's tool: the fitted measuring points and the TCP moved with them.
    let points = (report.fragment.lines())
        .find_map(|l| l.strip_prefix("# measuring_points_mm = "))
        .unwrap();
    let points: Vec<[f64; 3]> = serde_json::from_str(points).unwrap();
    let calibrated = setup
        .to_builder()
        .with_robot(robot)
        .with_measuring_points(points.iter().map(|p| Vector3::from(*p) * 1e-3).collect())
        .with_tcp(report.tcp.unwrap())
        .with_controller(controller)
        .build()
        .unwrap();
    let held_rms = report.validation.as_ref().unwrap().calibrated.rms;
    // The calibrated robot file carries the held-out errors the error budget reads.
    {
        let h = calibrated.robot().held_out().unwrap();
        let v = &report.validation.as_ref().unwrap().calibrated;
        assert_eq!(
            (h.source.as_str(), h.errors.len()),
            ("validate", v.errors.len())
        );
        assert!((h.errors[h.errors.len() - 1] - v.max).abs() <= 1e-12 * v.max.max(1e-3));
        assert!(h.quantile(0.5) <= v.max);
    }
    eprintln!(
        "calibration ({}): residual {:.4} mm, noise ratio {:.2}, held out {:.4} mm, nominal {:.4} mm",
        stiffid::internal::common::choice::Choice::name(gravity),
        report.fit.rms * 1e3,
        report.noise_ratio,
        held_rms * 1e3,
        report.validation.as_ref().unwrap().nominal.rms * 1e3
    );
    (
        calibrated,
        compliance,
        report.fit.estimate.frame,
        held_rms,
        report.start_frame,
    )
}

/// Compensates [`rectangle`] on `setup` (its part frame set) to KRL with `targets`: the program
/// and every point's result.
fn program(
    setup: &Setup,
    compliance: &stiffid::internal::model::Compliance,
    q0: &Vector6<f64>,
    targets: Targets,
) -> (String, Vec<Compensated>) {
    written(
        setup,
        compliance,
        q0,
        (Language::Robot(Dialect::Krl), targets),
    )
}

/// Compensates [`rectangle`] on `setup` (its part frame set) to `output` with `targets`: the
/// program and every point's result.
fn written(
    setup: &Setup,
    compliance: &stiffid::internal::model::Compliance,
    q0: &Vector6<f64>,
    output: (Language, Targets),
) -> (String, Vec<Compensated>) {
    written_from(setup, compliance, (q0, &rectangle()), output)
}

/// Compensates the G-code `gcode` on `setup` (its part frame set) from `q0` to `output` with
/// `targets`: the program and every point's result.
pub(crate) fn written_from(
    setup: &Setup,
    compliance: &stiffid::internal::model::Compliance,
    (q0, gcode): (&Vector6<f64>, &str),
    output: (Language, Targets),
) -> (String, Vec<Compensated>) {
    let process = include_str!("../../../../examples/milling/aluminium.toml");
    written_with(setup, compliance, (q0, gcode, process), output)
}

/// [`written_from`] under the process file `process` (its text).
pub(crate) fn written_with(
    setup: &Setup,
    compliance: &stiffid::internal::model::Compliance,
    (q0, gcode, process): (&Vector6<f64>, &str, &str),
    (output, targets): (Language, Targets),
) -> (String, Vec<Compensated>) {
    let process =
        stiffid::internal::machining::process::file::parse(process, "process.toml").unwrap();
    let mut options = Options::for_setup(setup);
    options.q0 = *q0;
    let request = compensate::Request {
        names: Default::default(),
        setup,
        compliance: compliance.clone(),
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "rectangle.nc".into(),
            text: gcode,
            data: None,
            language: Language::GCode,
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-5,
            output,
            out_name: match output {
                Language::GCode => "rectangle-compensated.nc".into(),
                // A name every language takes (LS: at most 8 characters by default).
                Language::Robot(d) => format!("rect.{}", d.controller().extensions()[0]),
            },
            // G-code output carries positions only: the targets' form is a robot program's.
            settings: match output {
                Language::GCode => Settings::default(),
                _ => Settings {
                    targets,
                    ..Settings::default()
                },
            },
        },
        options,
    };
    let mut results = Vec::new();
    let report = compensate::run::<stiffid::Error, _>(request, |_, _, r, _| {
        results.extend_from_slice(r);
        Ok(())
    })
    .unwrap();
    (
        crate::common::program_text(report.report.program.unwrap()),
        results,
    )
}

/// The axis angles the part is placed at on `case`'s robot.
pub(crate) fn q0(case: &Case) -> Vector6<f64> {
    (case.angles)(&Vector6::from_fn(|i, _| {
        [10.0f64, 10.0, -110.0, 20.0, -50.0, 40.0][i].to_radians()
    }))
}

/// The part where `setup`'s robot puts its tool at `q0`, the tool along its -z: `setup` with
/// that part frame, and the frame.
pub(crate) fn with_part(setup: &Setup, q0: &Vector6<f64>) -> (Setup, Isometry3<f64>) {
    let at = ik::tool_pose(&setup.robot().frames(q0), &setup.tool().tcp);
    let part = at * UnitQuaternion::from_euler_angles(std::f64::consts::PI, 0.0, 0.0);
    (
        setup.to_builder().with_workpiece(part).build().unwrap(),
        part,
    )
}

/// What the program compensated on `setup` (its part set, its tracker registered at `frame`)
/// with `compliance` does on the true robot: joint targets, Cartesian targets run by the
/// nominal controller's inverse kinematics (`nominal`, checked to return the compensated
/// angles), the Cartesian run's results and the mean predicted standard deviation of the
/// deflection's length (m).
pub(crate) fn landing(
    truth: &Truth,
    nominal: &Robot,
    (setup, compliance): (&Setup, &stiffid::internal::model::Compliance),
    q0: &Vector6<f64>,
    frame: &Isometry3<f64>,
) -> (Row, Row, Vec<Compensated>, f64) {
    let part = *setup.workpiece().unwrap();
    let error = |target: &Isometry3<f64>, q: &Vector6<f64>, w: &Vector6<f64>| {
        let want = frame.inverse() * Point3::from(target.translation.vector);
        (truth.tcp_at(q, w) - want.coords).norm()
    };
    // Joint targets.
    let (krl, results) = program(setup, compliance, q0, Targets::Joint);
    let qs = joint_targets(&krl);
    assert_eq!(qs.len(), results.len());
    let joint: Vec<f64> = (qs.iter().zip(&results))
        .map(|(q, r)| {
            assert!((q - r.q_compensated).amax() < 1e-8);
            error(&r.pose, q, &r.wrench)
        })
        .collect();
    // Cartesian targets, run by the controller's nominal inverse kinematics.
    let (krl, results) = program(setup, compliance, q0, Targets::Cartesian);
    let poses = cartesian_targets(&krl);
    assert_eq!(poses.len(), results.len());
    let mut previous = results[0].q;
    let mut cartesian = Vec::new();
    for ((pose, s, t), r) in poses.iter().zip(&results) {
        let target = part * pose;
        let q = ik::solve(
            nominal,
            &setup.tool().tcp,
            &target,
            &previous,
            &ik::Options::default(),
        )
        .unwrap()
        .q;
        let st = StatusTurn::of(&Configuration::of(nominal, &q));
        assert_eq!((st.status, st.turn), (*s, *t));
        // Round trip: the controller's inverse kinematics returns the compensated angles.
        assert!(
            (q - r.q_compensated).amax() < 1e-7,
            "{}",
            (q - r.q_compensated).amax()
        );
        cartesian.push(error(&r.pose, &q, &r.wrench));
        previous = q;
    }
    let std: Vec<f64> = results
        .iter()
        .filter_map(|r| r.translation_norm_std)
        .collect();
    let std = std.iter().sum::<f64>() / std.len().max(1) as f64;
    (row(&joint), row(&cartesian), results, std)
}

/// What the compensated G-code, written back as G-code for the controller's kinematics, does on
/// the true robot: the controller (`nominal`) runs its inverse kinematics of each point in the
/// part frame, the orientation as programmed.
pub(crate) fn gcode_landing(
    truth: &Truth,
    nominal: &Robot,
    (setup, compliance): (&Setup, &stiffid::internal::model::Compliance),
    q0: &Vector6<f64>,
    frame: &Isometry3<f64>,
) -> Row {
    let part = *setup.workpiece().unwrap();
    let (text, results) = written(setup, compliance, q0, (Language::GCode, Targets::Joint));
    let g = stiffid::internal::machining::gcode::parse(&text, 1e-5).unwrap();
    assert_eq!(g.points.len(), results.len());
    let mut previous = results[0].q;
    let errors: Vec<f64> = (g.points.iter().zip(&results))
        .map(|(p, r)| {
            let target =
                part * Isometry3::from_parts(Translation3::from(p.position), p.orientation);
            let tcp = &setup.tool().tcp;
            let q = ik::solve(nominal, tcp, &target, &previous, &ik::Options::default());
            previous = q.unwrap().q;
            let want = frame.inverse() * Point3::from(r.pose.translation.vector);
            (truth.tcp_at(&previous, &r.wrench) - want.coords).norm()
        })
        .collect();
    row(&errors)
}

fn campaign(case: &Case, seed: u64) -> Outcome {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let truth = Truth::new(&case.setup, &mut rng);
    let fit = postures(30, &mut rng, case.angles);
    let data = truth.readings(&fit, &WRENCHES, &mut rng);
    let held_postures = postures(12, &mut rng, case.angles);
    let held = truth.readings(&held_postures, &WRENCHES[..1], &mut rng);
    let (setup, compliance, frame, held_rms, nominal_frame) =
        calibrated(case, case.gravity, &data, &held);
    let compliance = compliance.unwrap();
    let q0 = q0(case);
    let (setup, part) = with_part(&setup, &q0);
    let nominal = case.setup.robot();
    let (joint, cartesian, results, _) =
        landing(&truth, nominal, (&setup, &compliance), &q0, &frame);
    let stored = crate::machining::program::rapid::stored::stored_landing(
        &truth,
        nominal,
        (&setup, &compliance),
        &q0,
        &frame,
    );
    let error =
        |frame: &Isometry3<f64>, target: &Isometry3<f64>, q: &Vector6<f64>, w: &Vector6<f64>| {
            let want = frame.inverse() * Point3::from(target.translation.vector);
            (truth.tcp_at(q, w) - want.coords).norm()
        };
    // The nominal controller without stiffid: its inverse kinematics of the part's targets, the
    // part located through the tracker registered on the nominal robot.
    let mut previous = results[0].q;
    let nominal_errors: Vec<f64> = (results.iter())
        .map(|r| {
            let target = nominal_frame * frame.inverse() * r.pose;
            let q = ik::solve(
                nominal,
                &case.setup.tool().tcp,
                &target,
                &previous,
                &ik::Options::default(),
            )
            .unwrap()
            .q;
            previous = q;
            error(&nominal_frame, &target, &q, &r.wrench)
        })
        .collect();
    // A geometry-only calibration of the same readings, joint targets.
    let (plain, plain_compliance, plain_frame, _, _) =
        calibrated(case, Gravity::None, &data, &held);
    let plain_compliance = plain_compliance.unwrap();
    let plain = plain.to_builder().with_workpiece(part).build().unwrap();
    let (krl, results) = program(&plain, &plain_compliance, &q0, Targets::Joint);
    let geometry_only: Vec<f64> = (joint_targets(&krl).iter().zip(&results))
        .map(|(q, r)| error(&plain_frame, &r.pose, q, &r.wrench))
        .collect();
    let std: Vec<f64> = results
        .iter()
        .filter_map(|r| r.translation_norm_std)
        .collect();
    Outcome {
        nominal: row(&nominal_errors),
        joint,
        cartesian,
        stored,
        geometry_only: row(&geometry_only),
        expected: held_rms + std.iter().sum::<f64>() / std.len().max(1) as f64,
    }
}

fn check(name: &str, o: &Outcome) {
    for (what, r) in [
        ("nominal controller", o.nominal),
        ("joint targets", o.joint),
        ("Cartesian targets", o.cartesian),
        ("RAPID module as stored", o.stored),
        ("geometry-only calibration", o.geometry_only),
    ] {
        eprintln!(
            "{name}: {what}: TCP error mean {:.4} mm, max {:.4} mm",
            r.mean * 1e3,
            r.max * 1e3
        );
    }
    eprintln!(
        "{name}: expected (held-out + deflection sd) {:.4} mm",
        o.expected * 1e3
    );
    for r in [o.joint, o.cartesian, o.stored] {
        assert!(
            r.mean <= 3.0 * o.expected,
            "{name}: {r:?} vs {}",
            o.expected
        );
        assert!(r.mean <= 0.05e-3, "{name}: {r:?}");
    }
    assert!(o.nominal.mean > 1e-3, "{name}: {:?}", o.nominal);
    assert!(o.joint.mean < o.geometry_only.mean, "{name}");
}

#[test]
fn program_lands_on_the_true_dh_robot() {
    check("DH robot", &campaign(&dh_case(), 1));
}

#[test]
fn program_lands_on_the_true_urdf_robot() {
    check("URDF robot", &campaign(&urdf_case(), 2));
}
