//! The robot's own bodies in the cell: a URDF's collision meshes as convex hulls, found through
//! package paths; distances equal to hand-computed ones; feasibility with hulls; the broad phase;
//! capsules as the fallback and the user's override; `[robot_geometry]` in robot TOML files.

#[path = "../support/mesh_robot.rs"]
pub(crate) mod mesh_robot;

use nalgebra::{Vector3, Vector6};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use stiffid::internal::cell::{
    self, body_body, body_box, body_floor, Body, CheckKind, Checker, Part,
};
use stiffid::internal::robot::Bodies;
use stiffid::internal::setup::reference::{self, Meshes};
use stiffid::internal::setup::Obstacle;
use stiffid::Setup;

/// The mesh robot's files under the directory `pkg`.
fn files() -> HashMap<PathBuf, Vec<u8>> {
    mesh_robot::files(48)
        .into_iter()
        .map(|(p, b)| (Path::new("pkg").join(p), b))
        .collect()
}

/// The setup `toml` read as `pkg/cell.toml`, meshes looked for in `package_paths` first.
fn setup_from(toml: &str, package_paths: &[PathBuf]) -> stiffid::Result<Setup> {
    let files = files();
    let text = |p: &Path| {
        Some(Ok::<_, stiffid::Error>(
            String::from_utf8(files.get(p)?.clone()).unwrap(),
        ))
    };
    let bytes = |p: &Path| files.get(p).cloned().map(Ok);
    let meshes = Meshes {
        read: &bytes,
        package_paths,
    };
    reference::setup_text_with_meshes(toml, "pkg/cell.toml", Path::new("pkg"), text, &meshes)
}

/// The mesh robot in its cell (also the 3D scene's tests').
pub fn mesh_setup() -> Setup {
    setup_from(&mesh_robot::setup_toml(), &[]).unwrap()
}

/// The first body of `part` at posture `q`.
fn body(setup: &Setup, q: &Vector6<f64>, part: Part) -> Body {
    let frames = setup.robot().frames(q);
    cell::bodies(setup.arm(), &frames)
        .into_iter()
        .find(|b| b.part() == part)
        .unwrap()
}

fn close(got: f64, want: f64, tolerance: f64) {
    assert!((got - want).abs() <= tolerance, "{got} vs {want}");
}

#[test]
fn hull_distances_equal_hand_computed_ones() {
    let setup = mesh_setup();
    let shapes = setup.shapes().expect("the URDF's meshes");
    assert_eq!(shapes.shapes.len(), 7);
    let zero = Vector6::zeros();
    // The prisms' vertices are f32: 1e-7 m.
    let tol = 1e-6;
    // The turret's lowest face at z = 0.15, above the floor at -0.1.
    close(
        body_floor(&body(&setup, &zero, Part::Link(1)), -0.1),
        0.25,
        tol,
    );
    // The forearm (link 4) along x at z = 0.78 + 1.28 + 0.2 = 2.26, radius 0.14 (a vertex of the
    // 48-gon straight up): a box 2.6 m high over it is 0.2 m away.
    let lid = Obstacle::fixed(
        "lid",
        Vector3::new(0.6, -0.5, 2.6),
        Vector3::new(1.0, 0.5, 3.0),
    );
    close(
        body_box(&body(&setup, &zero, Part::Link(4)), &lid),
        0.2,
        tol,
    );
    // The upper arm's top rim (x = 0.32 + 0.17, z = 2.06) and the forearm's first face's lowest
    // vertex (x = 0.32 + 0.2, z = 2.26 - 0.14): sqrt(0.03^2 + 0.06^2).
    let (arm, forearm) = (
        body(&setup, &zero, Part::Link(2)),
        body(&setup, &zero, Part::Link(4)),
    );
    close(body_body(&arm, &forearm), 0.0045f64.sqrt(), tol);
    // The tool's capsule stays a capsule.
    assert!(matches!(body(&setup, &zero, Part::Tool), Body::Capsule(_)));
}

#[test]
fn feasibility_uses_the_hulls_and_the_broad_phase_keeps_every_smallest_margin() {
    let setup = mesh_setup();
    let checker = Checker::new(&setup);
    let f = checker.feasibility(&Vector6::zeros());
    let floor = f
        .checks
        .iter()
        .find(|c| c.kind == CheckKind::Floor)
        .unwrap();
    // The turret, 0.25 m above the floor, less the 30 mm clearance.
    close(floor.margin, 0.22, 1e-6);
    assert_eq!(floor.between, ("link 1".to_string(), "floor".to_string()));
    // Forearm down into the floor.
    let down = Vector6::new(0.0, 1.2, 1.2, 0.0, 0.0, 0.0);
    assert!(checker
        .feasibility(&down)
        .violations()
        .any(|c| c.kind == CheckKind::Floor));
    // The broad phase: every check's smallest margin within FAR_MARGIN of failing is exact, and
    // no pair's margin exceeds its exact distance's.
    let b = setup.bounds();
    let mut exact_checks = 0;
    for k in 0..40 {
        let t = f64::from(k) / 40.0;
        let q = Vector6::from_fn(|a, _| {
            let s = ((t * 7.3 + a as f64 * 1.7).sin() + 1.0) / 2.0;
            b.lower[a] + s * (b.upper[a] - b.lower[a])
        });
        let margins = checker.margins(&q);
        for c in checker.feasibility(&q).checks {
            let smallest = margins
                .iter()
                .filter(|m| m.kind == c.kind)
                .map(|m| m.margin)
                .fold(f64::INFINITY, f64::min);
            assert!(
                smallest <= c.margin + 1e-12,
                "{}: {smallest} > {}",
                c.kind,
                c.margin
            );
            if c.margin < 0.1 {
                assert_eq!(smallest, c.margin, "{} at {q:?}", c.kind);
                exact_checks += 1;
            }
        }
    }
    assert!(exact_checks > 20, "{exact_checks}");
}

