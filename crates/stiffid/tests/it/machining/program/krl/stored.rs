//! A KRL program as KUKA System Software stores it (its points in the `.dat`, inline forms whose
//! frame data select tool 1 and base 1) is compensated as the same program with literal frames:
//! the first 40 motions of `examples/milling/pocket.src`, rewritten here as a teach pendant
//! writes them, against the setup's `[controller] tools` and `bases` holding the program's
//! `$TOOL` and `$BASE`.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::app::compensate::{self, Input};
use stiffid::internal::machining::compensate::{Compensated, Options};
use stiffid::internal::machining::program::cartesian::flags::ConfigurationData;
use stiffid::internal::machining::program::generate::Settings;
use stiffid::internal::machining::program::generate::Targets;
use stiffid::internal::machining::program::krl::StatusTurn;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::robot::configuration::Configuration;
use stiffid::internal::robot::ik;
use stiffid::internal::robot::presets;
use stiffid::internal::setup::NumberedFrames;

const MILLING: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/milling");

/// The KR 210 milling setup with the controller's tool 1 and base 1: the program's `$TOOL` and
/// `$BASE`.
fn setup() -> stiffid::Setup {
    let text = std::fs::read_to_string(format!("{MILLING}/kuka-milling.toml")).unwrap();
    let text = format!("{text}\n[controller]\ntools = [{{ number = 1, xyz_mm = [0, 0, 250] }}]\nbases = [{{ number = 1, xyz_mm = [2000, 0, 550] }}]\n");
    stiffid::internal::setup::parse(&text, "kuka-milling.toml", |name, _| presets::get(name))
        .unwrap()
}

/// The first `n` motions of the pocket with its literal frames, and its end.
fn literal(n: usize) -> String {
    let text = crate::common::pocket_krl();
    let mut out = String::new();
    let mut motions = 0;
    for l in text.lines() {
        // The first `n` straight moves, the corners' circles (`CIRC`) left out.
        if l.starts_with("CIRC") {
            continue;
        }
        if l.starts_with("PTP") || l.starts_with("LIN") {
            motions += 1;
            if motions > n {
                continue;
            }
        }
        out.push_str(l);
        out.push('\n');
    }
    out
}

/// `literal` as a teach pendant stores it: each motion an inline form (`FDAT_ACT`, `BAS`) to a
/// point of the `.dat`, tool 1 and base 1 by number, no literal frame left.
fn stored(literal: &str) -> (String, String) {
    let (mut src, mut dat) = (String::new(), String::from("&ACCESS RVP\nDEFDAT  POCKET\n"));
    let mut speed = String::new();
    for (n, l) in literal.lines().enumerate() {
        if l.starts_with("$TOOL") || l.starts_with("$BASE") {
            continue;
        }
        if let Some(v) = l.strip_prefix("$VEL.CP = ") {
            speed = v.to_string();
        }
        let Some((motion, rest)) = l.split_once(" {E6POS: ") else {
            src.push_str(l);
            src.push('\n');
            continue;
        };
        let (point, after) = rest.split_once('}').unwrap();
        let params = match motion {
            "PTP" => format!("PDAT_ACT=PPDAT{n}\nFDAT_ACT=FP{n}\nBAS(#PTP_PARAMS,20)"),
            _ => format!("LDAT_ACT=LCPDAT{n}\nFDAT_ACT=FP{n}\nBAS(#CP_PARAMS,{speed})"),
        };
        src.push_str(&format!(";FOLD {motion} P{n} Tool[1] Base[1];%{{PE}}\n$BWDSTART=FALSE\n{params}\n{motion} XP{n}{after}\n;ENDFOLD\n"));
        dat.push_str(&format!("DECL E6POS XP{n}={{{point}}}\nDECL FDAT FP{n}={{TOOL_NO 1,BASE_NO 1,IPO_FRAME #BASE,POINT2[] \" \"}}\n"));
    }
    dat.push_str("ENDDAT\n");
    (src, dat)
}

