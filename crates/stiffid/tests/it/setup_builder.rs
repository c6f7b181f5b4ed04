//! A setup built in code is checked as a setup file is: a bad value is an error naming the field,
//! never a panic later, and the builder and the TOML path give the same setup.

use nalgebra::{Vector3, Vector6};
use stiffid::internal::common::limits::JointBox;
use stiffid::internal::robot::presets;
use stiffid::internal::setup::{self, Noise, RopeLoad, Setup, SetupBuilder, Tracker};
use stiffid::Error;

fn mm(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z) * 1e-3
}

fn deg(q: [f64; 6]) -> Vector6<f64> {
    Vector6::from_iterator(q.iter().map(|d| d.to_radians()))
}

/// The paper's cell (setups/zhang2021-comau-nj165.toml) written in code, SI units.
fn paper_in_code() -> SetupBuilder {
    let robot = presets::get("comau-smart5-nj165-3.0").unwrap();
    Setup::builder("zhang2021-comau-nj165", robot)
        .with_description(
            "Zhang et al. (IEEE Access 2021) simulation cell: COMAU SMART5 NJ 165-3.0, 500 N \
             rope-mass load, 4 measuring points",
        )
        .with_robot_ref("comau-smart5-nj165-3.0")
        .with_characteristic_length(1200.0 * 1e-3)
        .with_nominal_stiffness(Vector6::new(
            950000.0, 3000000.0, 900000.0, 250000.0, 200000.0, 150000.0,
        ))
        .with_loading_point(mm(150.0, 0.0, 200.0))
        .with_measuring_points(vec![
            mm(80.0, 80.0, 260.0),
            mm(-80.0, 80.0, 260.0),
            mm(-80.0, -80.0, 260.0),
            mm(80.0, -80.0, 260.0),
        ])
        .with_load(RopeLoad {
            load: 500.0,
            anchor: mm(2000.0, 1500.0, 0.0),
        })
        .with_noise(Noise {
            // The file's reading_sd_mm squared: the paper's displacement variance, halved.
            reading_variance: 9.23e-5 * 1e-6 / 2.0,
            levels: vec![0.5, 1.0, 1.5, 2.0, 2.5, 3.0],
        })
        .with_bounds(JointBox {
            lower: deg([-90.0, -60.0, -180.0, -180.0, -90.0, -180.0]),
            upper: deg([90.0, 40.0, -40.0, 180.0, 90.0, 180.0]),
        })
        .with_test_postures(vec![
            deg([12.81, 33.07, -126.36, 72.81, -67.88, 24.27]),
            deg([-22.25, -34.46, -109.53, -94.38, 49.16, 186.07]),
            deg([-61.35, -10.10, -119.99, -272.36, -55.71, -110.56]),
        ])
}

#[test]
fn the_builder_and_the_file_give_the_same_paper_setup() {
    let from_file = setup::builtin("zhang2021-comau-nj165").unwrap();
    assert_eq!(paper_in_code().build().unwrap(), from_file);
    assert_eq!(from_file.to_builder().build().unwrap(), from_file);
}

/// The field named by an [`Error::InvalidField`], or a panic naming what came instead.
fn field_of(result: Result<Setup, Error>) -> String {
    match result {
        Err(Error::InvalidField { field, message }) => {
            assert!(!message.is_empty());
            field
        }
        Err(Error::OutsideBox { field, .. }) => field,
        other => panic!("expected a field error, got {other:?}"),
    }
}

#[test]
fn bad_values_in_code_name_the_field() {
    let nan = f64::NAN;
    let cases: Vec<(SetupBuilder, &str)> = vec![
        (
            paper_in_code().with_measuring_points(vec![]),
            "tool.measuring_points_mm",
        ),
        (
            paper_in_code().with_measuring_points(vec![mm(0.0, nan, 0.0)]),
            "tool.measuring_points_mm[2]",
        ),
        (
            paper_in_code().with_loading_point(mm(1e9, 0.0, 0.0)),
            "tool.loading_point_mm[1]",
        ),
        (
            paper_in_code().with_nominal_stiffness(Vector6::repeat(0.0)),
            "nominal_stiffness_nm_per_rad[1]",
        ),
        (
            paper_in_code().with_characteristic_length(nan),
            "characteristic_length_mm",
        ),
        (
            paper_in_code().with_noise(Noise {
                reading_variance: 1e-10,
                levels: vec![1.0, 0.0],
            }),
            "noise.level_multiples[2]",
        ),
        (
            paper_in_code().with_noise(Noise {
                reading_variance: -1.0,
                levels: vec![1.0],
            }),
            "noise.reading_sd_mm",
        ),
        (
            paper_in_code().with_bounds(JointBox {
                lower: Vector6::repeat(-10.0),
                upper: Vector6::repeat(10.0),
            }),
            "bounds.lower_deg[1]",
        ),
        (
            paper_in_code().with_bounds(JointBox {
                lower: Vector6::repeat(0.1),
                upper: Vector6::repeat(0.0),
            }),
            "bounds.lower_deg[1]",
        ),
        (
            paper_in_code().with_test_postures(vec![Vector6::repeat(100.0)]),
            "test.postures_deg[1][1]",
        ),
        (
            paper_in_code().with_tracker(Tracker {
                position: mm(3000.0, 0.0, 1000.0),
                max_incidence: None,
                measuring_normals: vec![Vector3::z()],
                base_from_tracker: None,
                registration_uncertainty: None,
            }),
            "tracker.measuring_normals",
        ),
        (
            paper_in_code().with_tool_radius(0.0),
            "robot_geometry.tool_radius_mm",
        ),
        (paper_in_code().with_description("x"), ""),
    ];
    for (builder, field) in cases {
        match field {
            "" => assert!(builder.build().is_ok()),
            _ => assert_eq!(field_of(builder.build()), field),
        }
    }
    let robot = presets::get("comau-smart5-nj165-3.0").unwrap();
    let e = field_of(Setup::builder(" ", robot.clone()).build());
    assert_eq!(e, "name");
    let e = field_of(Setup::builder("cell", robot).build());
    assert_eq!(e, "noise");
}

