//! KRL as KUKA System Software stores it (`stiffid_machining::program::krl`): points and frame
//! data in the `.dat`, inline forms old (`FDAT_ACT` + `BAS(#PTP_PARAMS)`) and new (`SLIN .. WITH
//! $TOOL = STOOL2(..)`), `CIRC`, loops and branches; every frame applied or refused, never
//! ignored.

use nalgebra::Vector3;
use stiffid_core::Error;
use stiffid_machining::program::cartesian::Frame;
use stiffid_machining::program::{self, parse_with_data, Dialect, JointProgram};

/// A `.src` with KSS 8.3 inline forms: a literal `$BASE` first (which the inline forms must
/// replace), PTP P1 and LIN P2 in tool 1 and base 2, CIRC P3 P4 in base 0, SLIN P5 with its own
/// WITH frames.
const SRC: &str = "&ACCESS RVP\r\n&REL 3\r\nDEF cell_cut( )\r\n;FOLD INI;%{PE}\r\n  BAS (#INITMOV,0 )\r\n;ENDFOLD (INI)\r\n$BASE = {X 680, Y 1000, Z 0, A 0, B 0, C 0}\r\n;FOLD PTP P1 Vel=100 % PDAT1 Tool[1] Base[2];%{PE}%R 8.3.21,%MKUKATPBASIS,%CMOVE,%VPTP,%P 1:PTP, 2:P1, 3:, 5:100, 7:PDAT1\r\n$BWDSTART=FALSE\r\nPDAT_ACT=PPDAT1\r\nFDAT_ACT=FP1\r\nBAS(#PTP_PARAMS,100)\r\nPTP XP1 \r\n;ENDFOLD\r\n;FOLD LIN P2 Vel=0.2 m/s CPDAT1 Tool[1] Base[2];%{PE}%R 8.3.21,%MKUKATPBASIS,%CMOVE,%VLIN,%P 1:LIN, 2:P2, 3:, 5:0.2, 7:CPDAT1\r\n$BWDSTART=FALSE\r\nLDAT_ACT=LCPDAT1\r\nFDAT_ACT=FP2\r\nBAS(#CP_PARAMS,0.2)\r\nLIN XP2 \r\n;ENDFOLD\r\nFDAT_ACT = {TOOL_NO 1, BASE_NO 0, IPO_FRAME #BASE}\r\nBAS(#FRAMES)\r\nCIRC XP3, XP4 C_DIS\r\nSLIN XP5 WITH $VEL = SVEL_CP(0.2, , LCPDAT1), $TOOL = STOOL2(FP5), $BASE = SBASE(FP5.BASE_NO), $IPO_MODE = SIPO_MODE(FP5.IPO_FRAME), $LOAD = SLOAD(FP5.TOOL_NO)\r\nEND\r\n";

/// Its `.dat`.
const DAT: &str = "&ACCESS RVP\r\n&REL 3\r\nDEFDAT  cell_cut\r\n;FOLD EXTERNAL DECLARATIONS;%{PE}%MKUKATPBASIS,%CEXT,%VCOMMON,%P\r\nEXT  BAS (BAS_COMMAND  :IN,REAL  :IN )\r\n;ENDFOLD (EXTERNAL DECLARATIONS)\r\nDECL BASIS_SUGG_T LAST_BASIS={POINT1[] \"P5\",POINT2[] \"P5\",CP_PARAMS[] \"CPDAT1\",PTP_PARAMS[] \"PDAT1\"}\r\nDECL E6POS XP1={X 120.5,Y -40.25,Z 300.0,A 10.0,B 80.0,C -5.0,S 6,T 27,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}\r\nDECL FDAT FP1={TOOL_NO 1,BASE_NO 2,IPO_FRAME #BASE,POINT2[] \" \"}\r\nDECL PDAT PPDAT1={VEL 100.0,ACC 100.0,APO_DIST 100.0,APO_MODE #CDIS}\r\nDECL E6POS XP2={X 220.5,Y -40.25,Z 300.0,A 10.0,B 80.0,C -5.0,S 6,T 27,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}\r\nDECL FDAT FP2={TOOL_NO 1,BASE_NO 2,IPO_FRAME #BASE,POINT2[] \" \"}\r\nDECL LDAT LCPDAT1={VEL 2.0,ACC 100.0,APO_DIST 100.0,APO_FAC 50.0,ORI_TYP #VAR}\r\nDECL E6POS XP3={X 250.0,Y -10.0,Z 300.0,A 10.0,B 80.0,C -5.0,S 6,T 27}\r\nDECL E6POS XP4={X 220.5,Y 20.0,Z 300.0,A 10.0,B 80.0,C -5.0,S 6,T 27}\r\nDECL E6POS XP5={X 120.5,Y 20.0,Z 300.0,A 10.0,B 80.0,C -5.0,S 6,T 27}\r\nDECL FDAT FP5={TOOL_NO 3,BASE_NO 4,IPO_FRAME #BASE,POINT2[] \" \"}\r\nENDDAT\r\n";

