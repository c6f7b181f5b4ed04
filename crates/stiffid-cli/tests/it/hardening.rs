//! Bad, extreme and hostile input, one test per class of issue 9: every command answers with exit
//! code 2, one `error: ` line naming the file, field or option and the value given (shortened),
//! no panic, nothing written and every input unchanged byte for byte.

use crate::common;

use common::{assert_success, json, refused, stiffid, temp_dir, write_file, GROUP};
use std::path::{Path, PathBuf};

const SETUP: &str = "zhang2021-comau-nj165";

/// A scratch directory holding `g.csv` (six postures) and `my.toml` (the paper setup's TOML).
fn scratch(name: &str) -> PathBuf {
    let dir = temp_dir(name);
    write_file(&dir, "g.csv", GROUP);
    let toml = stiffid(&["setups", "show", SETUP]);
    assert_success(&toml);
    std::fs::write(dir.join("my.toml"), toml.stdout).unwrap();
    dir
}

/// The paper setup's TOML with `from` replaced by `to` (which must occur).
fn setup_with(dir: &Path, name: &str, from: &str, to: &str) -> PathBuf {
    let text = std::fs::read_to_string(dir.join("my.toml")).unwrap();
    assert!(text.contains(from), "{from}");
    write_file(dir, name, &text.replacen(from, to, 1))
}

fn urdf_fixture() -> String {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../stiffid/tests/data/comau-nj165.urdf"
    );
    std::fs::read_to_string(path).unwrap()
}

fn select_args<'a>(setup: &'a str, out: &'a str) -> Vec<&'a str> {
    vec![
        "select",
        "--setup",
        setup,
        "--criterion",
        "classical",
        "--start",
        "{dir}/g.csv",
        "--max-evals",
        "20",
        "--out",
        out,
    ]
}

/// `select` from a seeded random start group, a short search, on the paper setup, writing `out`.
#[rustfmt::skip]
fn random_select_args(out: &str) -> [&str; 10] {
    ["select", "--setup", SETUP, "--criterion", "classical",
     "--start-random", "--max-evals", "20", "--out", out]
}

#[test]
fn special_files_are_never_replaced_and_symlinks_are_written_through() {
    let dir = scratch("special");
    std::fs::create_dir(dir.join("sub")).unwrap();
    let line = refused(
        &dir,
        &select_args(SETUP, "{dir}/sub"),
        &["--out", "sub", "directory"],
    );
    assert!(line.contains("not a regular file"), "{line}");
    let device = assert_usage_error_dev(&random_select_args("/dev/null"));
    assert!(device.contains("a device"), "{device}");
    std::os::unix::fs::symlink("target.csv", dir.join("link.csv")).unwrap();
    write_file(&dir, "target.csv", "old");
    let out = dir.join("link.csv");
    let args = random_select_args(out.to_str().unwrap());
    assert_success(&stiffid(&args));
    assert!(std::fs::symlink_metadata(&out)
        .unwrap()
        .file_type()
        .is_symlink());
    let written = std::fs::read_to_string(dir.join("target.csv")).unwrap();
    assert!(written.starts_with("posture,q1_deg"), "{written}");
    std::os::unix::fs::symlink("nowhere.csv", dir.join("dangling.csv")).unwrap();
    refused(
        &dir,
        &select_args(SETUP, "{dir}/dangling.csv"),
        &["dangling.csv", "symlink to nothing"],
    );
}

/// A failing command with an output outside the scratch directory (a device): the usual checks.
fn assert_usage_error_dev(args: &[&str]) -> String {
    let meta = std::fs::metadata("/dev/null").unwrap();
    let line = common::assert_usage_error(&stiffid(args), &["--out", "/dev/null"]);
    use std::os::unix::fs::FileTypeExt;
    let after = std::fs::metadata("/dev/null").unwrap();
    assert!(after.file_type().is_char_device() && meta.file_type() == after.file_type());
    line
}

#[test]
fn no_output_is_written_over_an_input() {
    let dir = scratch("inputs");
    refused(
        &dir,
        &select_args("{dir}/my.toml", "{dir}/my.toml"),
        &["--out", "my.toml", "input file"],
    );
    refused(
        &dir,
        &select_args(SETUP, "{dir}/g.csv"),
        &["input file", "g.csv"],
    );
    std::os::unix::fs::symlink("my.toml", dir.join("alias.toml")).unwrap();
    refused(
        &dir,
        &select_args("{dir}/my.toml", "{dir}/alias.toml"),
        &["input file", "my.toml"],
    );
    std::fs::create_dir(dir.join("report")).unwrap();
    write_file(&dir.join("report"), "deviation_rates.csv", GROUP);
    let sim = |force: bool| {
        let mut a = vec![
            "simulate",
            "--setup",
            SETUP,
            "--postures",
            "{dir}/report/deviation_rates.csv",
            "--runs",
            "2",
            "--out",
            "{dir}/report",
        ];
        if force {
            a.push("--force");
        }
        a
    };
    refused(
        &dir,
        &sim(false),
        &["--out", "report", "not empty", "--force"],
    );
    refused(&dir, &sim(true), &["deviation_rates.csv", "input file"]);
}