/// The milling example's KR 210 stiffness on `setup`.
fn kuka_compliance(setup: &stiffid::Setup) -> stiffid::internal::model::Compliance {
    stiffid::internal::io::stiffness::parse(
        &std::fs::read_to_string(format!("{MILLING}/kuka-stiffness.json")).unwrap(),
    )
    .unwrap()
    .compliance(setup.model())
    .unwrap()
}

/// Compensates `text` (with its `.dat` `data`) on `setup` with `compliance` from `q0`: the
/// program, its `.dat` and every point's result.
fn compensated(
    (setup, compliance, q0): (
        &stiffid::Setup,
        stiffid::internal::model::Compliance,
        Option<Vector6<f64>>,
    ),
    (text, data): (&str, Option<&str>),
) -> (String, Option<String>, Vec<Compensated>) {
    let mut options = Options::for_setup(setup);
    if let Some(q0) = q0 {
        options.q0 = q0;
    }
    let process = stiffid::internal::machining::process::file::parse(
        &std::fs::read_to_string(format!("{MILLING}/aluminium.toml")).unwrap(),
        "aluminium.toml",
    )
    .unwrap();
    let request = compensate::Request {
        names: Default::default(),
        setup,
        compliance,
        input: Input::Program {
            encoding: Default::default(),
            reading: Default::default(),
            name: "POCKET.src".into(),
            text,
            data,
            language: Language::Robot(Dialect::Krl),
            process_name: "aluminium.toml".into(),
            process,
            chord_tolerance: 1e-5,
            output: Language::Robot(Dialect::Krl),
            out_name: "POCKET_C.src".into(),
            settings: Settings::default(),
        },
        options,
    };
    let mut results = Vec::new();
    let report = compensate::run::<stiffid::Error, _>(request, |_, _, r, _| {
        results.extend_from_slice(r);
        Ok(())
    })
    .unwrap();
    let p = report.report.program.unwrap();
    (p.text, p.data, results)
}

/// The members `X` to `C` of every `E6POS` aggregate of `text`, as written, in text order.
fn poses(text: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("E6POS") {
        // `{E6POS: ..}` in a motion, `DECL E6POS XP1={..}` in a .dat.
        let open = match rest[..at].ends_with('{') {
            true => at - 1,
            false => at + rest[at..].find('{').unwrap(),
        };
        let close = open + rest[open..].find('}').unwrap();
        let members = rest[open + 1..close]
            .trim_start_matches("E6POS:")
            .split(',');
        let numbers: Vec<String> = members
            .filter(|m| {
                ["X", "Y", "Z", "A", "B", "C"].contains(&m.trim().split(' ').next().unwrap())
            })
            .map(|m| m.trim().split(' ').nth(1).unwrap().to_string())
            .collect();
        out.push(numbers);
        rest = &rest[close..];
    }
    out
}

#[test]
fn a_program_as_the_controller_stores_it_compensates_as_with_literal_frames() {
    let s = setup();
    let literal = literal(40);
    let (src, dat) = stored(&literal);
    assert!(!src.contains("$BASE") && !src.contains("E6POS"), "{src}");
    let how = (&s, kuka_compliance(&s), None);
    let (lit_out, none, lit) = compensated(how.clone(), (&literal, None));
    assert!(none.is_none());
    let (src_out, dat_out, sto) = compensated(how, (&src, Some(&dat)));
    assert_eq!(lit.len(), 40);
    assert_eq!(sto.len(), lit.len());
    for (a, b) in lit.iter().zip(&sto) {
        assert!((a.q_compensated - b.q_compensated).amax() < 1e-12);
        assert!((a.pose.translation.vector - b.pose.translation.vector).norm() < 1e-12);
    }
    // The compensated targets are written into the .dat, as the literal program writes them.
    let dat_out = dat_out.unwrap();
    let (a, b) = (poses(&lit_out), poses(&dat_out));
    assert_eq!(a.len(), 40);
    assert_eq!(a, b);
    assert_ne!(poses(&dat), b, "compensation moved the targets");
    // The .src keeps every byte but the bounds' comments; the .dat every byte but the numbers.
    let strip = |t: &str| {
        t.lines()
            .map(|l| l.split(" ; bound").next().unwrap().to_string())
            .collect::<Vec<_>>()
    };
    let renamed = src.replace("DEF POCKET( )", "DEF POCKET_C( )");
    assert_eq!(strip(&src_out), strip(&renamed));
    let digits = |t: &str| t.replace(|c: char| c.is_ascii_digit() || c == '.' || c == '-', "");
    assert_eq!(
        digits(&dat_out),
        digits(&dat.replace("DEFDAT  POCKET", "DEFDAT  POCKET_C"))
    );
}