/// The 1-based line of `text` that holds `needle` first.
fn line_of(text: &str, needle: &str) -> u64 {
    text.lines().position(|l| l.contains(needle)).unwrap() as u64 + 1
}

/// The `E6POS` points of a `.dat`, read independently of stiffid: `(name, [X, Y, Z, A, B, C])`.
fn dat_points(dat: &str) -> Vec<(String, [f64; 6])> {
    let mut out = Vec::new();
    for l in dat.lines().filter(|l| l.starts_with("DECL E6POS ")) {
        let (name, body) = l["DECL E6POS ".len()..].split_once("={").unwrap();
        let mut v = [f64::NAN; 6];
        for member in body.trim_end_matches('}').split(',') {
            let (key, value) = member.split_once(' ').unwrap();
            if let Some(k) = ["X", "Y", "Z", "A", "B", "C"]
                .iter()
                .position(|n| *n == key)
            {
                v[k] = value.parse().unwrap();
            }
        }
        out.push((name.to_string(), v));
    }
    out
}

fn frames(p: &JointProgram, i: usize) -> (Frame, Frame) {
    let c = p.targets[i].cartesian.as_deref().unwrap();
    (c.frame.clone(), c.tool.clone())
}

#[test]
fn inline_forms_read_points_from_the_dat_and_frames_by_number() {
    let p = parse_with_data(SRC, Some(DAT), Dialect::Krl).unwrap();
    // PTP XP1, LIN XP2, CIRC's auxiliary XP3 and end XP4, SLIN XP5.
    let lines: Vec<u64> = p.targets.iter().map(|t| t.line).collect();
    let circ = line_of(SRC, "CIRC XP3");
    assert_eq!(
        lines,
        [
            line_of(SRC, "PTP XP1"),
            line_of(SRC, "LIN XP2"),
            circ,
            circ,
            line_of(SRC, "SLIN XP5")
        ]
    );
    let points = dat_points(DAT);
    assert_eq!(points.len(), 5);
    for (t, (name, v)) in p.targets.iter().zip(&points) {
        let c = t.cartesian.as_deref().unwrap();
        let r = c.rotation.euler_angles();
        let abc = [r.2.to_degrees(), r.1.to_degrees(), r.0.to_degrees()];
        for k in 0..3 {
            assert!((c.position_mm[k] - v[k]).abs() < 1e-12, "{name}");
            assert!((abc[k] - v[3 + k]).abs() < 1e-9, "{name}: {abc:?}");
        }
    }
    // The literal $BASE is replaced by FP1's tool 1 and base 2 where BAS applies them.
    let bas = line_of(SRC, "BAS(#PTP_PARAMS");
    assert_eq!(
        frames(&p, 0),
        (Frame::Numbered(bas, 2), Frame::Numbered(bas, 1))
    );
    let bas = line_of(SRC, "BAS(#CP_PARAMS");
    assert_eq!(
        frames(&p, 1),
        (Frame::Numbered(bas, 2), Frame::Numbered(bas, 1))
    );
    // A literal FDAT_ACT: base 0 is the world, whatever $BASE was set to before.
    let bas = line_of(SRC, "BAS(#FRAMES");
    for i in [2, 3] {
        assert_eq!(frames(&p, i), (Frame::World, Frame::Numbered(bas, 1)));
    }
    // KSS 8's WITH frames: the motion's own.
    let slin = line_of(SRC, "SLIN XP5");
    assert_eq!(
        frames(&p, 4),
        (Frame::Numbered(slin, 4), Frame::Numbered(slin, 3))
    );
}

