//! A KRL program as KUKA System Software stores it (its points in the `.dat`, inline forms whose
//! frame data select tool 1 and base 1) is compensated as the same program with literal frames:
//! the first 40 motions of `examples/milling/pocket.src`, rewritten here as a teach pendant
//! writes them, against the setup's `[controller] tools` and `bases` holding the program's
//! `$TOOL` and `$BASE`.

use stiffid::app::compensate::{self, Input};
use stiffid::machining::compensate::{Compensated, Options};
use stiffid::machining::program::generate::Settings;
use stiffid::machining::program::Dialect;
use stiffid::machining::Language;
use stiffid::robot::presets;

const MILLING: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/milling");

/// The KR 210 milling setup with the controller's tool 1 and base 1: the program's `$TOOL` and
/// `$BASE`.
fn setup() -> stiffid::Setup {
    let text = std::fs::read_to_string(format!("{MILLING}/kuka-milling.toml")).unwrap();
    let text = format!("{text}\n[controller]\ntools = [{{ number = 1, xyz_mm = [0, 0, 250] }}]\nbases = [{{ number = 1, xyz_mm = [2000, 0, 550] }}]\n");
    stiffid::setup::parse(&text, "kuka-milling.toml", |name, _| presets::get(name)).unwrap()
}

/// The first `n` motions of the pocket with its literal frames, and its end.
fn literal(n: usize) -> String {
    let text = std::fs::read_to_string(format!("{MILLING}/pocket.src")).unwrap();
    let mut out = String::new();
    let mut motions = 0;
    for l in text.lines() {
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

/// Compensates `text` (with its `.dat` `data`) on `setup`: the program, its `.dat` and every
/// point's result.
fn compensated(
    setup: &stiffid::Setup,
    (text, data): (&str, Option<&str>),
) -> (String, Option<String>, Vec<Compensated>) {
    let compliance = stiffid::io::stiffness::parse(
        &std::fs::read_to_string(format!("{MILLING}/kuka-stiffness.json")).unwrap(),
    )
    .unwrap()
    .compliance(setup.model())
    .unwrap();
    let process = stiffid::machining::process::file::parse(
        &std::fs::read_to_string(format!("{MILLING}/aluminium.toml")).unwrap(),
        "aluminium.toml",
    )
    .unwrap();
    let request = compensate::Request {
        setup,
        compliance,
        input: Input::Program {
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
        options: Options::for_setup(setup),
    };
    let mut results = Vec::new();
    let report = compensate::run::<stiffid::Error, _>(request, |_, _, r, _| {
        results.extend_from_slice(r);
        Ok(())
    })
    .unwrap();
    let p = report.program.unwrap();
    (p.text, p.data, results)
}

/// The members `X` to `C` of every `E6POS` aggregate of `text`, as written, in text order.
fn poses(text: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("E6POS") {
        let open = at + rest[at..].find('{').unwrap();
        let close = open + rest[open..].find('}').unwrap();
        let members = rest[open + 1..close].trim_start_matches("E6POS:").split(',');
        let numbers: Vec<String> = members
            .filter(|m| ["X", "Y", "Z", "A", "B", "C"].contains(&m.trim().split(' ').next().unwrap()))
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
    let (lit_out, none, lit) = compensated(&s, (&literal, None));
    assert!(none.is_none());
    let (src_out, dat_out, sto) = compensated(&s, (&src, Some(&dat)));
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
    let strip = |t: &str| t.lines().map(|l| l.split(" ; bound").next().unwrap().to_string()).collect::<Vec<_>>();
    let renamed = src.replace("DEF POCKET( )", "DEF POCKET_C( )");
    assert_eq!(strip(&src_out), strip(&renamed));
    let digits = |t: &str| t.replace(|c: char| c.is_ascii_digit() || c == '.' || c == '-', "");
    assert_eq!(digits(&dat_out), digits(&dat.replace("DEFDAT  POCKET", "DEFDAT  POCKET_C")));
}