/// A literal KRL frame line `$TOOL = {X .., Y .., Z .., A .., B .., C ..}` (mm, deg), m.
fn frame_of(program: &str, name: &str) -> Isometry3<f64> {
    let line = program.lines().find(|l| l.starts_with(name)).unwrap();
    let inner = &line[line.find('{').unwrap() + 1..line.find('}').unwrap()];
    let n: Vec<f64> = inner
        .split(',')
        .map(|m| m.trim().split(' ').nth(1).unwrap().parse().unwrap())
        .collect();
    let r =
        UnitQuaternion::from_euler_angles(n[5].to_radians(), n[4].to_radians(), n[3].to_radians());
    Isometry3::from_parts(Translation3::new(n[0] * 1e-3, n[1] * 1e-3, n[2] * 1e-3), r)
}

/// The `E6POS` points of a `.dat` in order: the pose (its frame, m) and the status and turn.
fn dat_targets(dat: &str) -> Vec<(Isometry3<f64>, u8, u8)> {
    let mut out = Vec::new();
    for l in dat.lines().filter(|l| l.starts_with("DECL E6POS")) {
        let inner = &l[l.find('{').unwrap() + 1..l.find('}').unwrap()];
        let get = |name: &str| {
            inner
                .split(',')
                .map(str::trim)
                .find_map(|m| m.strip_prefix(&format!("{name} ")))
                .unwrap()
        };
        let n = |name: &str| get(name).parse::<f64>().unwrap();
        let bits = |name: &str| {
            u8::from_str_radix(get(name).trim_matches('\'').trim_start_matches('B'), 2).unwrap()
        };
        let r = UnitQuaternion::from_euler_angles(
            n("C").to_radians(),
            n("B").to_radians(),
            n("A").to_radians(),
        );
        let p = Vector3::new(n("X"), n("Y"), n("Z")) * 1e-3;
        out.push((
            Isometry3::from_parts(Translation3::from(p), r),
            bits("S"),
            bits("T"),
        ));
    }
    out
}

