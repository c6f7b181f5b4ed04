//! Each target's bound in a program (`stiffid::app::compensate::certify`).

use stiffid::app::compensate::certify::*;
use stiffid_machining::program::Dialect;

#[test]
fn every_target_carries_its_bound() {
    let krl = "DEF A( )\nPTP {A1 1, A2 2, A3 3, A4 4, A5 5, A6 6} ; start\nLIN {A1 1}\nEND\n";
    let out = at_lines(Dialect::Krl, krl, &[(2, 1.5e-5), (3, 2e-5)], 0.95);
    assert!(out.contains("; start ; bound 0.0150 mm at 95%\n"), "{out}");
    assert!(
        out.contains("LIN {A1 1} ; bound 0.0200 mm at 95%\n"),
        "{out}"
    );
    // Compensated again: the new bound in the old one's place, the user's comment kept.
    let again = at_lines(Dialect::Krl, &out, &[(2, 3e-5), (3, f64::INFINITY)], 0.95);
    assert!(
        again.contains("; start ; bound 0.0300 mm at 95%\n"),
        "{again}"
    );
    // An infinite bound says how many held-out values a finite one needs at the level.
    let infinite = "LIN {A1 1} ; bound infinite at 95% (needs 19 held-out values)\n";
    assert!(again.contains(infinite), "{again}");
    // A comment of the older form is a bound too: compensated again, it is replaced.
    let older = again.replace(
        infinite,
        "LIN {A1 1} ; bound infinite at 95% (too few held-out values)\n",
    );
    let replaced = at_lines(Dialect::Krl, &older, &[(3, 1e-5)], 0.95);
    assert!(
        replaced.contains("LIN {A1 1} ; bound 0.0100 mm at 95%\n"),
        "{replaced}"
    );
    let third = at_lines(Dialect::Krl, &again, &[(3, 1e-5)], 0.95);
    assert!(
        third.contains("LIN {A1 1} ; bound 0.0100 mm at 95%\n"),
        "{third}"
    );
    let inform = "NOP\nMOVJ C00000 VJ=10.00\nEND\n";
    let once = at_lines(Dialect::Inform, inform, &[(2, 1e-5)], 0.95);
    let twice = at_lines(Dialect::Inform, &once, &[(3, 2e-5)], 0.95);
    assert_eq!(
        twice,
        "NOP\n'bound 0.0200 mm at 95%\nMOVJ C00000 VJ=10.00\nEND\n"
    );
    let rapid = "  MoveAbsJ [[1,2,3,\n 4,5,6],[9E9]], v10, fine, tool0;\n";
    let out = at_lines(Dialect::Rapid, rapid, &[(1, 1e-5)], 0.9);
    assert!(
        out.ends_with("tool0; ! bound 0.0100 mm at 90%\n")
            && out.starts_with("  MoveAbsJ [[1,2,3,\n"),
        "{out}"
    );
    let again = at_lines(Dialect::Rapid, &out, &[(1, 2e-5)], 0.9);
    assert!(
        again.ends_with("tool0; ! bound 0.0200 mm at 90%\n"),
        "{again}"
    );
    let ls = "/MN\n   1:J P[1] 100% FINE ;\n   2:L P[2] 5mm/sec FINE ;\n/POS\nP[1]{\n J1= 1 deg\n};\nP[2:\"HOME\"]{\n};\n/END\n";
    let out = at_lines(Dialect::FanucLs, ls, &[(2, 3e-5), (3, 4e-5)], 0.95);
    assert!(out.contains("P[1:\"0.0300 mm\"]{\n"), "{out}");
    assert!(out.contains("P[2:\"HOME\"]{\n"), "{out}");
    let again = at_lines(Dialect::FanucLs, &out, &[(2, 7e-5), (3, 4e-5)], 0.95);
    assert!(
        again.contains("P[1:\"0.0700 mm\"]{\n") && !again.contains("0.0300"),
        "{again}"
    );
    // A circular motion: its via point and its end (on the continuation line) both carry it.
    let circular = "/PROG C\n/MN\n   1:C P[1]\n    :  P[2] 10mm/sec FINE\n    :  Arc End[1] ;\n   2:L P[3] 10mm/sec FINE ;\n/POS\nP[1]{\n};\nP[2]{\n};\nP[3]{\n};\n/END\n";
    let out = at_lines(
        Dialect::FanucLs,
        circular,
        &[(3, 2e-5), (3, 3e-5), (6, 1e-5)],
        0.95,
    );
    for (i, b) in [(1, "0.0300"), (2, "0.0300"), (3, "0.0100")] {
        assert!(out.contains(&format!("P[{i}:\"{b} mm\"]{{\n")), "{out}");
    }
    let generated = generated(
        Dialect::FanucLs,
        &[ls.to_string()],
        &[Some(5e-5), Some(6e-5)],
        0.95,
    );
    assert!(
        generated[0].contains("P[1:\"0.0500 mm\"]{"),
        "{}",
        generated[0]
    );
}

/// A job whose written text holds lines the read one does not (an INFORM variable's copy in
/// `//POS`) takes each bound before its motion's line where it now is, never inside `//POS`.
#[test]
fn a_bound_goes_before_its_motion_after_inserted_lines() {
    let read = "//POS\r\nC00000=1\r\n//INST\r\nMOVJ C00000\r\nMOVL P002\r\nMOVL P002\r\nEND\r\n";
    let written = "//POS\r\nC00000=2\r\n///PULSE\r\nC00001=3\r\n//INST\r\nMOVJ C00000\r\nMOVL C00001\r\nMOVL P002\r\nEND\r\n";
    let lines = moved(read, written, &[(4, 1e-5), (5, 2e-5), (6, 3e-5)]);
    assert_eq!(lines, [(6, 1e-5), (7, 2e-5), (8, 3e-5)]);
    let out = at_lines(Dialect::Inform, written, &lines, 0.95);
    assert!(out.contains("C00001=3\r\n//INST\r\n'bound 0.0100 mm at 95%\r\nMOVJ C00000\r\n'bound 0.0200 mm at 95%\r\nMOVL C00001\r\n'bound 0.0300 mm at 95%\r\nMOVL P002\r\n"), "{out}");
    assert_eq!(moved(read, read, &[(4, 1e-5)]), [(4, 1e-5)]);
}
