//! The real KRL programs of `crates/stiffid/tests/data/programs/krl` (SOURCES.md): each as
//! found, with the `.dat` beside it where there is one, refused naming the line and the construct
//! that stops it (the independent reading of their motions is
//! `crates/stiffid-py/tests/test_krl_corpus.py`).

use crate::program::{parse_with_data, Dialect};
use stiffid_core::Error;

const DIR: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../stiffid/tests/data/programs/krl"
);

/// Each file, the line its refusal names and words of the construct the message must hold.
const REFUSED: [(&str, u64, &str); 11] = [
    // ROS-Industrial RSI (KR C4, KSS 8.2-8.3; RSI 4; the NTNU axis correction; KSS 8.6): the
    // home PTP is read, the sensor-guided motion is not stiffid's.
    ("rsi_kr_c4.src", 84, "RSI_MOVECORR"),
    ("rsi_kr_c4_rsi4.src", 84, "RSI_MOVECORR"),
    ("rsi_axis_correction.src", 84, "RSI_MOVECORR"),
    ("rsi_kr_c4_kss86.src", 80, "RSI_MOVECORR"),
    // kroshu's drivers: iiQKA.OS2 and the KSS driver with no motion of its own before RSI.
    ("rsi_iiqka_os2.src", 85, "RSI_MOVECORR"),
    ("rsi_axis_corr_kss.src", 81, "RSI_MOVECORR"),
    // KR C2 RSI: a PTP to the axes where the robot stands, then home: no motion to compensate.
    (
        "rsi_kr_c2.src",
        106,
        "PTP HOME: the home position, passed through",
    ),
    // EKI drivers: targets received at run time.
    ("kuka_eki_hw_interface.src", 67, "joint_pos_tgt"),
    ("motion_eki.src", 79, "$axis_act_meas: a system variable"),
    ("aip_eki.src", 22, "$axis_act_meas: a system variable"),
    // A KR 120 R2700-2 cell's program (kukaKRLmagic): its joint move home is read, its cuts go
    // to points a routine computes from its parameters at run time.
    (
        "kukaKRLmagic_sample_program.src",
        157,
        "PSTART is declared on line 135 without a value",
    ),
];

#[test]
fn every_real_krl_program_is_refused_naming_its_line_and_construct() {
    for (file, line, needle) in REFUSED {
        let src = std::fs::read_to_string(format!("{DIR}/{file}")).unwrap();
        let dat =
            crate::program::files::data_beside(std::path::Path::new(&format!("{DIR}/{file}")))
                .map(|p| std::fs::read_to_string(p).unwrap());
        let with_dat = [
            "kuka_eki_hw_interface.src",
            "kukaKRLmagic_sample_program.src",
        ];
        assert_eq!(dat.is_some(), with_dat.contains(&file), "{file}");
        match parse_with_data(&src, dat.as_deref(), Dialect::Krl) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{file}: {message}");
                assert!(message.contains(needle), "{file}: {message}");
            }
            other => panic!("{file}: {other:?}"),
        }
    }
    // Every .src of the folder is in the list.
    let mut found: Vec<String> = (std::fs::read_dir(DIR).unwrap().flatten())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".src"))
        .collect();
    found.sort();
    let mut listed: Vec<&str> = REFUSED.iter().map(|r| r.0).collect();
    listed.sort();
    assert_eq!(found, listed);
}

/// Past the sensor-guided motion, kroshu's iiQKA file's return `PTP` writes `A5 0S`: no number to
/// KRL, refused naming the line and the member rather than read as 0.
#[test]
fn a_number_run_into_a_letter_is_refused() {
    let src = std::fs::read_to_string(format!("{DIR}/rsi_iiqka_os2.src")).unwrap();
    let without = src.replace("RSI_MOVECORR()", "");
    match parse_with_data(&without, None, Dialect::Krl) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, 93, "{message}");
            assert!(
                message.contains("A5") && message.contains("0S"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}
