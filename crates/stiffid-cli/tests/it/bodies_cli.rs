//! The robot's own collision meshes from the command line: a generated URDF with STL meshes in a
//! ROS package, found through the setup's `package_paths` or `--package-path`, its hulls in the
//! plan and its drawings; an unresolved package named.

#[path = "../../../stiffid/tests/support/mesh_robot.rs"]
mod mesh_robot;

use crate::common::{assert_success, stiffid, temp_dir, write_file};
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

/// Six postures of the mesh robot, within its setup's bounds.
const SIX: &str = "posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n1,0,0,-90,0,30,0\n\
    2,20,30,-60,40,-50,60\n3,-40,-20,-100,-90,60,-30\n4,60,40,-30,120,-80,90\n\
    5,-70,10,-120,60,20,-150\n6,30,-40,-40,-150,90,150\n";

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
    // The warning that the meshes were not found, then the error of the cell's checks.
    let refused = plot(&[]);
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.starts_with("warning: ") && stderr.lines().count() == 2,
        "{stderr}"
    );
    let error = stderr.lines().last().unwrap();
    for part in [
        "error: [cell]: ",
        "package 'mesh_robot'",
        "--package-path",
        "base_link",
    ] {
        assert!(error.contains(part), "{part}: {stderr}");
    }
    assert!(!figures.exists());
    let refused = plot(&["--package-path", arg(&dir.join("elsewhere"))]);
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("package 'mesh_robot' not found in the package paths"),
        "{stderr}"
    );
    let drawn = plot(&["--package-path", arg(&dir)]);
    assert_success(&drawn);
    assert!(figures.join("posture_01.svg").exists());
}

#[test]
fn kinematics_needs_no_meshes_only_the_cells_checks_do() {
    let dir = package("bodies-no-meshes");
    let urdf = dir.join(mesh_robot::URDF);
    let q = ["--q-deg", "0,10,-80,0,30,0"];
    let with = stiffid(&[
        "kinematics",
        "--robot",
        arg(&urdf),
        "--package-path",
        arg(&dir),
        q[0],
        q[1],
    ]);
    assert_success(&with);
    assert!(
        with.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&with.stderr)
    );
    let without = stiffid(&["kinematics", "--robot", arg(&urdf), q[0], q[1]]);
    assert_success(&without);
    assert_eq!(without.stdout, with.stdout);
    let stderr = String::from_utf8_lossy(&without.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("package 'mesh_robot'") && stderr.contains("--package-path"),
        "{stderr}"
    );
    // A setup without a cell: everything goes on; with one, the body checks name --package-path.
    let text = mesh_robot::setup_toml().replace("package_paths = [\".\"]\n", "");
    let cell_at = text.find("[cell]").unwrap();
    let bare = write_file(&dir, "bare.toml", &text[..cell_at]);
    let cell = write_file(&dir, "bare-cell.toml", &text);
    let postures = write_file(&dir, "p.csv", SIX);
    let evaluate = |setup: &Path| {
        stiffid(&[
            "evaluate",
            "--setup",
            arg(setup),
            "--postures",
            arg(&postures),
        ])
    };
    let evaluated = evaluate(&bare);
    assert_success(&evaluated);
    let stderr = String::from_utf8_lossy(&evaluated.stderr);
    assert_eq!(stderr.matches("--package-path").count(), 1, "{stderr}");
    let refused = evaluate(&cell);
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    let error = stderr.lines().last().unwrap();
    assert!(error.starts_with("error: [cell]: "), "{stderr}");
    for part in ["collision meshes", "--package-path DIR", "base_link"] {
        assert!(error.contains(part), "{part}: {stderr}");
    }
}

#[test]
fn setups_new_writes_the_package_paths_it_was_given() {
    let dir = package("bodies-setups-new");
    let urdf = dir.join(mesh_robot::URDF);
    std::fs::create_dir_all(dir.join("cells/a")).unwrap();
    let out = dir.join("cells/a/new.toml");
    let new = [
        "setups",
        "new",
        "--robot",
        arg(&urdf),
        "--package-path",
        arg(&dir),
        "--out",
        arg(&out),
    ];
    let written = stiffid(&new);
    assert_success(&written);
    assert!(
        written.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&written.stderr)
    );
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("\npackage_paths = [\"../..\"]\n"), "{text}");
    // As written, with its cell: the meshes are found (no warning), the body checks run.
    let with_cell = text
        .replace("# [cell]", "[cell]")
        .replace("# floor_z_mm", "floor_z_mm");
    let cell = write_file(&dir, "cells/a/with-cell.toml", &with_cell);
    let postures = write_file(&dir, "p.csv", SIX);
    let evaluated = stiffid(&[
        "evaluate",
        "--setup",
        arg(&cell),
        "--postures",
        arg(&postures),
    ]);
    assert_success(&evaluated);
    assert!(
        evaluated.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&evaluated.stderr)
    );
    assert!(String::from_utf8_lossy(&evaluated.stdout).contains("self-collision"));
}
