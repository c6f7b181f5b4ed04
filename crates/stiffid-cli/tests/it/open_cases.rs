//! Steps that would land a program or a model off without a word, refused or stated: G-code
//! written back on a cell with external axes for a controller that runs its own nominal model.

use crate::common;

use common::{example, refused, stiffid, temp_dir, write_file};

/// The track along x and the turntable about z through (1330, -680) mm beside the part, the
/// table's axis moved by `shift_mm` along x.
fn axes(shift_mm: f64) -> String {
    format!("\n[[external_axis]]\nname = \"track\"\nrole = \"carrier\"\ndirection = [1.0, 0.0, 0.0]\nlimits_mm = [0.0, 6000.0]\n\n[[external_axis]]\nname = \"table\"\nrole = \"positioner\"\ndirection = [0.0, 0.0, 1.0]\npoint_mm = [{:?}, -680.0, 0.0]\nlimits_deg = [-360.0, 360.0]\n", 1330.0 + shift_mm)
}

/// The FANUC preset as a robot file named `name` with the cell's axes ([`axes`]).
fn robot_file(dir: &std::path::Path, file: &str, name: &str, shift_mm: f64) -> String {
    let preset = include_str!("../../../stiffid-core/presets/fanuc-r2000ic-165f.toml");
    let text = preset.replace(
        "name = \"FANUC R-2000iC/165F\"",
        &format!("name = \"{name}\""),
    );
    assert!(text.contains(&format!("name = \"{name}\"")));
    let path = write_file(dir, file, &(text + &axes(shift_mm)));
    path.to_str().unwrap().to_string()
}

/// The milling example's FANUC cell on a calibrated robot file with the cell's axes
/// ([`robot_file`]), `controller` appended.
fn cell_setup(dir: &std::path::Path, controller: &str) -> String {
    let base = std::fs::read_to_string(example("milling/fanuc-milling.toml")).unwrap();
    let calibrated = robot_file(dir, "cal.toml", "FANUC R-2000iC/165F (calibrated)", 0.0);
    let base = base.replace(
        "robot = \"fanuc-r2000ic-165f\"",
        &format!("robot = \"{calibrated}\""),
    );
    format!("{base}\n{controller}")
}

/// A short contour with the track's `U` and the table's `C` in every block.
const GCODE: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n(stiffid: external = U C)\nG0 X0 Y0 Z5 U0 C0\nG1 Z0 F600\nG1 X40 U20 C5\nG1 Y30 C10\n";

fn compensate_gcode(dir: &std::path::Path, setup: &str) -> Vec<String> {
    let setup = write_file(dir, "cell.toml", setup);
    let program = write_file(dir, "part.nc", GCODE);
    [
        "compensate",
        "--setup",
        setup.to_str().unwrap(),
        "--stiffness",
        &example("milling/stiffness.json"),
        "--program",
        program.to_str().unwrap(),
        "--process",
        &example("milling/aluminium.toml"),
        "--out",
        dir.join("out.nc").to_str().unwrap(),
    ]
    .map(String::from)
    .to_vec()
}

