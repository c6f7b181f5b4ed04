//! The robot's own collision meshes from the command line: a generated URDF with STL meshes in a
//! ROS package, found through the setup's `package_paths` or `--package-path`, its hulls in the
//! plan and its drawings; an unresolved package named.

#[path = "../../../stiffid/tests/support/mesh_robot.rs"]
mod mesh_robot;

use crate::common::{assert_success, assert_usage_error, stiffid, temp_dir, write_file};
use std::path::Path;

/// The mesh robot's package under a new directory `name`, with its cell setup as `cell.toml`.
fn package(name: &str) -> std::path::PathBuf {
    let dir = temp_dir(name);
    for (path, bytes) in mesh_robot::files(24) {
        let path = dir.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, bytes).unwrap();
    }
    write_file(&dir, "cell.toml", &mesh_robot::setup_toml());
    dir
}

fn arg(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_plan_in_the_cell_is_drawn_with_the_robots_own_meshes() {
    let dir = package("bodies-plan");
    let (report, out) = (dir.join("plan"), dir.join("group.csv"));
    let run = stiffid(&[
        "select",
        "--setup",
        arg(&dir.join("cell.toml")),
        "--global",
        "--starts",
        "2",
        "--max-evals",
        "300",
        "--report",
        arg(&report),
        "--out",
        arg(&out),
    ]);
    assert_success(&run);
    let html = std::fs::read_to_string(report.join("plan.html")).unwrap();
    assert!(
        html.contains("the robot's own 7 collision shapes"),
        "{}",
        &html[..html.len().min(2000)]
    );
    assert!(report.join("figures/postures.svg").exists());
    // Every posture of the group passes the exact checks with the hulls.
    let evaluated = stiffid(&[
        "evaluate",
        "--setup",
        arg(&dir.join("cell.toml")),
        "--postures",
        arg(&out),
        "--json",
    ]);
    let v = crate::common::json(&evaluated);
    let feasibility = v["feasibility"].as_array().unwrap();
    assert_eq!(feasibility.len(), 6);
    assert!(
        feasibility.iter().all(|f| f["feasible"] == true),
        "{feasibility:?}"
    );
}

#[test]
fn package_path_finds_the_package_or_the_error_names_it() {
    let dir = package("bodies-package");
    let text = mesh_robot::setup_toml().replace("package_paths = [\".\"]\n", "");
    let setup = write_file(&dir, "bare.toml", &text);
    let postures = write_file(
        &dir,
        "p.csv",
        "posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n1,0,0,0,0,0,0\n",
    );
    let figures = dir.join("figures");
    let plot = |extra: &[&str]| {
        let mut args = vec![
            "plot",
            "--setup",
            arg(&setup),
            "--postures",
            arg(&postures),
            "--out",
            arg(&figures),
        ];
        args.extend_from_slice(extra);
        stiffid(&args)
    };
    assert_usage_error(
        &plot(&[]),
        &["package 'mesh_robot'", "package path", "base_link"],
    );
    assert!(!figures.exists());
    assert_usage_error(
        &plot(&["--package-path", arg(&dir.join("elsewhere"))]),
        &["package 'mesh_robot' not found in the package paths"],
    );
    let drawn = plot(&["--package-path", arg(&dir)]);
    assert_success(&drawn);
    assert!(figures.join("posture_01.svg").exists());
}