#[test]
fn the_file_names_itself_before_the_field() {
    let text = setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .replace("[80.0, 80.0, 260.0]", "[80.0, nan, 260.0]");
    let e = setup::parse(&text, "cell.toml", |r, _| presets::get(r)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "cell.toml: tool.measuring_points_mm[2]: NaN is outside [-100000, 100000] mm"
    );
}

#[test]
fn box_errors_show_the_value_beside_the_range() {
    let mut upper = deg([90.0, 40.0, -40.0, 180.0, 90.0, 180.0]);
    upper[1] = 100f64.to_radians();
    let lower = deg([-90.0, -60.0, -180.0, -180.0, -90.0, -180.0]);
    let e = paper_in_code()
        .with_bounds(JointBox::new(lower, upper))
        .build()
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "bounds.upper_deg[2] = 100.00 deg: expected within the robot's limits [-75.00, 95.00] deg"
    );
    let mut q = deg([12.81, 33.07, -126.36, 72.81, -67.88, 24.27]);
    q[2] = (-5f64).to_radians();
    let e = paper_in_code()
        .with_test_postures(vec![q])
        .build()
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "test.postures_deg[1][3] = -5.00 deg: expected within the robot's limits [-256.00, -10.00] deg"
    );
    let e = paper_in_code()
        .with_bounds(JointBox::new(upper, lower))
        .build()
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "bounds.lower_deg[1]: 90.00 deg is not below bounds.upper_deg[1] = -90.00 deg"
    );
    let text = setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .replace("upper_deg = [90.0, 40.0,", "upper_deg = [90.0, 95.001,");
    let e = setup::parse(&text, "cell.toml", |r, _| presets::get(r)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "cell.toml: bounds.upper_deg[2] = 95.001 deg: expected within the robot's limits [-75.00, 95.00] deg"
    );
}

/// Tool points in metres read as mm and angles in radians under `_deg` names are warned about;
/// the paper's setup and its postures are not.
#[test]
fn unit_slips_get_a_plausibility_warning() {
    use stiffid::internal::setup::plausibility::{radians_as_degrees, warnings};
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    assert!(warnings(&paper).is_empty(), "{:?}", warnings(&paper));
    let tool = paper.tool();
    let metres: Vec<_> = tool.measuring_points.iter().map(|p| p * 1e-3).collect();
    let slipped = paper
        .to_builder()
        .with_measuring_points(metres.clone())
        .with_loading_point(tool.loading_point * 1e-3)
        .build()
        .unwrap();
    let w = warnings(&slipped);
    assert!(
        w.len() == 1 && w[0].message.contains("every tool point"),
        "{w:?}"
    );
    // The measuring points alone in metres, the loading point in mm.
    let points = paper.to_builder().with_measuring_points(metres);
    let w = warnings(&points.build().unwrap());
    assert!(
        w.len() == 1
            && w[0].message.contains("every measuring point")
            && w[0].message.contains("the loading point 250.0 mm"),
        "{w:?}"
    );
    let postures = paper.test_postures();
    assert!(radians_as_degrees(postures).is_none());
    let radians: Vec<_> = postures.iter().map(|q| q.map(f64::to_radians)).collect();
    let w = radians_as_degrees(&radians).unwrap();
    assert!(w.message.contains("radians"), "{w}");
}

/// `[tool] mass_kg` and `centre_of_mass_mm`: the weight's wrench at the TCP (down the base z
/// axis, its moment from the lever `R (c - tcp)`); both or neither; the mass within its limits.
#[test]
fn the_tools_weight_is_a_wrench_at_the_tcp() {
    let base = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/milling/kuka-milling.toml"
    ))
    .unwrap();
    let s = stiffid::internal::setup::parse(&base, "kuka-milling.toml", |r, _| presets::get(r))
        .unwrap();
    let p = *s.payload().unwrap();
    assert_eq!(p.mass, 25.0);
    let tcp = s.tool().tcp;
    let down = p.wrench(&nalgebra::UnitQuaternion::identity(), &tcp);
    let g = 25.0 * stiffid::internal::setup::GRAVITY;
    assert_eq!(down, nalgebra::Vector6::new(0.0, 0.0, -g, 0.0, 0.0, 0.0));
    // The tool axis horizontal (the flange turned 90 deg about x): the centre of mass sits
    // 130 mm along +y of the TCP, its weight a moment of -0.13 g m about x.
    let turned = nalgebra::UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 0.0);
    let w = p.wrench(&turned, &tcp);
    assert!(
        (w[3] + 0.13 * g).abs() < 1e-12 && w[4].abs() < 1e-12 && w[5].abs() < 1e-12,
        "{w}"
    );
    let alone = base.replace("centre_of_mass_mm = [0, 0, 120]\n", "");
    let e = stiffid::internal::setup::parse(&alone, "k.toml", |r, _| presets::get(r))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("tool.mass_kg") && e.contains("both or neither"),
        "{e}"
    );
    let heavy = base.replace("mass_kg = 25", "mass_kg = 1e9");
    let e = stiffid::internal::setup::parse(&heavy, "k.toml", |r, _| presets::get(r))
        .unwrap_err()
        .to_string();
    assert!(e.contains("tool.mass_kg"), "{e}");
    assert!(s.tcp_given());
    assert!(!stiffid::internal::setup::builtin("fanuc-r2000ic-165f")
        .unwrap()
        .tcp_given());
}