/// The first Cartesian target of `src` (with [`DAT`]): its base's frame.
fn base_of(src: &str) -> Frame {
    let p = parse_with_data(src, Some(DAT), Dialect::Krl).unwrap();
    frames(&p, 0).0
}

#[test]
fn frames_stiffid_cannot_know_are_refused_naming_their_line_never_ignored() {
    let unknown = |src: String, line: u64, needle: &str| match base_of(&src) {
        Frame::Unknown(l, why) => {
            assert_eq!(l, line, "{why}");
            assert!(why.contains(needle), "{needle}: {why}");
        }
        other => panic!("{needle}: {other:?}"),
    };
    let ptp = line_of(SRC, "BAS(#PTP_PARAMS");
    let swap = |from: &str, to: &str| SRC.replacen(from, to, 1);
    // An external TCP, a record the files do not declare, an external kinematic, a variable.
    let external = swap(
        "FDAT_ACT=FP1",
        "FDAT_ACT={TOOL_NO 1,BASE_NO 2,IPO_FRAME #TCP}",
    );
    let p = parse_with_data(&external, Some(DAT), Dialect::Krl).unwrap();
    assert!(matches!(frames(&p, 0).0, Frame::Unknown(_, why) if why.contains("external TCP")));
    unknown(swap("FDAT_ACT=FP1", "FDAT_ACT=FP199"), ptp, "FP199");
    unknown(
        swap(
            "FDAT_ACT=FP1",
            "FDAT_ACT={TOOL_NO 1,BASE_NO 17,IPO_FRAME #BASE}",
        ),
        ptp,
        "external kinematic",
    );
    let var = swap(
        "FDAT_ACT=FP1\r\nBAS(#PTP_PARAMS,100)\r\n",
        "BAS(#BASE, MY_BASE)\r\n",
    );
    unknown(var, line_of(SRC, "FDAT_ACT=FP1"), "MY_BASE");
    // Frames set by INITMOV only: the BAS package's defaults.
    let bare = "DEF a( )\nBAS (#INITMOV,0 )\nPTP {X 1, Y 2, Z 3, A 0, B 0, C 0, S 2, T 0}\nEND\n";
    let p = parse_with_data(bare, None, Dialect::Krl).unwrap();
    assert!(matches!(frames(&p, 0).0, Frame::Unknown(2, why) if why.contains("INITMOV")));
    // After a motion with its own WITH frames, the next one without them is the controller's.
    let after = SRC.replace("END\r\n", "LIN XP1\r\nEND\r\n");
    let p = parse_with_data(&after, Some(DAT), Dialect::Krl).unwrap();
    let slin = line_of(SRC, "SLIN XP5");
    assert!(matches!(frames(&p, 5).0, Frame::Unknown(l, why) if l == slin && why.contains("WITH")));
    // Numbers selected by literal assignment and by BAS.
    let numbered = "DEF a( )\n$TOOL = TOOL_DATA[4]\nBAS(#BASE, 0)\nPTP {X 1, Y 2, Z 3, A 0, B 0, C 0, S 2, T 0}\nBAS(#TOOL, 0)\n$BASE = BASE_DATA[7]\nLIN {X 1, Y 2, Z 4, A 0, B 0, C 0}\nEND\n";
    let p = parse_with_data(numbered, None, Dialect::Krl).unwrap();
    assert_eq!(frames(&p, 0), (Frame::World, Frame::Numbered(2, 4)));
    assert_eq!(frames(&p, 1), (Frame::Numbered(6, 7), Frame::World));
}

