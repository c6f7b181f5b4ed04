//! The expansion against LinuxCNC's own interpreter tests (`nc_files/interp_test_*.ngc`, whose
//! comments state where the machine ends) and hand readings of FANUC/Haas macro B.

use super::expand;
use stiffid_core::setup::GcodeDialect;

fn run(text: &str, d: Option<GcodeDialect>) -> (String, Vec<u64>) {
    let e = expand(text, d).expect("expands").expect("needs expanding");
    (e.text, e.lines)
}

fn err(text: &str, d: Option<GcodeDialect>) -> (u64, String) {
    match expand(text, d) {
        Err(stiffid_core::Error::Program { line, message }) => (line, message),
        other => panic!(
            "expected a refusal, got {:?}",
            other.map(|e| e.map(|e| e.text))
        ),
    }
}

const LINUXCNC: Option<GcodeDialect> = Some(GcodeDialect::LinuxCnc);
const FANUC: Option<GcodeDialect> = Some(GcodeDialect::Fanuc);
const HAAS: Option<GcodeDialect> = Some(GcodeDialect::Haas);

#[test]
fn plain_programs_are_not_expanded() {
    assert!(expand("G21\nG0 X1 Y2 Z3 (a #comment [x])\nM30\n", None)
        .unwrap()
        .is_none());
    assert!(expand("%\nO1000\nG0 X1\nM30\n%\n", FANUC)
        .unwrap()
        .is_none());
}

#[test]
fn linuxcnc_nested_calls_with_arguments() {
    // LinuxCNC's interp_test_sub.ngc: "on exit X=2.4 Y=3.5 Z=4.6".
    let text = "%\no100 sub\no[150+50] call [2+#1][3+#2][4+#3]\no100 endsub\no200 sub\ng0 x#1 y#2 z#3\no200 endsub\no100 call [.1] [.2] [.3]\no100 call [.4] [.5] [.6]\n%\n";
    let (t, lines) = run(text, LINUXCNC);
    assert_eq!(t, "%\ng0 x2.1 y3.2 z4.3\ng0 x2.4 y3.5 z4.6\n%\n");
    assert_eq!(lines, vec![1, 6, 6, 10]);
}

#[test]
fn linuxcnc_loops_break_and_continue() {
    // LinuxCNC's interp_test_loop.ngc: "on exit X = 5.323 Y = 3.0 Z = 3.0".
    let text = "g0x0y0z0\n#100=0\no130 do\n#100=[#100+1]\ng0 x#100\no130 while [#100 LT 5.0]\n#101=0\no140 while [#101 LT 3]\n#101=[#101+1]\ng0 y#101\no140 endwhile\n#102=0\no150 while [#102 LT 3]\n#102=[#102+1]\ng0 z#102\no151 if [#102 eq 2]\no150 break\ng0 z5\no151 endif\no150 endwhile\ng0 x[#100+#101/10+#102/100]\n#103=0\no160 while [#103 LT 3]\n#103=[#103+1]\ng0 z#103\no161 if [#103 lt 100]\no160 continue\ng0 z5\no161 endif\no160 endwhile\ng0 x[#100+#101/10+#102/100+#103/1000]\n";
    let (t, _) = run(text, LINUXCNC);
    let moves: Vec<&str> = t.lines().collect();
    assert_eq!(moves[1..6], ["g0 x1", "g0 x2", "g0 x3", "g0 x4", "g0 x5"]);
    assert_eq!(moves[6..9], ["g0 y1", "g0 y2", "g0 y3"]);
    // The break leaves at #102 = 2 (the z5 after it is inside the if): z1, z2.
    assert_eq!(moves[9..11], ["g0 z1", "g0 z2"]);
    let x = |m: &str| m.strip_prefix("g0 x").and_then(|v| v.parse::<f64>().ok());
    assert_eq!(x(moves[11]), Some(5.0 + 3.0 / 10.0 + 2.0 / 100.0));
    // The continue skips the z5: z1, z2, z3; the file's "on exit X = 5.323".
    assert_eq!(moves[12..15], ["g0 z1", "g0 z2", "g0 z3"]);
    assert!((x(moves[15]).unwrap_or(0.0) - 5.323).abs() < 1e-12);
    assert_eq!(moves.len(), 16);
}