/// The true-robot campaign's rectangle (crate::true_robot) as a KRL program stored as the
/// controller stores it (points in the `.dat`, tool 1 and base 1 by number in the setup's
/// `[controller]` tables), compensated with its `.dat` and run by the nominal controller (its
/// inverse kinematics of the `.dat`'s points in the configuration their `S` and `T` name) on the
/// simulated true robot: it lands within 0.05 mm mean of its targets.
#[test]
fn a_stored_krl_program_compensated_lands_on_the_true_robot() {
    use crate::true_robot::{self as t, Truth, WRENCHES};
    let case = t::dh_case();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let truth = Truth::new(&case.setup, &mut rng);
    let data = truth.readings(&t::postures(30, &mut rng, case.angles), &WRENCHES, &mut rng);
    let held = truth.readings(
        &t::postures(12, &mut rng, case.angles),
        &WRENCHES[..1],
        &mut rng,
    );
    let (setup, compliance, frame, _, _) = t::calibrated(&case, case.gravity, &data, &held);
    let compliance = compliance.unwrap();
    let q0 = t::q0(&case);
    let (setup, part) = t::with_part(&setup, &q0);
    // The program: the rectangle as stiffid writes it for this cell, its frames then moved into
    // the controller's tables and its points into the .dat.
    let krl = (Language::Robot(Dialect::Krl), Targets::Cartesian);
    let (literal, _) = t::written_from(&setup, &compliance, (&q0, &t::rectangle()), krl);
    let mut controller = setup.workcell().controller().clone();
    controller.tools =
        NumberedFrames::new("controller.tools", &[(1, frame_of(&literal, "$TOOL"))]).unwrap();
    controller.bases =
        NumberedFrames::new("controller.bases", &[(1, frame_of(&literal, "$BASE"))]).unwrap();
    let setup = setup
        .to_builder()
        .with_controller(controller)
        .build()
        .unwrap();
    let (src, dat) = stored(&literal);
    let (_, dat_out, results) = compensated((&setup, compliance, Some(q0)), (&src, Some(&dat)));
    let targets = dat_targets(&dat_out.unwrap());
    assert_eq!(targets.len(), results.len());
    assert!(targets.len() > 10);
    // The nominal controller runs the .dat's points; the tool lands on the program's targets.
    let nominal = case.setup.robot();
    let mut previous = results[0].q;
    let errors: Vec<f64> = (targets.iter().zip(&results))
        .map(|((pose, s, t), r)| {
            let target = part * pose;
            let tcp = &setup.tool().tcp;
            let q = ik::solve(nominal, tcp, &target, &previous, &ik::Options::default())
                .unwrap()
                .q;
            let st = StatusTurn::of(&Configuration::of(nominal, &q));
            assert_eq!((st.status, st.turn), (*s, *t));
            assert!(
                (q - r.q_compensated).amax() < 1e-7,
                "{}",
                (q - r.q_compensated).amax()
            );
            previous = q;
            let want = frame.inverse() * Point3::from(r.pose.translation.vector);
            (truth.tcp_at(&q, &r.wrench) - want.coords).norm()
        })
        .collect();
    let row = t::row(&errors);
    eprintln!(
        "stored KRL on the true robot: mean {:.4} mm, max {:.4} mm",
        row.mean * 1e3,
        row.max * 1e3
    );
    assert!(row.mean <= 0.05e-3, "{row:?}");
}

/// The stored program with its 3rd to 5th motions inside `IF $IN[1] THEN .. ENDIF` and its
/// motions from the 9th on in a routine of the file, `DEF sub( )`, that the program calls where
/// they were: each motion is compensated where it is, to the values of the straight-line
/// program, and written back in place (the `.src` keeps every byte but the bounds' comments).
#[test]
fn motions_in_a_branch_and_in_a_called_routine_compensate_as_the_straight_program() {
    let s = setup();
    let (src, dat) = stored(&literal(12));
    let folds: Vec<usize> = src.match_indices(";FOLD").map(|(i, _)| i).collect();
    let ends: Vec<usize> = (src.match_indices(";ENDFOLD\n"))
        .map(|(i, _)| i + ";ENDFOLD\n".len())
        .collect();
    assert_eq!(folds.len(), 12);
    let end = src.rfind("END\n").unwrap();
    let tail = &src[folds[8]..ends[11]];
    let flowing = format!(
        "{}IF $IN[1] THEN\n{}ENDIF\n{}sub( )\n{}END\nDEF sub( )\n{tail}END\n",
        &src[..folds[2]],
        &src[folds[2]..ends[4]],
        &src[ends[4]..folds[8]],
        &src[ends[11]..end],
    );
    let how = (&s, kuka_compliance(&s), None);
    let (_, straight_dat, straight) = compensated(how.clone(), (&src, Some(&dat)));
    let (out, flowing_dat, results) = compensated(how, (&flowing, Some(&dat)));
    assert_eq!(results.len(), 12);
    for (a, b) in straight.iter().zip(&results) {
        assert!((a.q_compensated - b.q_compensated).amax() < 1e-12);
    }
    assert_eq!(flowing_dat, straight_dat);
    let strip = |t: &str| {
        t.lines()
            .map(|l| l.split(" ; bound").next().unwrap().to_string())
            .collect::<Vec<_>>()
    };
    assert_eq!(
        strip(&out),
        strip(&flowing.replace("DEF POCKET( )", "DEF POCKET_C( )"))
    );
}