/// A program that assigns an entry of the controller's base or tool table (`BASE_DATA[2] = {..}`,
/// as RoboDK's KUKA posts write before their motions) selects that frame by the number from
/// then on, not the setup's table; a selection before the assignment keeps the number; a member
/// assigned (`BASE_DATA[2].X = ..`, `$BASE.X = ..`) or an entry of a variable index refuses the
/// motions after it, naming the line.
#[test]
fn a_table_entry_the_program_assigns_is_the_frame_its_number_selects() {
    let src = |middle: &str| {
        format!("DEF a( )\n$BASE = BASE_DATA[2]\n{middle}\n$TOOL = TOOL_DATA[3]\nLIN {{X 1, Y 2, Z 3, A 0, B 0, C 0}}\n$BASE = BASE_DATA[2]\nLIN {{X 1, Y 2, Z 4, A 0, B 0, C 0}}\nEND\n")
    };
    let assigned = "BASE_DATA[2] = {FRAME: X 1500,Y 300,Z 400,A 90,B 0,C 0}\nTOOL_DATA[3] = {X 0,Y 0,Z 250,A 0,B 0,C 0}";
    let p = parse_with_data(&src(assigned), None, Dialect::Krl).unwrap();
    // The first motion: the base selected before the assignment (its number), the tool after.
    let (base, tool) = frames(&p, 0);
    assert_eq!(base, Frame::Numbered(2, 2));
    let Frame::Stated(4, t) = tool else {
        panic!("{tool:?}")
    };
    assert!((t.translation.vector - Vector3::new(0.0, 0.0, 0.25)).norm() < 1e-12);
    // The second: the base selected again, the program's entry.
    let Frame::Stated(3, b) = frames(&p, 1).0 else {
        panic!("{:?}", frames(&p, 1).0)
    };
    assert!((b.translation.vector - Vector3::new(1.5, 0.3, 0.4)).norm() < 1e-12);
    let turned = b.rotation * Vector3::x();
    assert!(
        (turned - Vector3::y()).norm() < 1e-12,
        "A 90 turns x onto y: {turned}"
    );
    for (middle, line, needle) in [
        (
            "BASE_DATA[2].X = 1500",
            3,
            "a member of an entry of BASE_DATA",
        ),
        (
            "BASE_DATA[I] = {X 0,Y 0,Z 0,A 0,B 0,C 0}",
            3,
            "whose index is not a number",
        ),
        ("$BASE.X = 1500", 3, "a member of $BASE"),
    ] {
        let p = parse_with_data(&src(middle), None, Dialect::Krl).unwrap();
        let base = frames(&p, if middle.starts_with('$') { 0 } else { 1 }).0;
        assert!(
            matches!(&base, Frame::Unknown(l, why) if *l == line && why.contains(needle)),
            "{middle}: {base:?}"
        );
    }
}

/// `PTP $AXIS_ACT` (RoboDK's KUKA posts begin with it) and `LIN $POS_ACT` move to where the robot
/// stands: no target, the motions around them read; any other system variable is refused.
#[test]
fn a_motion_to_where_the_robot_stands_moves_nothing() {
    let src = |first: &str| {
        format!("DEF a( )\n$BASE = {{X 0, Y 0, Z 0, A 0, B 0, C 0}}\n$TOOL = {{X 0, Y 0, Z 0, A 0, B 0, C 0}}\n{first}\nPTP {{A1 0, A2 -90, A3 90, A4 0, A5 45, A6 0}}\nlin $pos_act\nLIN {{X 1, Y 2, Z 4, A 0, B 0, C 0}}\nEND\n")
    };
    let p = parse_with_data(&src("PTP $AXIS_ACT"), None, Dialect::Krl).unwrap();
    let lines: Vec<u64> = p.targets.iter().map(|t| t.line).collect();
    assert_eq!(lines, [5, 7]);
    match parse_with_data(&src("PTP $AXIS_ACT_MES"), None, Dialect::Krl) {
        Err(Error::Program { line: 4, message }) => {
            assert!(message.contains("system variable"), "{message}")
        }
        other => panic!("{other:?}"),
    }
}

