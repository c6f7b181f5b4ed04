//! Property tests of the robot-program readers (KRL, RAPID, LS, INFORM): the milling example's
//! programs (and a small INFORM job) mutated, and with a hostile number as a programmed speed,
//! never panic, and whatever is accepted has one speed per target, finite axis angles for every
//! joint target, and every speed read within its limits.
//!
//! Generated cases per run: 4 x 48 mutated programs + 4 x 48 programs with a hostile speed =
//! 384. Each test counts the inputs its reader accepted ([`Tally`]) and fails when fewer than
//! its least were.

use crate::mutate;

use mutate::{apply, edit, hostile_number, Tally};
use proptest::prelude::*;
use stiffid::internal::machining::program::speed::Speed;
use stiffid::internal::machining::program::{self, Dialect};

const CASES: u32 = 48;
/// The largest path speed and the longest move a reader takes (the reference's), mm/s and s.
const MAX_PATH_SPEED_MM_S: f64 = 10_000.0;
const MAX_DURATION_S: f64 = 3_600.0;
// The least accepted of each test's inputs, about a third of what a run accepts (seen: 6 to 20
// of 48 mutated, 14 of 48 with a hostile speed).
const LEAST_MUTATED: u32 = 2;
const LEAST_HOSTILE: u32 = 5;

const INFORM: &str = "/JOB\r\n//NAME POCKET\r\n//POS\r\n///NPOS 2,0,0,0,0,0\r\n///TOOL 0\r\n///POSTYPE PULSE\r\n///PULSE\r\nC00000=1000,-2050,3000,0,-4500,500\r\nC00001=1100,-2000,3000,0,-4400,500\r\n//INST\r\n///DATE 2026/11/25 12:00\r\n///ATTR SC,RW\r\n///GROUP1 RB1\r\n'stiffid: pulses_per_deg = 100 100 100 100 100 100\r\nNOP\r\nMOVJ C00000 VJ=50.00\r\nMOVL C00001 V=100.0 PL=0\r\nEND\r\n";

/// A program of each dialect, and the text of its first programmed path speed.
fn programs() -> [(&'static str, Dialect, &'static str); 4] {
    [
        (crate::common::pocket_krl(), Dialect::Krl, "$VEL.CP = 0.03"),
        (
            include_str!("../../../../examples/milling/pocket.mod"),
            Dialect::Rapid,
            "[30,500,5000,1000]",
        ),
        (
            include_str!("../../../../examples/milling/pocket.ls"),
            Dialect::FanucLs,
            "30mm/sec",
        ),
        (INFORM, Dialect::Inform, "V=100.0"),
    ]
}

/// The first programmed speed of `text` written as the hostile number `n`.
fn with_speed(text: &str, speed: &str, n: &str) -> String {
    let hostile = match speed {
        "$VEL.CP = 0.03" => format!("$VEL.CP = {n}"),
        "[30,500,5000,1000]" => format!("[{n},500,5000,1000]"),
        "30mm/sec" => format!("{n}mm/sec"),
        _ => format!("V={n}"),
    };
    text.replacen(speed, &hostile, 1)
}

/// Whether `text` is read as a `dialect` program; what is read must be usable (module docs).
fn check(text: &str, dialect: Dialect) -> bool {
    let Ok(p) = program::parse(text, dialect) else {
        return false;
    };
    for t in &p.targets {
        if t.cartesian.is_none() {
            assert!(t.q_deg.iter().all(|v| v.is_finite()), "line {}", t.line);
        }
        match t.speed {
            Speed::Path(v) => assert!(v > 0.0 && v * 1e3 <= MAX_PATH_SPEED_MM_S, "{v}"),
            Speed::Duration(s) => assert!(s > 0.0 && s <= MAX_DURATION_S, "{s}"),
            Speed::Joint | Speed::Unread(_) => {}
        }
    }
    true
}

proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        // A fixed seed: every run tries the same cases (set another to explore).
        rng_seed: proptest::test_runner::RngSeed::Fixed(20_211_126),
        ..proptest::prelude::ProptestConfig::with_cases(CASES)
    })]

    #[test]
    fn mutated_programs(edits in prop::collection::vec(edit(), 1..4)) {
        static TALLY: [Tally; 4] = [
            Tally::new("mutated KRL", CASES, LEAST_MUTATED),
            Tally::new("mutated RAPID", CASES, LEAST_MUTATED),
            Tally::new("mutated LS", CASES, LEAST_MUTATED),
            Tally::new("mutated INFORM", CASES, LEAST_MUTATED),
        ];
        for (k, (text, dialect, _)) in programs().into_iter().enumerate() {
            TALLY[k].count(check(&apply(text, &edits), dialect));
        }
    }

    #[test]
    fn hostile_speeds(n in hostile_number()) {
        static TALLY: [Tally; 4] = [
            Tally::new("KRL with a hostile speed", CASES, LEAST_HOSTILE),
            Tally::new("RAPID with a hostile speed", CASES, LEAST_HOSTILE),
            Tally::new("LS with a hostile speed", CASES, LEAST_HOSTILE),
            Tally::new("INFORM with a hostile speed", CASES, LEAST_HOSTILE),
        ];
        for (k, (text, dialect, speed)) in programs().into_iter().enumerate() {
            assert!(text.contains(speed), "{dialect:?}");
            TALLY[k].count(check(&with_speed(text, speed, &n), dialect));
        }
    }
}