#[test]
fn long_names_work_and_failures_leave_nothing_behind() {
    let dir = scratch("leftovers");
    let name = format!("{}.csv", "p".repeat(251));
    let out = dir.join(&name);
    let args = random_select_args(out.to_str().unwrap());
    assert_success(&stiffid(&args));
    assert!(out.is_file());
    // A group that cannot identify joint 6 fails after the output directory was created: it goes.
    let j6 = setup_with(
        &dir,
        "j6.toml",
        "loading_point_mm = [150.0, 0.0, 200.0]",
        "loading_point_mm = [0.0, 0.0, 100.0]",
    );
    let new = dir.join("new/deeper");
    let e = stiffid(&[
        "simulate",
        "--setup",
        j6.to_str().unwrap(),
        "--postures",
        dir.join("g.csv").to_str().unwrap(),
        "--runs",
        "2",
        "--out",
        new.to_str().unwrap(),
    ]);
    common::assert_usage_error(&e, &["joint 6 cannot be identified"]);
    assert!(
        !dir.join("new").exists(),
        "the directories it created are removed"
    );
    // A stale temporary directory of a killed run is cleaned up by the next run.
    let report = dir.join("report");
    std::fs::create_dir_all(report.join(".stiffid-tmp")).unwrap();
    write_file(&report.join(".stiffid-tmp"), "killed.tmp", "half");
    let g = dir.join("g.csv");
    assert_success(&stiffid(&[
        "simulate",
        "--setup",
        SETUP,
        "--postures",
        g.to_str().unwrap(),
        "--runs",
        "2",
        "--out",
        report.to_str().unwrap(),
    ]));
    let mut names: Vec<_> = std::fs::read_dir(&report)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    names.sort();
    assert_eq!(names, ["deviation_rates.csv", "simulation.json"]);
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[test]
fn an_unwritable_report_directory_is_refused_before_computing() {
    let dir = scratch("unwritable");
    write_file(&dir, "file", "x");
    // The default study would run for minutes: the error comes first.
    refused(
        &dir,
        &["reproduce", "--out", "{dir}/file/report"],
        &["--out", "file/report", "Not a directory"],
    );
    refused(
        &dir,
        &["reproduce", "--out", "{dir}/file"],
        &["--out", "not a directory"],
    );
    refused(
        &dir,
        &[
            "select",
            "--setup",
            SETUP,
            "--criterion",
            "classical",
            "--global",
            "--out",
            "{dir}/none/x.csv",
        ],
        &["--out", "no directory"],
    );
}

#[test]
fn every_count_has_a_limit_named_in_the_message() {
    let dir = scratch("counts");
    let simulate = ["simulate", "--setup", SETUP, "--postures", "{dir}/g.csv"];
    let reproduce = ["reproduce", "--out", "{dir}/r"];
    let select = ["select", "--setup", SETUP, "--criterion", "classical"];
    let global = [&select[..], &["--global", "--out", "{dir}/x.csv"]].concat();
    let random = [&select[..], &["--start-random", "--out", "{dir}/x.csv"]].concat();
    // (command, option, value given, what the message must show)
    let cases: [(&[&str], &str, &str, &str); 10] = [
        (
            &simulate,
            "--runs",
            "3074457345618258603",
            "3074457345618258603",
        ),
        (
            &simulate,
            "--runs",
            "9223372036854775808",
            "9223372036854775808",
        ),
        (&simulate, "--runs", "1000000000", "1000000000"),
        (&reproduce, "--runs", "4611686018427387904", "1..=100000"),
        (&reproduce, "--trials", "1000000000", "0..=2000"),
        (&reproduce, "--starts", "1000000000", "1..=10000"),
        (&global, "--starts", "1000000000", "1000000000"),
        (&random, "--count", "1000000000", "2..=100"),
        (&random, "--max-evals", "99999999999", "99999999999"),
        (&random, "--seed", "-1", "-1"),
    ];
    for (command, option, value, shown) in cases {
        let given = format!("{option}={value}");
        let args = [command, &[given.as_str()]].concat();
        refused(&dir, &args, &[option, shown]);
    }
}

#[test]
fn every_setup_field_is_checked_at_load_time() {
    let dir = scratch("fields");
    for (from, to, mention) in [
        (
            "level_multiples = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0]",
            "level_multiples = []",
            "noise.level_multiples: 0 entries",
        ),
        (
            "level_multiples = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0]",
            "level_multiples = [0.5, nan]",
            "noise.level_multiples[2]: NaN",
        ),
        (
            "name = \"zhang2021-comau-nj165\"",
            "name = \"  \"",
            "name: expected a non-empty name",
        ),
        (
            "nominal_stiffness_nm_per_rad = [950000.0",
            "nominal_stiffness_nm_per_rad = [1e-320",
            "nominal_stiffness_nm_per_rad[1]: 1e-320 is outside [1, 1e10] Nm/rad",
        ),
        (
            "reading_sd_mm = 0.006793379129711516",
            "reading_sd_mm = 0.0",
            "noise.reading_sd_mm: 0 is outside",
        ),
        (
            "load_n = 500.0",
            "load_n = 1e308",
            "loading.load_n: 1e308 is outside",
        ),
        (
            "anchor_mm = [2000.0,",
            "anchor_mm = [inf,",
            "loading.anchor_mm[1]: inf",
        ),
    ] {
        let path = setup_with(&dir, "bad.toml", from, to);
        let p = path.to_str().unwrap();
        refused(
            &dir,
            &["evaluate", "--setup", p, "--postures", "{dir}/g.csv"],
            &["bad.toml", mention],
        );
        simulate_refused(&dir, p, &[mention]);
    }
}

#[test]
fn a_deeply_nested_urdf_is_refused_before_parsing() {
    let dir = temp_dir("deep-urdf");
    let deep = format!(
        "<robot name=\"r\">{}{}</robot>",
        "<a>".repeat(20_000),
        "</a>".repeat(20_000)
    );
    write_file(&dir, "deep.urdf", &deep);
    kinematics_refused(
        &dir,
        "{dir}/deep.urdf",
        "0,0,0,0,0,0",
        &["deep.urdf", "nest deeper than 64"],
    );
    // Quoted '>' and '/>' do not hide elements.
    let hidden = format!(
        "<robot name=\"r\">{}</robot>",
        "<a x=\"/>\">".repeat(20_000)
    );
    write_file(&dir, "hidden.urdf", &hidden);
    kinematics_refused(&dir, "{dir}/hidden.urdf", "0,0,0,0,0,0", &["nest deeper"]);
}

#[test]
fn stdout_write_errors_are_an_error_exit() {
    let full = std::fs::File::options()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stiffid"))
        .args(["setups", "show", SETUP])
        .stdout(full)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.starts_with("error: stdout: cannot write"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn input_files_have_a_size_limit() {
    let dir = temp_dir("size");
    refused(
        &dir,
        &["evaluate", "--setup", SETUP, "--postures", "/dev/zero"],
        &["/dev/zero", "is a device, not a regular file"],
    );
    refused(
        &dir,
        &["evaluate", "--setup", SETUP, "--postures", "{dir}"],
        &["is a directory"],
    );
    std::fs::write(dir.join("bin.csv"), [0xff, 0xfe, 0x00]).unwrap();
    refused(
        &dir,
        &["evaluate", "--setup", SETUP, "--postures", "{dir}/bin.csv"],
        &["bin.csv", "not UTF-8"],
    );
}

/// A URDF revolute joint without `<limit>` is unlimited: a setup on it gives the experiment's
/// bounds, or is refused naming them (never a bound of -inf the file does not hold).
#[test]
fn a_joint_without_limits_needs_the_experiments_bounds() {
    let dir = scratch("unlimited");
    let limit = r#"<limit lower="-3.2" upper="3.2" effort="1000" velocity="2"/>"#;
    let urdf = urdf_fixture();
    assert!(urdf.contains(limit));
    write_file(&dir, "u.urdf", &urdf.replacen(limit, "", 1));
    let robot = "robot = \"comau-smart5-nj165-3.0\"";
    let bounded = setup_with(&dir, "bounded.toml", robot, "robot = \"u.urdf\"");
    let text = std::fs::read_to_string(&bounded).unwrap();
    let (head, tail) = text.split_once("[bounds]").unwrap();
    let tail = tail.split_once("[test]").unwrap().1;
    write_file(&dir, "unbounded.toml", &format!("{head}[test]{tail}"));
    let evaluate =
        |setup: &'static str| ["evaluate", "--setup", setup, "--postures", "{dir}/g.csv"];
    let line = refused(
        &dir,
        &evaluate("{dir}/unbounded.toml"),
        &["bounds", "joint 1 has no limits"],
    );
    assert!(!line.contains("inf"), "{line}");
    let d = dir.to_str().unwrap();
    let args = evaluate("{dir}/bounded.toml").map(|a| a.replace("{dir}", d));
    assert_success(&stiffid(
        &args.iter().map(String::as_str).collect::<Vec<_>>(),
    ));
}

#[test]
fn non_finite_or_absurd_robot_geometry_is_refused() {
    let dir = temp_dir("geometry");
    let urdf = urdf_fixture();
    for (from, to, mention) in [
        (
            "xyz=\"0.1 -0.2 0.5\"",
            "xyz=\"NaN -0.2 0.5\"",
            "joint 'mount': origin xyz[1]: NaN",
        ),
        (
            "xyz=\"0.1 -0.2 0.5\"",
            "xyz=\"0.1 inf 0.5\"",
            "origin xyz[2]: inf",
        ),
        (
            "xyz=\"0 0 0.83\"",
            "xyz=\"0 0 1e308\"",
            "1e308 is outside [-100, 100] m",
        ),
        ("rpy=\"0 0 0.7\"", "rpy=\"0 0 -inf\"", "origin rpy[3]: -inf"),
    ] {
        assert!(urdf.contains(from), "{from}");
        write_file(&dir, "r.urdf", &urdf.replacen(from, to, 1));
        kinematics_refused(&dir, "{dir}/r.urdf", "0,0,0,0,0,0", &["r.urdf", mention]);
    }
    let preset = stiffid::internal::robot::presets::text("comau-smart5-nj165-3.0").unwrap();
    for (extra, mention) in [
        ("\n[base]\nxyz_mm = [nan, 0, 0]\n", "base.xyz_mm[1]: NaN"),
        (
            "\n[flange]\nrpy_deg = [0, inf, 0]\n",
            "flange.rpy_deg[2]: inf",
        ),
        // A direction has no unit: the range is named without one.
        (
            "\n[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1e308, 0, 0]\nlimits_mm = [0, 6000]\n",
            "(track).direction[1]: 1e308 is outside [-100000, 100000]\n",
        ),
    ] {
        write_file(&dir, "r.toml", &format!("{preset}{extra}"));
        kinematics_refused(&dir, "{dir}/r.toml", "0,0,-90,0,0,0", &["r.toml", mention]);
    }
    write_file(
        &dir,
        "r.toml",
        &preset.replacen("d_mm = 830.0", "d_mm = 1e308", 1),
    );
    kinematics_refused(
        &dir,
        "{dir}/r.toml",
        "0,0,-90,0,0,0",
        &["joint[1].d_mm: 1e308 is outside [-100000, 100000] mm"],
    );
}

#[test]
fn a_stiffness_outside_the_physical_range_is_refused() {
    let dir = scratch("stiffness");
    let predict = [
        "predict",
        "--setup",
        SETUP,
        "--q-deg",
        "0,0,-90,0,0,0",
        "--wrench",
    ];
    for (k, mention) in [
        ("1e-320", "[1]: 1e-320 is outside [1, 1e10] Nm/rad"),
        ("1e300", "[1]: 1e300 is outside"),
    ] {
        write_file(
            &dir,
            "k.json",
            &format!("{{\"stiffness_nm_per_rad\": [{k}, 1e6, 1e6, 1e6, 1e6, 1e6]}}"),
        );
        let args = [&predict[..], &["0,0,100", "--stiffness", "{dir}/k.json"]].concat();
        refused(&dir, &args, &["k.json", mention]);
    }
    refused(
        &dir,
        &[&predict[..], &["0,0,1e300"]].concat(),
        &["--wrench[3]: 1e300 is outside"],
    );
}

#[test]
fn infinite_values_say_why() {
    let dir = scratch("infinite");
    // A full-rank group with one wrist-singular posture (q5 = 0).
    let wrist = GROUP.replacen("1,10,-20,-100,30,40,-60", "1,10,-20,-100,30,0,-60", 1);
    let path = write_file(&dir, "wrist.csv", &wrist);
    let evaluate = |extra: &[&str]| {
        let args = [
            "evaluate",
            "--setup",
            SETUP,
            "--postures",
            path.to_str().unwrap(),
        ];
        stiffid(&[&args[..], extra].concat())
    };
    let out = evaluate(&[]);
    assert_success(&out);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("classical    infinite (a posture is singular"),
        "{text}"
    );
    assert!(!text.contains("rank deficient"), "{text}");
    let doc = json(&evaluate(&["--json"]));
    assert!(doc["classical"].is_null() && doc["zhang2021"].is_null());
    // The document says why: the singular posture, for exactly the two criteria it makes
    // infinite.
    assert_eq!(
        doc["infinite"],
        serde_json::json!([
            {"criterion": "classical", "reason": "singular"},
            {"criterion": "zhang2021", "reason": "singular"}
        ])
    );
    assert!(doc["relative_a"]
        .as_f64()
        .is_some_and(|v| v.is_finite() && v > 0.0));
    // A wrist-singular posture in `kinematics`: tests/schemas.rs (dexterity null).
}

#[test]
fn select_and_evaluate_name_the_joint_that_cannot_be_identified() {
    let dir = scratch("unidentifiable");
    // A loading point on the joint-6 axis never loads joint 6.
    let j6 = setup_with(
        &dir,
        "j6.toml",
        "loading_point_mm = [150.0, 0.0, 200.0]",
        "loading_point_mm = [0.0, 0.0, 100.0]",
    );
    let p = j6.to_str().unwrap();
    refused(
        &dir,
        &["evaluate", "--setup", p, "--postures", "{dir}/g.csv"],
        &["g.csv", "joint 6 cannot be identified"],
    );
    refused(
        &dir,
        &[
            "select",
            "--setup",
            p,
            "--criterion",
            "relative-a",
            "--start-random",
            "--max-evals",
            "50",
            "--out",
            "{dir}/out.csv",
        ],
        &["joint 6 cannot be identified"],
    );
    simulate_refused(&dir, p, &["joint 6 cannot be identified"]);
}

#[test]
fn postures_files_group_names_and_bounds() {
    let dir = scratch("groups");
    let outside = GROUP.replacen("1,10,-20,-100", "1,10,-80,-100", 1);
    write_file(&dir, "outside.csv", &outside);
    refused(
        &dir,
        &[
            "evaluate",
            "--setup",
            SETUP,
            "--postures",
            "{dir}/outside.csv",
        ],
        &["outside.csv", "line 2", "q2_deg = -80", "setup's bounds"],
    );
    refused(
        &dir,
        &[
            "simulate",
            "--setup",
            SETUP,
            "--postures",
            "{dir}/outside.csv",
            "--runs",
            "2",
        ],
        &["line 2", "bounds"],
    );
    write_file(&dir, "a,b.csv", GROUP);
    std::fs::create_dir(dir.join("x")).unwrap();
    write_file(&dir.join("x"), "g.csv", GROUP);
    let d = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let out = d("sim");
    assert_success(&stiffid(&[
        "simulate",
        "--setup",
        SETUP,
        "--postures",
        &d("a,b.csv"),
        &d("g.csv"),
        &d("x/g.csv"),
        "--runs",
        "2",
        "--out",
        &out,
    ]));
    let csv = std::fs::read_to_string(dir.join("sim/deviation_rates.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let mut groups: Vec<String> = reader
        .records()
        .map(|r| r.unwrap()[0].to_string())
        .collect();
    groups.dedup();
    assert_eq!(groups, ["a,b".to_string(), d("g.csv"), d("x/g.csv")]);
}

#[test]
fn urdf_diagnostics_name_the_problem() {
    let dir = temp_dir("urdf-diagnostics");
    let urdf = urdf_fixture();
    let cases = [
        (
            "<parent link=\"world\"/>",
            "<parent link=\"nowhere\"/>",
            "joint 'mount' names the parent link 'nowhere', which is not declared",
        ),
        (
            "<child link=\"link_1\"/>",
            "<child link=\"link_1_rot\"/>",
            "link 'link_1_rot' is the child of two joints",
        ),
        (
            "<link name=\"world\"/>",
            "<link name=\"world\"/><link name=\"island\"/>",
            "the links are not connected: 2 links have no parent joint (world, island)",
        ),
        (
            "<link name=\"link_5\"/>",
            "<link name=\"link_5\"/><link name=\"link_5\"/>",
            "link 'link_5' is declared twice",
        ),
        (
            "<joint name=\"d_1\" type=\"fixed\">",
            "<joint name=\"joint_1\" type=\"fixed\">",
            "joint 'joint_1' is declared twice",
        ),
        (
            "</robot>",
            "</robot>\n<robot name=\"second\"/>",
            "an element follows the document's root element: '<robot name=\"second\"/>'",
        ),
        (
            "<axis xyz=\"0 0 1\"/>",
            "<axis xyz=\"NaN 0 1\"/>",
            "joint 'joint_1': axis xyz[1]: NaN",
        ),
        (
            "<axis xyz=\"0 0 1\"/>",
            "<axis xyz=\"0 0 1\"/><orgin xyz=\"0 0 0.1\"/>",
            "<orgin> in a <joint> is not a URDF element; did you mean <origin>?",
        ),
        (
            "<link name=\"link_5\"/>",
            "<link name=\"link_5\"><inertial><mas value=\"1\"/></inertial></link>",
            "<mas> in a <inertial> is not a URDF element; did you mean <mass>?",
        ),
        (
            "lower=\"-3.2\" upper=\"3.2\"",
            "lower=\"3.2\" upper=\"-3.2\"",
            "joint 'joint_1': limit lower = 3.2 is not below upper = -3.2",
        ),
        (
            "lower=\"-3.2\" upper=\"3.2\"",
            "lower=\"NaN\" upper=\"3.2\"",
            "joint 'joint_1': limit lower, upper[1]: NaN",
        ),
    ];
    for (from, to, mention) in cases {
        assert!(urdf.contains(from), "{from}");
        write_file(&dir, "r.urdf", &urdf.replacen(from, to, 1));
        kinematics_refused(&dir, "{dir}/r.urdf", "0,0,0,0,0,0", &["r.urdf", mention]);
    }
    // A well-conditioned axis map of determinant 1e-18 is accepted; a singular one is not.
    let preset = stiffid::internal::robot::presets::text("kuka-kr210-robond").unwrap();
    let scaled = "\n[axis_map]\nmatrix = [[0.001,0,0,0,0,0],[0,0.001,0,0,0,0],[0,0,0.001,0,0,0],[0,0,0,0.001,0,0],[0,0,0,0,0.001,0],[0,0,0,0,0,0.001]]\noffset_deg = [0,0,0,0,0,0]\n";
    assert!(!preset.contains("\n[axis_map]"));
    write_file(&dir, "r.toml", &format!("{preset}{scaled}"));
    let r = dir.join("r.toml");
    assert_success(&stiffid(&[
        "kinematics",
        "--robot",
        r.to_str().unwrap(),
        "--q-deg",
        "0,0,0,0,0,0",
    ]));
    write_file(
        &dir,
        "r.toml",
        &format!("{preset}{}", scaled.replace("0.001]]", "0]]")),
    );
    kinematics_refused(
        &dir,
        "{dir}/r.toml",
        "0,0,0,0,0,0",
        &["axis_map.matrix", "condition number is inf"],
    );
}

/// The line of a misspelt URDF element is named; legacy and extension elements a URDF reader
/// passes over (`<joint_properties>`, `<drake:gear_ratio>`) pass, the robot unchanged.
#[test]
fn urdf_misspelt_elements_are_named_and_extensions_pass() {
    let dir = temp_dir("urdf-misspelt");
    let urdf = urdf_fixture();
    let misspelt = urdf.replacen("<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 0 1\"/><orgin/>", 1);
    let line = 1 + misspelt[..misspelt.find("<orgin/>").unwrap()]
        .matches('\n')
        .count();
    write_file(&dir, "r.urdf", &misspelt);
    kinematics_refused(
        &dir,
        "{dir}/r.urdf",
        "0,0,0,0,0,0",
        &[&format!("line {line}: <orgin>")],
    );
    let kinematics = |urdf: &str| {
        write_file(&dir, "r.urdf", urdf);
        let r = dir.join("r.urdf");
        let out = stiffid(&[
            "kinematics",
            "--robot",
            r.to_str().unwrap(),
            "--q-deg",
            "10,20,30,40,50,60",
        ]);
        assert_success(&out);
        out.stdout
    };
    let extended = urdf
        .replacen(
            "<robot name=\"comau_nj165_test\">",
            "<robot name=\"comau_nj165_test\" xmlns:drake=\"http://drake.mit.edu\">",
            1,
        )
        .replacen(
            "<axis xyz=\"0 0 1\"/>",
            "<axis xyz=\"0 0 1\"/><joint_properties damping=\"0\"/><drake:gear_ratio value=\"1\"/>",
            1,
        );
    assert_ne!(extended, urdf);
    assert_eq!(kinematics(&extended), kinematics(&urdf));
}

#[test]
fn long_values_are_cut_and_numbers_are_short() {
    let dir = scratch("long");
    let field = "x".repeat(5_000_000);
    write_file(
        &dir,
        "long.toml",
        &format!("name = \"r\"\nconvention = \"{field}\"\n"),
    );
    let line = kinematics_refused(
        &dir,
        "{dir}/long.toml",
        "0,0,0,0,0,0",
        &["long.toml", "..."],
    );
    assert!(line.len() < 1000, "{} bytes", line.len());
    let posture = GROUP.replacen("1,10,-20", &format!("1,10,{field}"), 1);
    write_file(&dir, "long.csv", &posture);
    let line = refused(
        &dir,
        &["evaluate", "--setup", SETUP, "--postures", "{dir}/long.csv"],
        &["long.csv", "line 2", "q2_deg", "..."],
    );
    assert!(line.len() < 300, "{} bytes", line.len());
    let line = refused(
        &dir,
        &[
            "kinematics",
            "--robot",
            "comau-smart5-nj165-3.0",
            "--q-deg",
            &format!("0,0,{},0,0,0", &field[..100_000]),
        ],
        &["--q-deg", "value 3"],
    );
    assert!(line.len() < 300, "{} bytes", line.len());
    kinematics_refused(
        &dir,
        "comau-smart5-nj165-3.0",
        "0,0,1e308,0,0,0",
        &["--q-deg[3]: 1e308 is outside"],
    );
}

#[test]
fn a_saved_builtin_setup_works_from_any_directory() {
    let dir = scratch("saved-setup");
    let elsewhere = temp_dir("saved-setup-elsewhere");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stiffid"))
        .current_dir(&elsewhere)
        .args([
            "evaluate",
            "--setup",
            dir.join("my.toml").to_str().unwrap(),
            "--postures",
            dir.join("g.csv").to_str().unwrap(),
            "--json",
        ])
        .output()
        .unwrap();
    assert_success(&out);
    let missing = setup_with(
        &dir,
        "missing.toml",
        "robot = \"comau-smart5-nj165-3.0\"",
        "robot = \"robots/nj165.toml\"",
    );
    refused(
        &dir,
        &[
            "evaluate",
            "--setup",
            missing.to_str().unwrap(),
            "--postures",
            "{dir}/g.csv",
        ],
        &["robots/nj165.toml", "no file", "no preset"],
    );
    refused(
        &dir,
        &[
            "evaluate",
            "--setup",
            "{dir}/nothing.toml",
            "--postures",
            "{dir}/g.csv",
        ],
        &["nothing.toml", "no file", "and no built-in setup"],
    );
}

#[test]
fn report_markdown_escapes_html_from_the_setup() {
    let dir = scratch("markdown");
    let setup = setup_with(
        &dir,
        "xss.toml",
        "name = \"zhang2021-comau-nj165\"",
        "name = \"<script>alert(1)</script>\"",
    );
    let out = dir.join("report");
    let run = stiffid(&[
        "reproduce",
        "--setup",
        setup.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--runs",
        "2",
        "--starts",
        "1",
        "--trials",
        "0",
    ]);
    assert_success(&run);
    for file in ["report.md", "report.html"] {
        let text = std::fs::read_to_string(out.join(file)).unwrap();
        // Outside `code spans` (shown literally by Markdown) no raw tag.
        let prose: String = text.split('`').step_by(2).collect();
        assert!(!prose.contains("<script>"), "{file}");
        assert!(text.contains("&lt;script&gt;"), "{file}");
    }
    assert!(!out.join(".stiffid-tmp").exists());
}

#[test]
fn a_measurement_row_labelled_with_a_hash_is_not_dropped_as_a_comment() {
    let dir = temp_dir("hash-label");
    let data = std::fs::read_to_string(common::fanuc_csv()).unwrap();
    let mut lines: Vec<String> = data.lines().map(str::to_string).collect();
    lines[3] = format!("#{}", lines[3]);
    write_file(&dir, "hash.csv", &(lines.join("\n") + "\n"));
    refused(
        &dir,
        &[
            "identify",
            "--setup",
            "fanuc-r2000ic-165f",
            "--data",
            "{dir}/hash.csv",
        ],
        &["hash.csv", "line 4", "may not start with '#'"],
    );
}

/// `stiffid kinematics --robot ROBOT --q-deg Q` refused in `dir`, the message mentioning `mention`.
fn kinematics_refused(dir: &Path, robot: &str, q: &str, mention: &[&str]) -> String {
    refused(
        dir,
        &["kinematics", "--robot", robot, "--q-deg", q],
        mention,
    )
}

/// `stiffid simulate --setup SETUP --postures {dir}/g.csv --runs 2` refused in `dir`, the message
/// mentioning `mention`.
fn simulate_refused(dir: &Path, setup: &str, mention: &[&str]) {
    let args = [
        "simulate",
        "--setup",
        setup,
        "--postures",
        "{dir}/g.csv",
        "--runs",
        "2",
    ];
    refused(dir, &args, mention);
}

/// `--out` naming the data file the command reads is refused, whatever the order in which the
/// command reads its inputs and prepares its outputs, and the data are left byte for byte.
#[test]
fn out_on_the_data_file_is_refused_for_every_fit() {
    let dir = scratch("out-on-data");
    std::fs::copy(common::fanuc_csv(), dir.join("data.csv")).unwrap();
    let identify = |extra: &[&'static str]| -> Vec<&'static str> {
        let base = ["identify", "--setup", "fanuc-r2000ic-165f"];
        [
            &base[..],
            &["--data", "{dir}/data.csv", "--out", "{dir}/data.csv"],
            extra,
        ]
        .concat()
    };
    for extra in [
        &[][..],
        &["--compare-models"],
        &["--robust", "huber"],
        &["--folds", "3"],
    ] {
        refused(&dir, &identify(extra), &["input file", "data.csv"]);
    }
}

/// A model the group cannot separate (the base mount's `base_rz` turns about joint 1's axis):
/// `evaluate` says so for every infinite criterion and for the prediction, names the
/// combinations, and never blames the floating-point range.
#[test]
fn evaluate_names_a_model_the_group_cannot_separate() {
    let dir = scratch("inseparable");
    let text = std::fs::read_to_string(dir.join("my.toml")).unwrap();
    let model = "\n[[model.family]]\nfamily = \"base\"\nnominal_stiffness_nm_per_rad = 1e6\nnominal_stiffness_n_per_mm = 1e4\n";
    write_file(&dir, "base.toml", &(text + model));
    let d = dir.to_str().unwrap();
    let (setup, group) = (format!("{d}/base.toml"), format!("{d}/g.csv"));
    let out = stiffid(&["evaluate", "--setup", &setup, "--postures", &group]);
    assert_success(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(!stdout.contains("floating-point"), "{stdout}");
    assert!(
        stdout.contains("relative-a   infinite: the group cannot separate"),
        "{stdout}"
    );
    assert!(
        stdout.contains("not computed: the group cannot separate"),
        "{stdout}"
    );
    assert!(
        stdout.contains("cannot separate: ") && stdout.contains("base_rz"),
        "{stdout}"
    );
    // The document gives the same reason for every infinite criterion, relative_a among them.
    let doc = json(&stiffid(&[
        "evaluate",
        "--setup",
        &setup,
        "--postures",
        &group,
        "--json",
    ]));
    let infinite = doc["infinite"].as_array().unwrap();
    assert!(
        infinite.iter().any(|i| i["criterion"] == "relative_a"),
        "{infinite:?}"
    );
    for i in infinite {
        assert_eq!(i["reason"], "not-separable", "{i}");
        assert!(doc[i["criterion"].as_str().unwrap()].is_null(), "{i}");
    }
}

/// A stiffness file of the paper setup's six drives (`parameters`), `extra` JSON after them.
fn drives_file(identified_k6: &str, extra: &str) -> String {
    let k = [1e6, 2e6, 1e6, 3e5, 2e5, 1e5];
    let params: Vec<String> = (0..6)
        .map(|j| {
            let flag = match j {
                5 => identified_k6,
                _ => "",
            };
            format!(
                r#"{{"name": "k{}", "kind": "drive", "unit": "Nm/rad", "stiffness": {}{flag}}}"#,
                j + 1,
                k[j]
            )
        })
        .collect();
    format!(r#"{{"parameters": [{}]{extra}}}"#, params.join(", "))
}

#[test]
fn unidentified_parameters_and_unknown_keys_of_a_stiffness_file_are_refused() {
    let dir = scratch("stiffness-unidentified");
    let predict = |file: &Path| {
        vec![
            "predict".to_string(),
            "--setup".into(),
            SETUP.into(),
            "--q-deg".into(),
            "0,10,-80,0,30,0".into(),
            "--wrench".into(),
            "0,0,-1000".into(),
            "--stiffness".into(),
            file.to_str().unwrap().into(),
        ]
    };
    fn args(v: &[String]) -> Vec<&str> {
        v.iter().map(String::as_str).collect()
    }
    let good = write_file(
        &dir,
        "good.json",
        &drives_file(r#", "identified": true"#, ""),
    );
    assert_success(&stiffid(&args(&predict(&good))));
    let text = drives_file(
        r#", "identified": false, "ci95": null"#,
        r#", "unidentifiable": ["0.71 k6 - 0.71 tool_rz"]"#,
    );
    let bad = write_file(&dir, "unidentified.json", &text);
    refused(
        &dir,
        &args(&predict(&bad)),
        &[
            "unidentified.json: parameters[6].identified: false: identify could not identify 'k6' (the data cannot separate 0.71 k6 - 0.71 tool_rz)",
        ],
    );
    let misspelt = drives_file("", r#", "compliance_covariance": [[1]]"#);
    let bad = write_file(&dir, "misspelt.json", &misspelt);
    refused(
        &dir,
        &args(&predict(&bad)),
        &["misspelt.json: compliance_covariance: unknown key"],
    );
    let inner = drives_file(r#", "stifness": 3"#, "");
    let bad = write_file(&dir, "inner.json", &inner);
    refused(
        &dir,
        &args(&predict(&bad)),
        &["inner.json", "unknown field `stifness`"],
    );
}

/// `--compare-models` with `--offsets` (which it ignored) or on two postures (where it recommended
/// negative stiffness with no held-out error) is refused, saying the minimum.
#[test]
fn compare_models_refuses_offsets_and_too_few_postures() {
    let dir = scratch("compare-few");
    let text = std::fs::read_to_string(common::fanuc_csv()).unwrap();
    let two: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("posture") || l.starts_with("1,") || l.starts_with("2,"))
        .collect();
    write_file(&dir, "two.csv", &(two.join("\n") + "\n"));
    std::fs::copy(common::fanuc_csv(), dir.join("all.csv")).unwrap();
    let base = [
        "identify",
        "--setup",
        "fanuc-r2000ic-165f",
        "--compare-models",
    ];
    refused(
        &dir,
        &[&base[..], &["--data", "{dir}/two.csv"]].concat(),
        &[
            "two.csv",
            "postures: 2 given: comparing models needs at least 3 postures",
        ],
    );
    refused(
        &dir,
        &[&base[..], &["--data", "{dir}/all.csv", "--offsets"]].concat(),
        &["--compare-models", "--offsets"],
    );
}

/// `--bootstrap` needs `--compare-models` and takes 1 to 2000 resamples; `--seed` needs
/// `--bootstrap`. Each refusal names the option.
#[test]
fn bootstrap_is_refused_out_of_range_or_without_compare_models() {
    let dir = scratch("bootstrap-refused");
    std::fs::copy(common::fanuc_csv(), dir.join("all.csv")).unwrap();
    let base = [
        "identify",
        "--setup",
        "fanuc-r2000ic-165f",
        "--data",
        "{dir}/all.csv",
    ];
    let compare = [&base[..], &["--compare-models"]].concat();
    refused(
        &dir,
        &[&compare[..], &["--bootstrap", "0"]].concat(),
        &["--bootstrap: 0 resamples: expected 1 to 2000"],
    );
    refused(
        &dir,
        &[&compare[..], &["--bootstrap", "2001"]].concat(),
        &["--bootstrap: 2001 resamples: expected 1 to 2000"],
    );
    refused(
        &dir,
        &[&base[..], &["--bootstrap", "10"]].concat(),
        &["--compare-models"],
    );
    refused(
        &dir,
        &[&compare[..], &["--seed", "3"]].concat(),
        &["--bootstrap"],
    );
}