#[test]
fn linuxcnc_if_elseif_else_and_precedence() {
    // LinuxCNC's interp_test_if.ngc ("exits with X=.4 Z=4") and interp_test_operator.ngc
    // ("X = 1.0 Z = 1.0").
    let text = "#100=0\n#101=0\n#102=0\n#103=0\n#104=0\n#200=0\n#201=0\n#202=0\n#203=0\n#204=0\no1 if[1 eq 0]\n#200=.1\no1 elseif[2 eq 0]\n#201=.2\no1 elseif[3 eq 3]\n   #202=.4\n   o2 if[1 eq 0]\n   #100 = 1\n   o2 elseif[2 eq 0]\n   #101 = 2\n   o2 elseif[3 eq 3]\n   #102 = 4\n   o2 elseif[4 eq 4]\n   #103 = 8\n   o2 else\n   #104 = 16\n   o2 endif\no1 elseif[4 eq 4]\n#203=1.0\no1 else\n#204=2.0\no1 endif\ng0z[#100+#101+#102+#103+#104] x[#200+#201+#202+#203+#204]\n#2 = [[2*3+4]/10]\n#1 = [1+2 eq 3 and 2*3+4 eq 10]\ng0 x#1\ng0 z#2\n";
    let (t, lines) = run(text, LINUXCNC);
    assert_eq!(t, "g0z4 x0.4\ng0 x1\ng0 z1\n");
    assert_eq!(lines, vec![33, 36, 37]);
}

#[test]
fn linuxcnc_repeat_functions_and_named_parameters() {
    let text = "#<r> = 10\n#<_n> = 0\no1 repeat [3]\n#<_n> = [#<_n> + 1]\nG1 X[#<r> * COS[#<_n> * 30]] Y[ATAN[1]/[1]] Z[2 ** 3 MOD 5] F[SQRT[16]]\no1 endrepeat\nG0 X[FIX[-1.5]] Y[FUP[-1.5]] Z[ROUND[-2.5]]\nM2\nG0 X99\n";
    let (t, _) = run(text, LINUXCNC);
    let l: Vec<&str> = t.lines().collect();
    assert_eq!(l.len(), 5, "{t}");
    assert_eq!(
        l[0],
        format!("G1 X{} Y45 Z3 F4", 10.0 * 30f64.to_radians().cos())
    );
    assert_eq!(
        l[2],
        format!("G1 X{} Y45 Z3 F4", 10.0 * 90f64.to_radians().cos())
    );
    // LinuxCNC's FIX and FUP are floor and ceil; ROUND half away from zero.
    assert_eq!(l[3], "G0 X-2 Y-1 Z-3");
    assert_eq!(l[4], "M2");
}

#[test]
fn fanuc_subprogram_with_repeats_and_shared_locals() {
    let text = "%\nO1000\nG90 G21\n#1 = 0\nM98 P2000 L3\nG0 X#1\nM30\nO2000\n#1 = #1 + 2.5\nG1 Y#1 F100\nM99\n%\n";
    let (t, lines) = run(text, FANUC);
    assert_eq!(
        t,
        "%\nO1000\nG90 G21\nG1 Y2.5 F100\nG1 Y5 F100\nG1 Y7.5 F100\nG0 X7.5\nM30\n"
    );
    assert_eq!(lines, vec![1, 2, 3, 10, 10, 10, 6, 7]);
}

#[test]
fn fanuc_g65_macro_while_if_goto() {
    // A bolt circle macro: A = count, R = radius (#18), B = start angle.
    let text = "O1\nG65 P9100 A4 R10 B45\nM30\nO9100\n#10 = 0\nWHILE [#10 LT #1] DO 1\n#11 = #2 + #10 * 360 / #1\nG0 X[#18 * COS[#11]] Y[#18 * SIN[#11]]\n#10 = #10 + 1\nIF [#10 EQ 3] GOTO 100\nEND 1\nN100 G0 Z50\nM99\n";
    let (t, lines) = run(text, FANUC);
    let l: Vec<&str> = t.lines().collect();
    assert_eq!(l.len(), 6, "{t}");
    let at = |deg: f64| {
        format!(
            "G0 X{} Y{}",
            10.0 * deg.to_radians().cos(),
            10.0 * deg.to_radians().sin()
        )
    };
    assert_eq!(l[1..4], [at(45.0), at(135.0), at(225.0)]);
    assert_eq!(l[4], "N100 G0 Z50");
    assert_eq!(lines, vec![1, 8, 8, 8, 12, 3]);
}

