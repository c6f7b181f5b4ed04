//! G-code drilling canned cycles (G81, G82, G83) read as the moves they make
//! (`crate::gcode::cycles`): each cycle's points, the drill in the air or in the hole drilled, a
//! peck cycle's bottom.

use crate::gcode::{self, Motion};
use nalgebra::Vector3;

const HEADER: &str = "(stiffid: tool_rpy_deg = 180 0 0)\n";

/// The points of `text` as (line, position mm, rapid).
fn moves(text: &str) -> Vec<(u64, [f64; 3], bool)> {
    gcode::parse(text, 1e-5)
        .unwrap()
        .points
        .iter()
        .map(|p| {
            let mm = p.position * 1e3;
            (
                p.line,
                [mm.x, mm.y, mm.z].map(|v| (v * 1e9).round() / 1e9),
                p.motion == Motion::Rapid,
            )
        })
        .collect()
}

#[test]
fn canned_cycles_make_the_moves_of_their_definition() {
    // G81 with G98: over the hole at the starting level, down to R, feed to Z (through the
    // part's surface, Z = 0, where the drill meets material: stated twice, reached unloaded and
    // then under the thrust; the bottom stated twice, under the thrust and without it), back up to the starting level (above R); the next block drills
    // the next hole with the same Z and R.
    let g81 = format!(
        "{HEADER}G21 G90 G17\nG0 X0 Y0 Z10\nG98 G81 X10 Y20 Z-5 R2 F120\nX30\nG80\nG0 Z20\n"
    );
    let r = true;
    assert_eq!(
        moves(&g81),
        vec![
            (3, [0.0, 0.0, 10.0], r),
            (4, [10.0, 20.0, 10.0], r),
            (4, [10.0, 20.0, 2.0], r),
            (4, [10.0, 20.0, 0.0], !r),
            (4, [10.0, 20.0, 0.0], !r),
            (4, [10.0, 20.0, -5.0], !r),
            (4, [10.0, 20.0, -5.0], r),
            (4, [10.0, 20.0, 10.0], r),
            (5, [30.0, 20.0, 10.0], r),
            (5, [30.0, 20.0, 2.0], r),
            (5, [30.0, 20.0, 0.0], !r),
            (5, [30.0, 20.0, 0.0], !r),
            (5, [30.0, 20.0, -5.0], !r),
            (5, [30.0, 20.0, -5.0], r),
            (5, [30.0, 20.0, 10.0], r),
            (7, [30.0, 20.0, 20.0], r),
        ]
    );
    let g = gcode::parse(&g81, 1e-5).unwrap();
    assert_eq!(g.cycles.len(), 2);
    assert_eq!(g.cycles[1].code, 81);
    assert!((g.cycles[1].bottom - Vector3::new(30e-3, 20e-3, -5e-3)).norm() < 1e-15);
    assert_eq!((g.cycles[1].retract, g.cycles[1].clearance), (2e-3, 10e-3));
    assert_eq!(g.points[4].cycle, Some(0));
    assert_eq!(g.points[0].cycle, None);
    // The feed in the air: from R to the surface, each hole's first arrival there.
    let air: Vec<usize> = (g.drilled_in_air().iter().enumerate())
        .filter(|(_, a)| **a)
        .map(|(i, _)| i)
        .collect();
    assert_eq!(air, [3, 10]);
    // G83 with G99 in inches: pecks of Q0.1 in from R0.05 in to Z-0.25 in, out to R after each,
    // back to 0.010 in (0.254 mm) above the depth reached, feed through the depth reached (where
    // the drill meets material again), retract to R.
    let g83 = format!("{HEADER}G20 G90 G17\nG0 X0 Y0 Z1\nG99 G83 X1 Y0 Z-0.25 R0.05 Q0.1 F4\n");
    let inch = |v: f64| v * 25.4;
    let expected: Vec<(u64, [f64; 3], bool)> = [
        (3, [0.0, 0.0, 1.0], r),
        (4, [1.0, 0.0, 1.0], r),
        (4, [1.0, 0.0, 0.05], r),
        (4, [1.0, 0.0, 0.0], !r),
        (4, [1.0, 0.0, 0.0], !r),
        (4, [1.0, 0.0, -0.05], !r),
        (4, [1.0, 0.0, -0.05], r),
        (4, [1.0, 0.0, 0.05], r),
        (4, [1.0, 0.0, -0.04], r),
        (4, [1.0, 0.0, -0.05], !r),
        (4, [1.0, 0.0, -0.05], !r),
        (4, [1.0, 0.0, -0.15], !r),
        (4, [1.0, 0.0, -0.15], r),
        (4, [1.0, 0.0, 0.05], r),
        (4, [1.0, 0.0, -0.14], r),
        (4, [1.0, 0.0, -0.15], !r),
        (4, [1.0, 0.0, -0.15], !r),
        (4, [1.0, 0.0, -0.25], !r),
        (4, [1.0, 0.0, -0.25], r),
        (4, [1.0, 0.0, 0.05], r),
    ]
    .into_iter()
    .map(|(l, p, m)| (l, p.map(|v| (inch(v) * 1e9).round() / 1e9), m))
    .collect();
    assert_eq!(moves(&g83), expected);
    let g = gcode::parse(&g83, 1e-5).unwrap();
    assert!((g.cycles[0].peck.unwrap() - 0.1 * 25.4e-3).abs() < 1e-15);
    // In the air or the hole drilled: the feed to the surface and each peck's re-entry to the
    // depth reached.
    let air: Vec<usize> = (g.drilled_in_air().iter().enumerate())
        .filter(|(_, a)| **a)
        .map(|(i, _)| i)
        .collect();
    assert_eq!(air, [3, 9, 15]);
    // The feed of the cycle: F4 inch/min.
    assert!((g.points[3].feed.unwrap() - 4.0 * 25.4e-3 / 60.0).abs() < 1e-15);
}

