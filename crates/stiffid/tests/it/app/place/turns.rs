//! The turns a placement's program does not pin (`stiffid::app::place::turns`).

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use stiffid::app::place::turns::{probes, warning};
use stiffid::app::place::Evaluation;

/// A placement at (1.5, 0.2, 0.55) m turned by `yaw_deg` about the base z axis, of peak bound
/// `peak` (m).
fn at(yaw_deg: f64, peak: f64) -> Evaluation {
    Evaluation {
        base_from_part: Isometry3::from_parts(
            Translation3::new(1.5, 0.2, 0.55),
            UnitQuaternion::from_euler_angles(0.0, 0.0, yaw_deg.to_radians()),
        ),
        peak,
        sum: peak,
        points: 1,
        worst_line: 1,
        limit_margin: 0.1,
        condition: 10.0,
        clearance: None,
    }
}

/// Other placements (yaw deg, peak m; a negative peak: as good, 11 mm away) and the turns named.
type Row = (&'static [(f64, f64)], Option<&'static str>);

#[test]
fn equally_good_turns_are_named_and_a_pinned_turn_is_not() {
    let placed = at(-135.0, 2.8257e-4);
    // The other placements evaluated, and the ranges of yaw the warning names (none: pinned).
    let rows: [Row; 5] = [
        // A rectangular pocket turned by a half turn about its centre: the same path.
        (&[(45.0, 2.8257e-4)], Some("turned -135.00, 45.00 deg")),
        // A flat optimum: turns within 5 deg as good (0.36% worse), and one 1% worse.
        (
            &[(-140.0, 2.8359e-4), (-130.5, 2.8300e-4), (90.0, 2.854e-4)],
            Some("turned -140.00 to -130.50 deg"),
        ),
        // Within 2 deg only, or as good but 1% worse: pinned.
        (&[(-133.5, 2.8257e-4), (-136.9, 2.82e-4)], None),
        (&[(45.0, 2.8544e-4), (0.0, 3.0e-4)], None),
        // As good 11 mm away (the position differs): pinned at the chosen position.
        (&[(45.0, -1.0)], None),
    ];
    for (others, named) in rows {
        let moved = |mut e: Evaluation| {
            e.base_from_part.translation.vector.x += 0.011;
            e.peak = 2.8257e-4;
            e
        };
        let others: Vec<Evaluation> = (others.iter())
            .map(|&(y, p)| if p < 0.0 { moved(at(y, p)) } else { at(y, p) })
            .collect();
        let w = warning(&placed, &others, |e| e.peak, "largest");
        match named {
            Some(text) => {
                let m = w.expect("a warning").message;
                assert!(
                    m.contains(text) && m.contains("0.2826 mm at -135.00 deg"),
                    "{m}"
                );
            }
            None => assert!(w.is_none(), "{others:?}: {w:?}"),
        }
    }
    // Across the half turn of yaw: -179 and 178 deg are 3 deg apart, one range.
    let near = warning(&at(-179.0, 1e-4), &[at(178.0, 1e-4)], |e| e.peak, "largest");
    assert!(near.is_some_and(|w| w.message.contains("turned 178.00 to -179.00 deg")));
    // The probes: every 15 deg of turn within the region's rotation (from the own), the chosen
    // one left out: +-40 deg around a turn of 10 deg from the own gives 25, 40, -35, -20 and -5.
    let own = UnitQuaternion::from_euler_angles(0.0, 0.0, 0.3);
    let chosen = Isometry3::from_parts(
        Translation3::new(1.0, 0.0, 0.4),
        UnitQuaternion::from_euler_angles(0.0, 0.0, 10f64.to_radians()) * own,
    );
    let turn_of = |p: &Isometry3<f64>| (p.rotation * own.inverse()).euler_angles().2;
    let turns: Vec<f64> = probes(&chosen, turn_of, [-40f64.to_radians(), 40f64.to_radians()])
        .iter()
        .map(|p| (turn_of(p).to_degrees() * 1e6).round() / 1e6)
        .collect();
    assert_eq!(turns, [25.0, 40.0, -35.0, -20.0, -5.0]);
}