#[test]
fn haas_m97_local_subprogram() {
    let text = "O00010\nG0 X0 Y0\nM97 P100 L2\nM30\nN100 G91 G1 X5 F100\nG90\nM99\n";
    let (t, lines) = run(text, HAAS);
    assert_eq!(
        t,
        "O00010\nG0 X0 Y0\nN100 G91 G1 X5 F100\nG90\nN100 G91 G1 X5 F100\nG90\nM30\n"
    );
    assert_eq!(lines, vec![1, 2, 5, 6, 5, 6, 4]);
    let (line, m) = err(text, FANUC);
    assert_eq!(line, 3);
    assert!(m.contains("Haas"), "{m}");
}

#[test]
fn refusals_name_the_line() {
    let (line, m) = err("G0 X1\nM98 P5000\nM30\n", FANUC);
    assert_eq!(line, 2);
    assert!(m.contains("O5000 is not in this file"), "{m}");
    let (line, m) = err("G0 X1\no<probe> call\nM2\n", LINUXCNC);
    assert_eq!(line, 2);
    assert!(m.contains("no O<probe> sub in this file"), "{m}");
    let (line, m) = err("#1 = #5061\nG0 X#1\n", LINUXCNC);
    assert_eq!(line, 1);
    assert!(m.contains("#5061") && m.contains("run time"), "{m}");
    let (line, m) = err("G0 X#100\n", FANUC);
    assert_eq!(line, 1);
    assert!(m.contains("before the program sets it"), "{m}");
    let (line, m) = err("#1 = 0\nWHILE [#1 LT 1] DO 1\nG0 X1\nEND 1\n", FANUC);
    assert_eq!(line, 2, "{m}");
    assert!(m.contains("1000000 blocks"), "{m}");
    let (line, m) = err("o1 sub\no1 call\no1 endsub\no1 call\nM2\n", LINUXCNC);
    assert_eq!(line, 2);
    assert!(m.contains("deeper than 10"), "{m}");
    let (line, m) = err("G0 X1\nM99\n", HAAS);
    assert_eq!(line, 2);
    assert!(m.contains("forever"), "{m}");
    let (line, m) = err("#1 = 1\nG0 X[FIX[-#1 / 2]]\n", None);
    assert_eq!(line, 2);
    assert!(m.contains("dialect"), "{m}");
}

#[test]
fn fanuc_and_linuxcnc_differ_where_they_should() {
    // FIX of a negative value: towards zero on FANUC, down on LinuxCNC.
    assert_eq!(run("#1 = FIX[-1.5]\nG0 X#1\n", FANUC).0, "G0 X-1\n");
    assert_eq!(run("#1 = FIX[-1.5]\nG0 X#1\n", LINUXCNC).0, "G0 X-2\n");
    // EQ within 0.0001 on LinuxCNC.
    assert_eq!(
        run("o1 if [1 EQ 1.00005]\nG0 X1\no1 endif\n", LINUXCNC).0,
        "G0 X1\n"
    );
    assert_eq!(
        run("IF [1 EQ 1.5] GOTO 5\nG0 X1\nN5 G0 X2\n", FANUC).0,
        "G0 X1\nN5 G0 X2\n"
    );
}

/// A loop or branch without its end is refused naming its line (a controller alarms; run
/// through, the blocks after it were read as its body once, exit 0).
#[test]
fn a_loop_or_branch_without_its_end_is_refused_naming_its_line() {
    let cases = [
        (
            "#1 = 0\nWHILE [#1 LT 5] DO 1\nG0 X#1\n#1 = #1 + 1\nM30\n",
            FANUC,
            2,
            "END 1",
        ),
        ("o100 while [1]\nG0 X1\nM2\n", LINUXCNC, 1, "endwhile"),
        ("o100 if [1]\nG0 X1\nM2\n", LINUXCNC, 1, "endif"),
        ("o100 repeat [3]\nG0 X1\nM2\n", LINUXCNC, 1, "endrepeat"),
        ("o100 do\nG0 X1\nM2\n", LINUXCNC, 1, "while"),
    ];
    for (text, dialect, line, needle) in cases {
        let (l, m) = err(text, dialect);
        assert_eq!(l, line, "{text}: {m}");
        assert!(m.contains(needle), "{text}: {m}");
    }
    // With their ends, they run.
    assert_eq!(
        run("o100 repeat [2]\nG0 X1\no100 endrepeat\n", LINUXCNC).0,
        "G0 X1\nG0 X1\n"
    );
}