#[test]
fn a_peck_cycle_ends_at_its_bottom_whatever_the_pecks_sum_to_in_floating_point() {
    // Six pecks of 0.75 mm from R3 to Z-1.5 (LinuxCNC's: each out to R and back to 0.254 mm
    // above the depth reached; below the surface, Z0, the depth reached stated twice where the
    // drill meets material again), then out to the starting level: no seventh peck at the
    // bottom.
    let text =
        format!("{HEADER}G21 G90 G17\nG0 X0 Y0 Z10\nG98 G83 X0 Y0 Z-1.5 R3 Q0.75 F200\nG80\n");
    let (r, f) = (true, false);
    let mut want = vec![(3, [0.0, 0.0, 10.0], r), (4, [0.0, 0.0, 3.0], r)];
    for (k, depth) in [2.25, 1.5, 0.75, 0.0, -0.75, -1.5].into_iter().enumerate() {
        if k > 0 {
            let reached: f64 = 3.0 - 0.75 * k as f64;
            want.push((4, [0.0, 0.0, 3.0], r));
            want.push((4, [0.0, 0.0, reached + 0.254], r));
            if reached <= 0.0 && reached > depth {
                want.extend([(4, [0.0, 0.0, reached], f); 2]);
            }
        }
        want.push((4, [0.0, 0.0, depth], f));
        // The thrust gone where the feed stops: the exit starts from there.
        want.push((4, [0.0, 0.0, depth], r));
    }
    want.push((4, [0.0, 0.0, 10.0], r));
    let got = moves(&text);
    assert_eq!(got, want);
    let g = gcode::parse(&text, 1e-5).unwrap();
    assert_eq!(g.points[g.points.len() - 2].position.z, -1.5e-3);
}

#[test]
fn repeats_drill_again_each_shifted_by_the_increments_under_g91() {
    // G91: R from the level the cycle started at (10 - 8 = 2), Z from R (2 - 7 = -5), each of
    // the three holes X5 Y1 further on (LinuxCNC's `interp_cycles.cc`); FANUC's K the same;
    // L2 in G90 drills one place twice; G82's dwell written after each bottom.
    let fanuc = gcode::Machine {
        dialect: Some(gcode::GcodeDialect::Fanuc),
        ..Default::default()
    };
    let bottoms = |text: &str, m: &gcode::Machine| {
        let g = gcode::parse_on(text, 1e-5, m).unwrap();
        let b: Vec<[f64; 4]> = (g.cycles.iter())
            .map(|c| {
                let p = c.bottom * 1e3;
                [p.x, p.y, p.z, c.clearance * 1e3].map(|v| (v * 1e9).round() / 1e9)
            })
            .collect();
        (b, g)
    };
    let holes = [
        [5.0, 1.0, -5.0, 10.0],
        [10.0, 2.0, -5.0, 10.0],
        [15.0, 3.0, -5.0, 10.0],
    ];
    for (k, words) in ["L3", "K3"].into_iter().enumerate() {
        let text = format!(
            "{HEADER}G21 G90 G17\nG0 X0 Y0 Z10\nG91 G98 G81 X5 Y1 Z-7 R-8 {words} F100\nG80\n"
        );
        let m = if k == 0 {
            Default::default()
        } else {
            fanuc.clone()
        };
        let (b, g) = bottoms(&text, &m);
        assert_eq!(b, holes, "{words}");
        assert_eq!(g.points.iter().filter(|p| p.cycle == Some(2)).count(), 7);
        // Written as increments in the block's G91, the L dropped.
        let written = g
            .write(&g.points.iter().map(|p| p.position).collect::<Vec<_>>())
            .unwrap();
        assert!(
            written.contains("G91 F100\nG0 X5.000000 Y1.000000 Z0.000000\n"),
            "{written}"
        );
    }
    let text = format!("{HEADER}G21 G90 G17\nG0 X0 Y0 Z10\nG82 X4 Y4 Z-2 R1 P0.5 L2 F100\nG80\n");
    let (b, g) = bottoms(&text, &Default::default());
    assert_eq!(b, [[4.0, 4.0, -2.0, 10.0]; 2]);
    let written = g
        .write(&g.points.iter().map(|p| p.position).collect::<Vec<_>>())
        .unwrap();
    assert_eq!(written.matches("G4 P0.5").count(), 2, "{written}");
    // K on another controller than FANUC, L outside a cycle: refused (L0 and L2.5: gcode_cycles).
    for (bad, why) in [
        ("G81 X1 Y1 Z-2 R1 K2 F100", "K"),
        ("G1 X1 L2 F100", "outside a canned cycle"),
    ] {
        let text = format!("{HEADER}G21 G90 G17\nG0 X0 Y0 Z10\n{bad}\n");
        let e = gcode::parse(&text, 1e-5).unwrap_err().to_string();
        assert!(e.contains("line 4") && e.contains(why), "{bad}: {e}");
    }
}