/// A declaration in a routine after the module's main one is local to it (KRL): two routines
/// may each declare `target`, and the main routine's motions see neither; a name declared twice
/// in the main routine is still refused.
#[test]
fn declarations_of_later_routines_are_their_own() {
    let fns = "DEFFCT INT F1( )\n  DECL E6POS target = {X 1, Y 2, Z 3, A 0, B 0, C 0, S 2, T 0}\n  RETURN 0\nENDFCT\nDEFFCT INT F2( )\n  DECL E6POS target = {X 9, Y 9, Z 9, A 0, B 0, C 0, S 2, T 0}\n  RETURN 0\nENDFCT\n";
    let main = |body: &str| format!("DEF a( )\n{body}\nEND\n{fns}");
    let p = parse_with_data(
        &main("PTP {A1 0, A2 -90, A3 90, A4 0, A5 45, A6 0}"),
        None,
        Dialect::Krl,
    )
    .unwrap();
    assert_eq!(p.targets.len(), 1);
    match parse_with_data(&main("PTP target"), None, Dialect::Krl) {
        Err(Error::Program { line: 2, message }) => {
            assert!(message.contains("not a point declared"), "{message}")
        }
        other => panic!("{other:?}"),
    }
    let twice = "DECL E6AXIS p = {A1 0, A2 -90, A3 90, A4 0, A5 45, A6 0}\nDECL E6AXIS p = {A1 1, A2 -90, A3 90, A4 0, A5 45, A6 0}\nPTP p";
    match parse_with_data(&main(twice), None, Dialect::Krl) {
        Err(Error::Program { line: 3, message }) => {
            assert!(message.contains("declared twice"), "{message}")
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_point_in_a_missing_dat_is_refused_naming_the_line_and_the_point() {
    let line = line_of(SRC, "PTP XP1");
    match parse_with_data(SRC, None, Dialect::Krl) {
        Err(Error::Program { line: l, message }) => {
            assert_eq!(l, line);
            assert!(
                message.contains("XP1") && message.contains(".dat"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    // A point of the .dat that cannot be read is refused by the motion to it.
    let dat = DAT.replace("{X 220.5,Y -40.25", "{X 220.5,Y -40.25S");
    match parse_with_data(SRC, Some(&dat), Dialect::Krl) {
        Err(Error::Program { line: l, message }) => {
            assert_eq!(l, line_of(SRC, "LIN XP2"));
            assert!(
                message.contains("XP2") && message.contains("of the .dat"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn circles_read_both_points_and_refuse_what_ends_elsewhere() {
    let refused = |src: String, needle: &str| match parse_with_data(&src, Some(DAT), Dialect::Krl) {
        Err(Error::Program { line, message }) => {
            assert_eq!(line, line_of(SRC, "CIRC XP3"), "{message}");
            assert!(message.contains(needle), "{needle}: {message}");
        }
        other => panic!("{needle}: {other:?}"),
    };
    refused(
        SRC.replace("CIRC XP3, XP4 C_DIS", "CIRC XP3, XP4, CA 90"),
        "CA",
    );
    refused(SRC.replace("CIRC XP3, XP4 C_DIS", "CIRC XP3"), "end point");
    refused(
        SRC.replace(
            "CIRC XP3, XP4 C_DIS",
            "CIRC {A1 0, A2 -90, A3 90, A4 0, A5 0, A6 0}, XP4",
        ),
        "axis angles",
    );
}

/// A motion KRL cannot read was passed over, dropping its target: a keyword with a stray
/// character (`LIN]`, `LIéN`), or a word after the approximation (`C_DIS XX`). Refused naming
/// the line.
#[test]
fn a_motion_krl_cannot_read_is_refused_not_passed_over() {
    let line = line_of(SRC, "CIRC XP3");
    for (motion, needle) in [
        ("CIRC] XP3, XP4 C_DIS", "'CIRC]': not a KRL statement"),
        (
            "CI\u{e9}RC XP3, XP4 C_DIS",
            "'CI\u{e9}RC': not a KRL statement",
        ),
        ("\\CIRC XP3, XP4 C_DIS", "'\\CIRC': not a KRL statement"),
        (
            "CIRC XP3, XP4 C_DIS XX",
            "CIRC: 'XX' after the target is not followed",
        ),
    ] {
        let src = SRC.replace("CIRC XP3, XP4 C_DIS", motion);
        match parse_with_data(&src, Some(DAT), Dialect::Krl) {
            Err(Error::Program { line: l, message }) => {
                assert_eq!(l, line, "{message}");
                assert!(message.contains(needle), "{needle}: {message}");
            }
            other => panic!("{motion}: {other:?}"),
        }
    }
    // A WITH clause holds expressions: the words after it are the controller's.
    let with = SRC.replace(
        "CIRC XP3, XP4 C_DIS",
        "CIRC XP3, XP4 C_DIS WITH $VEL.CP = 0.1",
    );
    let read = |src: &str| {
        parse_with_data(src, Some(DAT), Dialect::Krl)
            .unwrap()
            .targets
            .len()
    };
    assert_eq!(read(&with), read(SRC));
}

#[test]
fn motions_in_loops_branches_and_routines_are_read_where_they_are() {
    let wrapped = SRC
        .replace("$BWDSTART=FALSE\r\nPDAT_ACT=PPDAT1", "IF $IN[1] THEN\r\n  WAIT SEC 1\r\nENDIF\r\nLOOP\r\n  $OUT[2] = TRUE\r\n  EXIT\r\nENDLOOP\r\n$BWDSTART=FALSE\r\nPDAT_ACT=PPDAT1");
    let p = parse_with_data(&wrapped, Some(DAT), Dialect::Krl).unwrap();
    assert_eq!(p.targets.len(), 5);
    let inside = SRC.replace("LIN XP2 \r\n", "LOOP\r\nLIN XP2 \r\nENDLOOP\r\n");
    let p = parse_with_data(&inside, Some(DAT), Dialect::Krl).unwrap();
    let straight = parse_with_data(SRC, Some(DAT), Dialect::Krl).unwrap();
    assert_eq!(p.targets.len(), straight.targets.len());
    assert_eq!(p.targets[1].line, line_of(&inside, "LIN XP2"));
    assert_eq!(frames(&p, 1), frames(&straight, 1));
    // A frame set inside a branch leaves the next motion's frame to the run.
    let branch = SRC.replace(
        "FDAT_ACT=FP1\r\n",
        "IF $IN[2] THEN\r\nFDAT_ACT=FP1\r\nENDIF\r\n",
    );
    let p = parse_with_data(&branch, Some(DAT), Dialect::Krl).unwrap();
    let (set, open) = (
        line_of(&branch, "FDAT_ACT=FP1"),
        line_of(&branch, "IF $IN[2]"),
    );
    match frames(&p, 0).0 {
        Frame::Unknown(l, why) => {
            assert_eq!(l, line_of(&branch, "BAS(#PTP_PARAMS"), "{why}");
            for part in [format!("IF (line {open})"), format!("line {set}")] {
                assert!(why.contains(&part), "{part}: {why}");
            }
        }
        other => panic!("{other:?}"),
    }
    // Left as found on request: that motion named, the others read.
    let leave = program::Context::default()
        .with_data(Some(DAT))
        .with_leave_refused(true);
    let p = program::parse_in(&branch, Dialect::Krl, &leave).unwrap();
    assert_eq!(p.left.len(), 1);
    assert_eq!(p.left[0].line, line_of(&branch, "PTP XP1"));
    assert!(p.left[0].why.contains("IF"), "{}", p.left[0].why);
    assert!(p.targets.iter().all(|t| t.line != p.left[0].line));
    // A routine of the file that sets a frame, called before a motion.
    let called = SRC
        .replace("LIN XP2 \r\n", "set_base( )\r\nLIN XP2 \r\n")
        .replace(
            "END\r\n",
            "END\r\nDEF set_base( )\r\n$BASE = {X 1, Y 2, Z 3, A 0, B 0, C 0}\r\nEND\r\n",
        );
    let p = parse_with_data(&called, Some(DAT), Dialect::Krl).unwrap();
    let call = line_of(&called, "set_base( )");
    assert!(
        matches!(frames(&p, 1).0, Frame::Unknown(l, why) if l == call && why.contains("SET_BASE"))
    );
    // A jump anywhere.
    let jump = SRC.replace("END\r\n", "GOTO LABEL1\r\nEND\r\n");
    assert!(matches!(
        parse_with_data(&jump, Some(DAT), Dialect::Krl),
        Err(Error::Program { line, .. }) if line == line_of(&jump, "GOTO")
    ));
    // Motions in a routine no line of the file calls: its frames are its caller's.
    let called = SRC.replace("END\r\n", "END\r\nDEF sub( )\r\nPTP XP1\r\nEND\r\n");
    let p = parse_with_data(&called, Some(DAT), Dialect::Krl).unwrap();
    let last = p.targets.len() - 1;
    assert!(
        matches!(frames(&p, last).0, Frame::Unknown(_, why) if why.contains("DEF SUB") && why.contains("not called")),
        "{:?}",
        frames(&p, last)
    );
}

/// A literal `$BASE` or `$TOOL` beyond the limits (a position beyond 100 m, an angle beyond 1e4
/// deg) is no frame: 1e308 mm reached inverse kinematics as "inf mm away". The motions in it are
/// refused naming the line that set it and the member.
#[test]
fn a_literal_frame_beyond_the_limits_is_refused_naming_its_member() {
    for (frame, member) in [
        (
            "$BASE = {X 1e308, Y 0, Z 0, A 0, B 0, C 0}",
            "X 1e308: outside -100000 to 100000 mm",
        ),
        (
            "$TOOL = {X 0, Y 0, Z 250, A 0, B 0, C -2e4}",
            "C -20000: outside -10000 to 10000 deg",
        ),
    ] {
        let src = format!("DEF a( )\n$BASE = $WORLD\n$TOOL = $NULLFRAME\n{frame}\nLIN {{X 1, Y 2, Z 3, A 0, B 0, C 0, S 2, T 0}}\nEND\n");
        let p = parse_with_data(&src, None, Dialect::Krl).unwrap();
        let (base, tool) = frames(&p, 0);
        let set = if frame.starts_with("$BASE") {
            base
        } else {
            tool
        };
        match set {
            Frame::Unknown(4, why) => assert!(why.contains(member), "{why}"),
            other => panic!("{frame}: {other:?}"),
        }
    }
}

/// The BAS package's correction frames switched on before the inline forms (`TOOL_CORR_ON =
/// TRUE`, `BASE_CORR_ON = TRUE`): every tool or base `BAS(#FRAMES)`, `BAS(#PTP_PARAMS)`, `TOOL(n)`
/// or `STOOL2` selects after it is linked to the correction, which stiffid does not apply:
/// refused naming the switch's line, never read without the correction; switched off again, the
/// numbers are read.
#[test]
fn a_correction_frame_switched_on_before_the_inline_forms_is_refused() {
    let init = ";ENDFOLD (INI)\r\n";
    for (switch, base) in [
        ("TOOL_CORR_ON = TRUE", false),
        ("BASE_CORR_ON = TRUE", true),
    ] {
        let src = SRC.replacen(init, &format!("{init}{switch}\r\n"), 1);
        let p = parse_with_data(&src, Some(DAT), Dialect::Krl).unwrap();
        let on = line_of(&src, switch);
        for i in [0, 1, 4] {
            let (b, t) = frames(&p, i);
            let (corrected, other) = if base { (b, t) } else { (t, b) };
            assert!(
                matches!(&corrected, Frame::Unknown(_, why) if why.contains(&format!("line {on}"))),
                "{switch} target {i}: {corrected:?}"
            );
            assert!(
                !matches!(other, Frame::Unknown(..)),
                "{switch} {i}: {other:?}"
            );
        }
        let off = SRC.replacen(
            init,
            &format!("{init}{switch}\r\n{}\r\n", switch.replace("TRUE", "FALSE")),
            1,
        );
        let p = parse_with_data(&off, Some(DAT), Dialect::Krl).unwrap();
        let bas = line_of(&off, "BAS(#PTP_PARAMS");
        assert_eq!(
            frames(&p, 0),
            (Frame::Numbered(bas, 2), Frame::Numbered(bas, 1))
        );
    }
}
