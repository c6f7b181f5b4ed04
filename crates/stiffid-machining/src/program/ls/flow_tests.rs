//! The order of run of LS instructions ([`super`]).

use super::*;

/// The instructions of `lines`, numbered from line 1, and which are motions (`L ..`).
fn read(lines: &[&str]) -> (Vec<(u64, String)>, Vec<bool>) {
    let instructions: Vec<(u64, String)> = (lines.iter().enumerate())
        .map(|(i, t)| (i as u64 + 1, t.to_string()))
        .collect();
    let motions = lines.iter().map(|t| t.starts_with("L ")).collect();
    (instructions, motions)
}

#[test]
fn jumps_branches_and_loops_have_their_successors() {
    let (i, m) = read(&[
        "LBL[1:top]",
        "IF R[1]=1,JMP LBL[2]",
        "L P[1] 10mm/sec FINE",
        "IF (R[2]=1) THEN",
        "L P[2] 10mm/sec FINE",
        "ELSE",
        "L P[3] 10mm/sec FINE",
        "ENDIF",
        "FOR R[3]=1 TO 3",
        "L P[4] 10mm/sec FINE",
        "ENDFOR",
        "LBL[2]",
        "SELECT R[4]=1,JMP LBL[1]",
        "=2,JMP LBL[2]",
        "ELSE,JMP LBL[3]",
        "LBL[3]",
        "END",
    ]);
    let g = graph(&i, &m).unwrap();
    let expected: Vec<Vec<usize>> = vec![
        vec![1],
        vec![2, 11],
        vec![3],
        vec![4, 6],
        vec![5],
        vec![7],
        vec![7],
        vec![8],
        vec![9],
        vec![10],
        vec![9, 11],
        vec![12],
        vec![13, 0],
        vec![14, 11],
        vec![15],
        vec![16],
        vec![],
    ];
    assert_eq!(g.next, expected);
    assert!(g.reached().iter().all(|r| *r));
    assert!(g.stops[14] && g.stops[16] && !g.stops[13]);
}

#[test]
fn a_missing_label_a_register_label_and_an_open_if_are_refused_naming_the_line() {
    for (lines, line, why) in [
        (&["L P[1] 10mm/sec FINE", "JMP LBL[4]"][..], 2, "no LBL[4]"),
        (
            &["JMP LBL[R[1]]", "L P[1] 10mm/sec FINE"][..],
            1,
            "from a register",
        ),
        (
            &["IF (R[1]=1) THEN", "L P[1] 10mm/sec FINE"][..],
            1,
            "without its ENDIF",
        ),
        (
            &["L P[1] 10mm/sec FINE", "ENDFOR"][..],
            2,
            "without its FOR",
        ),
        (&["LBL[1]", "LBL[1]"][..], 2, "also on line 1"),
    ] {
        let (i, m) = read(lines);
        match graph(&i, &m) {
            Err(stiffid_core::Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{message}");
                assert!(message.contains(why), "{message}");
            }
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn a_value_set_on_one_path_only_joins_where_paths_meet() {
    let (i, m) = read(&[
        "IF R[1]=1,JMP LBL[1]",
        "R[2]=5",
        "LBL[1]",
        "L P[1] 10mm/sec FINE",
    ]);
    let g = graph(&i, &m).unwrap();
    // The state: the value set, or `None` where paths disagree.
    let states = g.states(
        Some(0),
        |k, s: &Option<i32>| if k == 1 { Some(5) } else { *s },
        |a, b, _| {
            let changed = *a != *b && a.is_some();
            if changed {
                *a = None;
            }
            changed
        },
    );
    assert_eq!(states[1], Some(Some(0)));
    assert_eq!(states[3], Some(None));
}

/// A `FOR` loop's bounds: numbers decide whether its body runs; a register's leave both; any
/// other form is refused naming the line.
#[test]
fn a_for_loops_bounds_are_read_or_refused_naming_the_line() {
    let next = |f: &str| {
        let (i, m) = read(&["L P[1] 10mm/sec FINE", f, "L P[2] 10mm/sec FINE", "ENDFOR"]);
        graph(&i, &m).map(|g| g.next[1].clone())
    };
    assert_eq!(next("FOR R[1]=1 TO 3").unwrap(), [2]);
    assert_eq!(next("FOR R[1:count]=3 DOWNTO -2").unwrap(), [2]);
    assert_eq!(next("FOR R[1]=5 TO 5").unwrap(), [2]);
    assert_eq!(next("FOR R[1]=5 TO 4").unwrap(), [4]);
    assert_eq!(next("FOR R[1]=1 DOWNTO 3").unwrap(), [4]);
    assert_eq!(next("FOR R[1]=1 TO R[2:n]").unwrap(), [2, 4]);
    assert_eq!(next("FOR R[1]=AR[1] DOWNTO 0").unwrap(), [2, 4]);
    for bad in [
        "FOR R[1]=1 TO abc",
        "FOR R[1]=1 TO",
        "FOR R[1]=1 UPTO 3",
        "FOR P[1]=1 TO 3",
        "FOR R[x]=1 TO 3",
        "FOR R[1]=1.5 TO 3",
        "FOR R[1]=AR[1 TO 3",
        "FOR",
    ] {
        let e = next(bad).unwrap_err().to_string();
        assert!(
            e.contains("line 2") && e.contains("expected FOR R[i]=a TO b"),
            "{bad}: {e}"
        );
    }
    // A body that never runs: its motion is reached by no path.
    let (i, m) = read(&[
        "L P[1] 10mm/sec FINE",
        "FOR R[1]=2 TO 1",
        "L P[2] 10mm/sec FINE",
        "ENDFOR",
    ]);
    assert_eq!(graph(&i, &m).unwrap().reached(), [true, true, false, false]);
}
