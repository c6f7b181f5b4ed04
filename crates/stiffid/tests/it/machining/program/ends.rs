//! Where each language's program ends: a KRL, RAPID or LS program cut off at a line boundary
//! (its closing `END`, `ENDMODULE`, `/END` and the lines before it missing) is refused naming
//! its last line, never read as a whole program with its last motions lost; a text whose lines
//! end with a lone CR is refused saying so.

use stiffid_core::Error;
use stiffid_machining::program::{parse, parse_with_data, Dialect};

const KRL: &str = "&ACCESS RVP\nDEF cut( )\nPTP {A1 0, A2 -90, A3 90, A4 0, A5 30, A6 0}\nPTP {A1 1, A2 -90, A3 90, A4 0, A5 30, A6 0}\nPTP {A1 2, A2 -90, A3 90, A4 0, A5 30, A6 0}\nPTP {A1 3, A2 -90, A3 90, A4 0, A5 30, A6 0}\nEND ; of cut\n";

const RAPID: &str = "MODULE cut\n  PROC main()\n    MoveAbsJ [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, tool0;\n    MoveAbsJ [[1,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, tool0;\n    MoveAbsJ [[2,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, tool0;\n  ENDPROC\nENDMODULE\n";

fn ls() -> String {
    let mut s = "/PROG  CUT\n/ATTR\n/MN\n   1:J P[1] 100% FINE ;\n   2:J P[2] 100% FINE ;\n/POS\n"
        .to_string();
    for i in 1..=2 {
        s += &format!("P[{i}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {i}.0 deg,\tJ2= 0.0 deg,\tJ3= 0.0 deg,\n\tJ4= 0.0 deg,\tJ5= 30.0 deg,\tJ6= 0.0 deg\n}};\n");
    }
    s + "/END\n"
}

/// `text` without its lines from the one holding `from` on.
fn cut(text: &str, from: &str) -> String {
    text[..text.find(from).unwrap()].to_string()
}

fn refused(text: &str, dialect: Dialect) -> (u64, String) {
    match parse(text, dialect) {
        Err(Error::Program { line, message }) => (line, message),
        other => panic!("{dialect:?}: {other:?}"),
    }
}

#[test]
fn a_program_cut_off_at_a_line_boundary_is_refused_naming_its_last_line() {
    assert_eq!(parse(KRL, Dialect::Krl).unwrap().targets.len(), 4);
    let krl = cut(KRL, "PTP {A1 2");
    let (line, m) = refused(&krl, Dialect::Krl);
    assert_eq!(line, 4, "{m}");
    assert!(
        m.contains("without END or ENDFCT") && m.contains("cut off"),
        "{m}"
    );
    // A KRL program's .dat cut off before ENDDAT.
    let src = "DEF cut( )\nPTP XP1\nEND\n";
    let dat = "DEFDAT cut\nDECL E6AXIS XP1={A1 0, A2 -90, A3 90, A4 0, A5 30, A6 0}\nENDDAT\n";
    assert!(parse_with_data(src, Some(dat), Dialect::Krl).is_ok());
    match parse_with_data(src, Some(&cut(dat, "ENDDAT")), Dialect::Krl) {
        Err(Error::Program { line: 1, message }) => {
            assert!(
                message.contains("line 2, 'DECL E6AXIS XP1") && message.contains("without ENDDAT"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    // Without its DEFDAT (the data list's start lost, or another file): not a data list.
    let headless = dat.replacen("DEFDAT cut\n", "", 1);
    match parse_with_data(src, Some(&headless), Dialect::Krl) {
        Err(Error::Program { line: 1, message }) => assert!(
            message.starts_with("the program's .dat opens on its line 1 with 'DECL E6AXIS XP1")
                && message.contains("not DEFDAT"),
            "{message}"
        ),
        other => panic!("{other:?}"),
    }
    let ls = ls();
    assert_eq!(parse(&ls, Dialect::FanucLs).unwrap().targets.len(), 2);
    let (line, m) = refused(&cut(&ls, "/END"), Dialect::FanucLs);
    assert_eq!(line, 18, "{m}");
    assert!(m.contains("without /END"), "{m}");
    assert_eq!(parse(RAPID, Dialect::Rapid).unwrap().targets.len(), 3);
    let rapid = cut(RAPID, "    MoveAbsJ [[2");
    let (line, m) = refused(&rapid, Dialect::Rapid);
    assert_eq!(line, 4, "{m}");
    assert!(m.contains("without ENDMODULE"), "{m}");
}

#[test]
fn lines_ending_with_a_lone_cr_are_refused_saying_so() {
    let (line, m) = refused(&KRL.replace('\n', "\r"), Dialect::Krl);
    assert_eq!(line, 1);
    assert!(m.contains("lone CR"), "{m}");
    // CR LF is read as LF.
    assert_eq!(
        parse(&KRL.replace('\n', "\r\n"), Dialect::Krl)
            .unwrap()
            .targets
            .len(),
        4
    );
}