#[test]
fn a_body_wholly_below_the_floor_fails_the_broad_phase_too() {
    // A floor 3 m up: every link's bounding sphere lies below it, most far more than
    // FAR_MARGIN beyond their radius. The broad phase must not take them for far above it.
    let text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .to_string()
        + "\n[cell]\nfloor_z_mm = 3000.0\nclearance_mm = 50.0\n";
    let setup = stiffid::internal::setup::parse(&text, "cell.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap();
    let checker = Checker::new(&setup);
    let q = Vector6::new(0.0, 0.0, -90f64.to_radians(), 0.0, 30f64.to_radians(), 0.0);
    let f = checker.feasibility(&q);
    let floor = f
        .checks
        .iter()
        .find(|c| c.kind == CheckKind::Floor)
        .unwrap();
    assert!(floor.margin < -2.0, "{}", floor.margin);
    let smallest = checker
        .margins(&q)
        .iter()
        .filter(|m| m.kind == CheckKind::Floor)
        .map(|m| m.margin)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(smallest, floor.margin);
    assert!(checker.violation(&q) > 2.0);
}

#[test]
fn package_urls_resolve_in_the_setups_and_the_given_package_paths_or_name_the_package() {
    let without = mesh_robot::setup_toml().replace("package_paths = [\".\"]\n", "");
    // Meshes not found: the setup loads (kinematics needs none), the cell's checks refuse it.
    let bare = setup_from(&without, &[]).unwrap();
    assert!(bare.shapes().is_none());
    let warning = stiffid::internal::setup::plausibility::warnings(&bare);
    assert_eq!(warning.len(), 1, "{warning:?}");
    assert!(warning[0].message.contains("--package-path"), "{warning:?}");
    let e = bare.check_bodies().unwrap_err().to_string();
    assert!(
        e.starts_with("[cell]: ") && e.contains("--package-path DIR"),
        "{e}"
    );
    assert!(
        e.contains("mesh 'package://mesh_robot/meshes/base_link.stl' is in package 'mesh_robot'"),
        "{e}"
    );
    let e = setup_from(&without, &[PathBuf::from("elsewhere")])
        .unwrap()
        .check_bodies()
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("package 'mesh_robot' not found in the package paths (no elsewhere/mesh_robot/meshes/base_link.stl)"),
        "{e}"
    );
    // Given on the command line instead of in the setup.
    let setup = setup_from(
        &without,
        &[PathBuf::from("elsewhere"), PathBuf::from("pkg")],
    )
    .unwrap();
    assert_eq!(setup.shapes().unwrap().shapes.len(), 7);
    let e = setup_from(
        &mesh_robot::setup_toml().replace("package_paths = [\".\"]", "package_paths = [\" \"]"),
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("package_paths[1]"), "{e}");
}

#[test]
fn capsules_are_the_fallback_and_the_users_override() {
    let radii = "[robot_geometry]\nlink_radius_mm = [400, 300, 200, 180, 140, 110, 90]\n";
    let setup = setup_from(&(mesh_robot::setup_toml() + radii), &[]).unwrap();
    assert!(setup.shapes().is_none());
    close(setup.geometry().link_radii[1], 0.3, 1e-12);
    let frames = setup.robot().frames(&Vector6::zeros());
    assert!(cell::bodies(setup.arm(), &frames)
        .iter()
        .all(|b| matches!(b, Body::Capsule(_))));
    // Without a mesh reader, a URDF robot has capsules.
    let files = files();
    let text = |p: &Path| {
        Some(Ok::<_, stiffid::Error>(
            String::from_utf8(files.get(p)?.clone()).unwrap(),
        ))
    };
    let plain = reference::setup_text(
        &mesh_robot::setup_toml(),
        "pkg/cell.toml",
        Path::new("pkg"),
        text,
    )
    .unwrap();
    assert!(plain.shapes().is_none());
    // Rebuilt, a setup keeps its shapes.
    let rebuilt = mesh_setup().to_builder().build().unwrap();
    assert!(rebuilt.shapes().is_some());
}

#[test]
fn robot_files_accept_robot_geometry() {
    let preset = stiffid::internal::robot::presets::text("comau-smart5-nj165-3.0").unwrap();
    let text = format!(
        "{preset}\n[robot_geometry]\nlink_radius_mm = [350, 260, 195, 175, 130, 110, 90]\n"
    );
    let robot = stiffid::internal::robot::file::parse(&text, "r.toml").unwrap();
    match &robot.bodies() {
        Bodies::Capsules(r) => close(r[2], 0.195, 1e-12),
        other => panic!("{other:?}"),
    }
    let files = HashMap::from([(PathBuf::from("r.toml"), text.clone())]);
    let read = |p: &Path| files.get(p).cloned().map(Ok::<_, stiffid::Error>);
    let setup_text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .replace("robot = \"comau-smart5-nj165-3.0\"", "robot = \"r.toml\"");
    let setup = reference::setup_text(&setup_text, "s.toml", Path::new(""), read).unwrap();
    close(setup.geometry().link_radii[2], 0.195, 1e-12);
    let bad = text.replace("[350, 260", "[0, 260");
    let e = stiffid::internal::robot::file::parse(&bad, "r.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("r.toml: robot_geometry.link_radius_mm"), "{e}");
    let e = stiffid::internal::robot::file::parse(&format!("{text}tool_radius_mm = 5\n"), "r.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("tool_radius_mm"), "{e}");
}