/// A nominal controller whose robot file declares no external axes: the G-code written back
/// would place the part by the calibrated model of the track and table, which the controller
/// does not run. Refused naming `controller.robot` and what it needs, nothing written. With a
/// controller loaded with the calibrated cell it is written without a word of it; with a nominal
/// controller declaring its own axes, written with a warning naming its model.
#[test]
fn gcode_on_a_cell_for_a_nominal_controller_without_its_axes_is_refused() {
    let dir = temp_dir("open-gcode-cell");
    let nominal = "[controller]\nkinematics = \"nominal\"\nrobot = \"fanuc-r2000ic-165f\"\n";
    let args = compensate_gcode(&dir, &cell_setup(&dir, nominal));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let line = refused(&dir, &args, &["controller.robot", "track, table", "G-code"]);
    assert!(line.contains("kinematics = \"calibrated\""), "{line}");
    let run = |controller: &str| {
        let _ = std::fs::remove_file(dir.join("out.nc"));
        let args = compensate_gcode(&dir, &cell_setup(&dir, controller));
        let out = stiffid(&args.iter().map(String::as_str).collect::<Vec<_>>());
        common::assert_success(&out);
        assert!(dir.join("out.nc").exists());
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let stderr = run("[controller]\nkinematics = \"calibrated\"\n");
    assert!(!stderr.contains("G-code on a cell"), "{stderr}");
    let own = robot_file(&dir, "nominal.toml", "FANUC R-2000iC/165F", 1.0);
    let stderr = run(&format!(
        "[controller]\nkinematics = \"nominal\"\nrobot = \"{own}\"\n"
    ));
    assert!(
        stderr.contains("G-code on a cell with external axes (track, table)")
            && stderr.contains("robot 'FANUC R-2000iC/165F' (kinematics = \"nominal\")"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Readings whose joint 6 barely turns (0.01 deg between postures) leave its offset and the
/// measuring points' positions about the flange's axis correlated beyond 0.999: the document
/// names each such parameter's partners (both ways, exactly the pairs its correlations list
/// beyond 0.999), and the printed table gives no standard deviation for them but says why.
#[test]
fn parameters_the_readings_do_not_separate_print_no_standard_deviation() {
    use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
    let d = temp_dir("open-inseparable");
    let model = model();
    let x = truth(&model);
    let tracker = nalgebra::Isometry3::translation(3.0, -2.0, 1.5);
    let mut qs = postures(25, 1);
    for (i, q) in qs.iter_mut().enumerate() {
        q[5] = 10.0 + 0.01 * i as f64;
    }
    let data = write_file(&d, "fit.csv", &readings(&model, &x, &tracker, &qs));
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
    ];
    let doc = common::json(&stiffid(&[&args[..], &["--json"]].concat()));
    let strong: Vec<(String, String)> = (doc["correlations"].as_array().unwrap().iter())
        .filter(|c| c["rho"].as_f64().unwrap().abs() > 0.999)
        .map(|c| {
            (
                c["a"].as_str().unwrap().into(),
                c["b"].as_str().unwrap().into(),
            )
        })
        .collect();
    assert!(!strong.is_empty(), "{}", doc["correlations"]);
    let text = String::from_utf8(stiffid(&args).stdout).unwrap();
    for p in doc["parameters"].as_array().unwrap() {
        let name = p["name"].as_str().unwrap();
        let mut partners: Vec<&str> = (strong.iter())
            .filter_map(|(a, b)| match (a == name, b == name) {
                (true, _) => Some(b.as_str()),
                (_, true) => Some(a.as_str()),
                _ => None,
            })
            .collect();
        let mut listed: Vec<&str> = (p["inseparable_from"].as_array().unwrap().iter())
            .map(|v| v.as_str().unwrap())
            .collect();
        partners.sort();
        listed.sort();
        assert_eq!(listed, partners, "{name}");
        if !p["identified"].as_bool().unwrap() {
            continue;
        }
        let row = (text.lines())
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("{name}: {text}"));
        assert_eq!(row.ends_with(" inseparable"), !partners.is_empty(), "{row}");
    }
    assert!(
        text.contains("inseparable: ") && text.contains("not separately identifiable"),
        "{text}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// A calibrated robot with 30 held-out errors gives no finite calibration part at 99.7% (it
/// needs 333): the bound and what it is made of both say infinite and how many it needs, and
/// neither calls the calibration absent.
#[test]
fn an_infinite_calibration_part_is_not_called_absent() {
    let dir = temp_dir("open-infinite");
    let base = std::fs::read_to_string(example("milling/fanuc-milling.toml")).unwrap();
    let preset = include_str!("../../../stiffid-core/presets/fanuc-r2000ic-165f.toml");
    let errors: Vec<String> = (1..=30).map(|i| format!("{:?}", 0.01 * i as f64)).collect();
    let robot = preset.replace(
        "name = \"FANUC R-2000iC/165F\"",
        "name = \"FANUC R-2000iC/165F (calibrated)\"",
    ) + &format!(
        "\n[held_out]\nsource = \"validate\"\nerrors_mm = [{}]\n",
        errors.join(", ")
    );
    let robot = write_file(&dir, "cal.toml", &robot);
    let setup = base.replace(
        "robot = \"fanuc-r2000ic-165f\"",
        &format!("robot = \"{}\"", robot.display()),
    ) + "\n[controller]\nkinematics = \"calibrated\"\n";
    let setup = write_file(&dir, "cell.toml", &setup);
    let out = dir.join("out.nc");
    let run = |level: &str| {
        let args = [
            "compensate",
            "--setup",
            setup.to_str().unwrap(),
            "--stiffness",
            &example("milling/stiffness.json"),
            "--program",
            &example("milling/pocket.nc"),
            "--process",
            &example("milling/aluminium.toml"),
            "--out",
            out.to_str().unwrap(),
            "--level",
            level,
        ];
        let out = stiffid(&args);
        common::assert_success(&out);
        String::from_utf8(out.stdout).unwrap()
    };
    let text = run("0.997");
    let needs = "infinite (a finite bound at 99.7% needs at least 333 held-out values)";
    let made_of = (text.lines())
        .find(|l| l.starts_with("the error that remains"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(
        made_of.contains(&format!("calibration {needs}")),
        "{made_of}"
    );
    assert!(!text.contains("calibration absent"), "{text}");
    // At 95% the 30 errors give a finite part: the ceil(0.95 * 31) = 30th smallest.
    let text = run("0.95");
    assert!(text.contains("calibration 0.3000 mm"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The part located after a calibration that read no reflector (as one fit with load steps
/// reads none): `calibrate --update` of its robot file with check readings of the arm and the
/// part's three reflectors writes the part where it truly is into the updated file's `[part]`.
#[test]
fn a_calibrated_robot_locates_its_part_in_an_update() {
    use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
    use nalgebra::{Isometry3, Point3, Vector3};
    let d = temp_dir("open-part-update");
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    let setup = stiffid::internal::setup::builtin_text(SETUP).unwrap();
    let first = write_file(&d, "setup.toml", setup);
    let fit = write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(25, 1)),
    );
    let robot = d.join("robot.toml");
    let args = ["calibrate", "--setup", first.to_str().unwrap(), "--data"];
    let out = stiffid(
        &[
            &args[..],
            &[fit.to_str().unwrap(), "--out", robot.to_str().unwrap()],
        ]
        .concat(),
    );
    common::assert_success(&out);
    // The second step: the setup on the calibrated file, the part's reflectors placed.
    let on_part = [
        [300.0, 0.0, 40.0],
        [-200.0, 250.0, 40.0],
        [-100.0, -300.0, 60.0],
    ];
    let part = Isometry3::new(
        Vector3::new(1.5, 0.2, 0.6),
        Vector3::z() * 30f64.to_radians(),
    );
    let second = setup.replace("robot = \"comau-smart5-nj165-3.0\"", "robot = \"robot.toml\"")
        + &format!("\n[workpiece]\nbase_from_part = {{ xyz_mm = [1502.0, 200.0, 600.0], rpy_deg = [0.0, 0.0, 30.0] }}\nreflectors_mm = {on_part:?}\n");
    let second = write_file(&d, "second.toml", &second);
    let mut check = readings(&model, &x, &tracker, &postures(12, 3));
    let row: Vec<String> = check
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(String::from)
        .collect();
    for (k, r) in on_part.iter().enumerate() {
        let t = tracker.inverse() * part * Point3::from(Vector3::from(*r) * 1e-3);
        let q = row[2..8].join(",");
        check += &format!(
            "P1,T{},{q},{:?},{:?},{:?}\n",
            k + 1,
            t.x * 1e3,
            t.y * 1e3,
            t.z * 1e3
        );
    }
    let check = write_file(&d, "check.csv", &check);
    let updated = d.join("updated.toml");
    let args = [
        "calibrate",
        "--setup",
        second.to_str().unwrap(),
        "--update",
        "--data",
    ];
    let out = stiffid(
        &[
            &args[..],
            &[check.to_str().unwrap(), "--out", updated.to_str().unwrap()],
        ]
        .concat(),
    );
    common::assert_success(&out);
    let file = std::fs::read_to_string(&updated).unwrap();
    let located = stiffid::internal::robot::file::parse(&file, "updated.toml").unwrap();
    let located = *located.part().expect("[part]");
    let off = (located.translation.vector - part.translation.vector).norm();
    let turn = located.rotation.angle_to(&part.rotation);
    eprintln!(
        "part located {:.2e} mm and {:.2e} deg off",
        off * 1e3,
        turn.to_degrees()
    );
    assert!(off < 1e-6, "{off} m");
    assert!(turn < 1e-6);
    reflectors_beside_load_steps_are_refused(&d, &row[2..8].join(","));
    std::fs::remove_dir_all(&d).unwrap();
}

/// The gravity terms under one name and a stated conversion: each fitted term's
/// `robot_file_si` is the value the written robot file's `[gravity]` holds under its name, and
/// the printed table's note says the file holds them in SI, the table's value times 1e-6, naming
/// every term whose file value is not that (turned into the file's link frames).
#[test]
fn gravity_terms_name_their_robot_file_values() {
    use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
    let d = temp_dir("open-gravity-names");
    let model = model();
    let x = truth(&model);
    let tracker = nalgebra::Isometry3::translation(3.0, -2.0, 1.5);
    let data = write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(40, 1)),
    );
    let robot = d.join("robot.toml");
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--gravity",
        "lumped",
        // The gravity terms are the subject: no choice of maps.
        "--maps",
        "none",
        "--out",
        robot.to_str().unwrap(),
    ];
    let text = String::from_utf8(stiffid(&args).stdout).unwrap();
    let doc = common::json(&stiffid(&[&args[..], &["--json"]].concat()));
    let file = std::fs::read_to_string(&robot).unwrap();
    let file = stiffid::internal::robot::file::parse(&file, "robot.toml").unwrap();
    let own = file.own_weight().expect("[gravity]");
    let mut turned = Vec::new();
    let mut fitted = 0;
    for p in doc["parameters"].as_array().unwrap() {
        let name = p["name"].as_str().unwrap();
        let in_file = own.terms.iter().find(|(n, _)| n == name).map(|t| t.1);
        assert_eq!(p["robot_file_si"].as_f64(), in_file, "{name}");
        if let (Some(si), true) = (in_file, p["identified"].as_bool().unwrap()) {
            fitted += 1;
            let value = p["value"].as_f64().unwrap();
            if (value * 1e-6 - si).abs() > 1e-9 * si.abs().max(value.abs() * 1e-6) {
                turned.push(name.to_string());
            }
        }
    }
    assert!(fitted > 0, "{}", doc["parameters"]);
    assert!(
        text.contains("gravity terms: the robot file's [gravity] states them in SI, value_si = the value above x 1e-6"),
        "{text}"
    );
    for name in &turned {
        assert!(text.contains(&format!("{name} = ")), "{name}: {text}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// The KUKA example's pocket with its first `LIN` target moved into a `.dat` as `XP1`, whose
/// declaration there is `decl`; compensated into `out.src`.
fn krl_with_dat(dir: &std::path::Path, decl: &dyn Fn(&str) -> String) -> Vec<String> {
    // The example as one file: its points put back from its .dat into its motions.
    let src = common::inlined(
        &std::fs::read_to_string(example("milling/pocket.src")).unwrap(),
        &std::fs::read_to_string(example("milling/pocket.dat")).unwrap(),
    );
    let line = src.lines().find(|l| l.starts_with("LIN {")).unwrap();
    let (target, rest) = line[4..].split_at(line[4..].find('}').unwrap() + 1);
    let src = src
        .replacen(line, &format!("LIN XP1{rest}"), 1)
        .replacen("DEF pocket", "DEF cut", 1);
    write_file(dir, "cut.src", &src);
    write_file(
        dir,
        "cut.dat",
        &format!("DEFDAT cut\n{}ENDDAT\n", decl(target)),
    );
    [
        "compensate",
        "--setup",
        &example("milling/kuka-milling.toml"),
        "--stiffness",
        &example("milling/kuka-stiffness.json"),
        "--program",
        "{dir}/cut.src",
        "--process",
        &example("milling/aluminium.toml"),
        "--out",
        "{dir}/out.src",
    ]
    .map(String::from)
    .to_vec()
}

/// A point declared twice in a KRL `.dat` (the controller refuses the module) is refused where a
/// motion uses it, naming both declarations; a coordinate beyond any length (`X 1e300`) is
/// refused naming the member, not searched for as a pose out of reach. The target as declared
/// once compensates.
#[test]
fn a_krl_point_declared_twice_or_out_of_range_is_refused_naming_it() {
    let dir = temp_dir("open-krl-dat");
    let once = |t: &str| format!("DECL E6POS XP1={t}\n");
    let args = krl_with_dat(&dir, &once);
    let run = |args: &[String]| {
        let d = dir.to_str().unwrap();
        let args: Vec<String> = args.iter().map(|a| a.replace("{dir}", d)).collect();
        stiffid(&args.iter().map(String::as_str).collect::<Vec<_>>())
    };
    common::assert_success(&run(&args));
    std::fs::remove_file(dir.join("out.src")).unwrap();
    let _ = std::fs::remove_file(dir.join("out.dat"));
    let twice = |t: &str| format!("DECL E6POS XP1={t}\nDECL E6POS XP1={t}\n");
    let args = krl_with_dat(&dir, &twice);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    refused(
        &dir,
        &args,
        &[
            "cut.src",
            "XP1 is declared twice",
            "on line 2 of the .dat",
            "on line 3 of the .dat",
        ],
    );
    let huge = |t: &str| {
        let x = t.find("X ").unwrap() + 2;
        let end = x + t[x..].find(',').unwrap();
        format!("DECL E6POS XP1={}1e300{}\n", &t[..x], &t[end..])
    };
    let args = krl_with_dat(&dir, &huge);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    refused(
        &dir,
        &args,
        &["cut.src", "X 1e300: outside -100000 to 100000 mm"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A linear motion the arm cannot make without changing its configuration from the target
/// before it (here the pocket's first cut started from an axis posture, shoulder and elbow
/// elsewhere) is refused saying so, with the configurations that reach it.
#[test]
fn a_linear_motion_that_would_change_the_configuration_is_refused_saying_so() {
    let dir = temp_dir("open-krl-kept");
    let axes = |_: &str| "DECL E6AXIS XP1={A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}\n".to_string();
    let args = krl_with_dat(&dir, &axes);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let message = refused(
        &dir,
        &args,
        &[
            "cut.src",
            "without changing the arm's configuration from the target before it",
            "a linear or circular motion keeps them",
            "inverse kinematics reaches it in S 'B",
        ],
    );
    assert!(!message.contains("in the configuration S"), "{message}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Reflector rows beside load steps (in `d`, with its `second.toml`, the arm's axis angles `q`
/// of a posture): refused, the message saying how to locate the part.
fn reflectors_beside_load_steps_are_refused(d: &std::path::Path, q: &str) {
    // Reflector rows beside load steps: refused, the message saying how to locate the part.
    let loaded = format!(
        "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,load_n,fx_n,fy_n,fz_n,x_tracker_mm,y_tracker_mm,z_tracker_mm\n\
         P1,1,{q},0,0,0,0,100.0,200.0,300.0\nP1,1,{q},100,0,0,-100,100.0,200.0,299.9\n\
         P1,T1,{q},0,0,0,0,500.0,200.0,300.0\n"
    );
    write_file(d, "loaded.csv", &loaded);
    let args = [
        "calibrate",
        "--setup",
        "{dir}/second.toml",
        "--data",
        "{dir}/loaded.csv",
    ];
    refused(
        d,
        &args,
        &[
            "loaded.csv: line 4, column 2 (point)",
            "load steps",
            "calibrate --update",
        ],
    );
}
