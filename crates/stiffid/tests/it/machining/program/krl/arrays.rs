//! Arrays of points given their values in the `.dat` (`DECL E6AXIS XJ[3]`, `XJ[1]={..}`), moved
//! to by a literal index: each element a point, compensated in place; an index the run gives, one
//! outside the array, or an element the program assigns refused naming the line. A label defined
//! twice in a routine refused naming both lines.

use stiffid::internal::machining::program::{self, Dialect};
use stiffid::Error;

const DAT: &str = "DEFDAT cell\nDECL E6AXIS XJ[3]\nXJ[1]={A1 1, A2 -85, A3 85, A4 0, A5 40, A6 0}\nXJ[2]={A1 2, A2 -80, A3 80, A4 0, A5 40, A6 0}\nENDDAT\n";

fn parse(src: &str) -> stiffid::Result<program::JointProgram> {
    let context = program::Context::default().with_data(Some(DAT));
    program::parse_in(src, Dialect::Krl, &context)
}

#[test]
fn elements_of_an_array_with_literal_indices_are_points_of_their_own() {
    // By literal indices, and by a FOR loop's variable (unrolled).
    let looped = "DEF cell( )\nINT I\nFOR I = 2 TO 1 STEP -1\nPTP XJ[I]\nENDFOR\nPTP XJ[2]\nEND\n";
    for src in [
        "DEF cell( )\nPTP XJ[2]\nPTP XJ[1]\nPTP XJ[2]\nEND\n",
        looped,
    ] {
        elements_compensated_in_place(src);
    }
}

fn elements_compensated_in_place(src: &str) {
    let p = parse(src).unwrap();
    let a1: Vec<f64> = p.targets.iter().map(|t| t.q_deg[0]).collect();
    assert_eq!(a1, [2.0, 1.0, 2.0]);
    assert_eq!(p.targets[1].q_deg, [1.0, -85.0, 85.0, 0.0, 40.0, 0.0]);
    let mut q: Vec<[f64; 6]> = p.targets.iter().map(|t| t.q_deg).collect();
    q[1][1] = -85.5;
    let (main, data, _) = p.write_files(&q, &vec![Vec::new(); 3]).unwrap();
    assert_eq!(main, src);
    assert_eq!(data.unwrap(), DAT.replace("A2 -85,", "A2 -85.500000000,"));
}

/// A FOR loop whose motion goes to a point its body computes from the variable: each run a target
/// of its own, which the motion's one line cannot hold once compensated apart: refused naming it.
#[test]
fn a_loop_whose_runs_need_apart_one_point_is_refused_naming_the_motion() {
    let dat = "DEFDAT cell\nDECL E6AXIS XK={A1 0, A2 -85, A3 85, A4 0, A5 40, A6 0}\nENDDAT\n";
    let src = "DEF cell( )\nINT I\nFOR I = 1 TO 2\nXK = {A1 0, A2 -85, A3 85, A4 0, A5 40, A6 0}\nXK.A1 = I\nPTP XK\nENDFOR\nEND\n";
    let context = program::Context::default().with_data(Some(dat));
    let p = program::parse_in(src, Dialect::Krl, &context).unwrap();
    let a1: Vec<f64> = p.targets.iter().map(|t| t.q_deg[0]).collect();
    assert_eq!(a1, [1.0, 2.0]);
    let q: Vec<[f64; 6]> = (p.targets.iter())
        .map(|t| [t.q_deg[0], -85.5, 85.0, 0.0, 40.0, 0.0])
        .collect();
    match p.write_files(&q, &vec![Vec::new(); 2]) {
        Err(Error::Program { line: 6, message }) => {
            assert!(message.contains("runs more than once"), "{message}")
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn an_element_the_file_does_not_state_is_refused_naming_the_line() {
    for (src, line, what) in [
        (
            "DEF cell( )\nPTP XJ[1]\nPTP XJ[4]\nEND\n",
            3,
            "outside the array XJ[3]",
        ),
        (
            "DEF cell( )\nPTP XJ[1]\nPTP XJ[3]\nEND\n",
            3,
            "no value of this element",
        ),
        (
            "DEF cell( )\nINT I\nI = $IN[2]\nPTP XJ[I]\nEND\n",
            4,
            "index the run gives",
        ),
        (
            "DEF cell( )\nXJ[1] = XJ[2]\nPTP XJ[1]\nEND\n",
            3,
            "assigned on line 2",
        ),
    ] {
        match parse(src) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{message}");
                assert!(message.contains(what), "{src}: {message}");
            }
            other => panic!("{src}: {other:?}"),
        }
    }
}

#[test]
fn a_label_defined_twice_in_a_routine_is_refused_naming_both_lines() {
    let src = "DEF cell( )\nPTP XJ[1]\nTOP:\nPTP XJ[2]\ntop:\nEND\n";
    match parse(src) {
        Err(Error::Program { line: 5, message }) => {
            assert!(message.contains("lines 3 and 5"), "{message}")
        }
        other => panic!("{other:?}"),
    }
    // One label per routine: two routines may each have theirs.
    let two = "DEF cell( )\nTOP:\nPTP XJ[1]\nEND\nDEF other( )\nTOP:\nEND\n";
    assert!(parse(two).is_ok());
}
