//! The G-code's comments on lines of their own (the CAM post's operation, tool and header
//! comments) written in each robot language at their place between the motions, sanitised to
//! what the language's comment takes.

use super::process::{corpus, motion_lines, plan, router, targets, PULSES};
use stiffid::internal::machining::gcode::{self, Comment};
use stiffid_core::setup::Pulses;
use stiffid_machining::program::generate::*;
use stiffid_machining::program::Dialect;

/// The comments on lines of their own of a G-code text, read here from the text alone: a line
/// of `( .. )` groups and blanks only, or a `;` comment alone; stiffid's directives and empty
/// comments left out.
fn independent(text: &str) -> Vec<(u64, String)> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let mut rest = line.trim();
        let mut found = Vec::new();
        let mut words = false;
        while !rest.is_empty() {
            if let Some(r) = rest.strip_prefix(';') {
                found.push(r.trim().to_string());
                break;
            }
            let Some(r) = rest.strip_prefix('(') else {
                words = true;
                break;
            };
            let end = r.find(')').unwrap();
            found.push(r[..end].trim().to_string());
            rest = r[end + 1..].trim_start();
        }
        if !words {
            let kept = (found.into_iter()).filter(|c| !c.is_empty() && !c.starts_with("stiffid:"));
            out.extend(kept.map(|c| (i as u64 + 1, c)));
        }
    }
    out
}

#[test]
fn the_fusion_files_comments_on_lines_of_their_own_are_read_in_order() {
    for (name, workpiece, process, ..) in &crate::gcode_corpus::READ[..5] {
        let text = corpus(name);
        let m = crate::gcode_corpus::machine(workpiece, process);
        let g = gcode::parse_on(&text, 1e-5, &m).unwrap();
        let read: Vec<(u64, String)> = g
            .comments
            .iter()
            .map(|c| (c.line, c.text.clone()))
            .collect();
        assert_eq!(read, independent(&text), "{name}");
    }
    // By eye: the router's header, its tool and its operation, before its first point (line 19).
    let g = router();
    let read: Vec<(u64, &str)> = g
        .comments
        .iter()
        .map(|c| (c.line, c.text.as_str()))
        .collect();
    assert_eq!(
        read,
        [
            (1, "1001"),
            (2, "MACHINE"),
            (3, "VENDOR AUTODESK"),
            (4, "MODEL GENERIC 3-AXIS ROUTER"),
            (5, "DESCRIPTION THIS MACHINE HAS XYZ AXIS ON THE HEAD"),
            (6, "T1 D=152.4 CR=0. - ZMIN=-12.7 - FACE MILL"),
            (12, "FACE1"),
        ]
    );
    let lines: Vec<Option<u64>> = g.points.iter().map(|p| Some(p.line)).collect();
    assert_eq!(place_comments(&g.comments, &lines), [0; 7]);
    // Where the path has a home posture before it: after the home move.
    let homed: Vec<Option<u64>> = [None].into_iter().chain(lines).collect();
    assert_eq!(place_comments(&g.comments, &homed), [1; 7]);
}

/// A language's comment line of `text` as its pendant keeps it: KRL and RAPID whole, an LS
/// remark's text at most 32 characters, an INFORM comment line at most 32 with its `'` (the
/// manuals' remark and comment lengths).
fn comment_line(d: Dialect, text: &str) -> String {
    let cut = |n: usize| text[..text.len().min(n)].trim_end().to_string();
    match d {
        Dialect::Krl => format!("; {text}"),
        Dialect::Rapid => format!("    ! {text}"),
        Dialect::FanucLs => format!("! {} ;", cut(32)),
        _ => format!("'{}", cut(31)),
    }
}

#[test]
fn the_fusion_routers_comments_are_written_in_every_language_in_order_before_its_words() {
    let g = router();
    let m = moves(&g.points, 2.0).unwrap();
    let t = targets(g.points.len());
    let lines: Vec<Option<u64>> = g.points.iter().map(|p| Some(p.line)).collect();
    let (before, comments_before) = (
        place(&g.process, &lines),
        place_comments(&g.comments, &lines),
    );
    let process = Process {
        words: &g.process,
        before: &before,
        io: None,
        comments: &g.comments,
        comments_before: &comments_before,
    };
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    for d in [
        Dialect::Krl,
        Dialect::Rapid,
        Dialect::FanucLs,
        Dialect::Inform,
    ] {
        let written = generate_with(&plan(d, &t, &m, &pulses, Targets::Joint), &process).unwrap();
        let text = &written.files[0].text;
        // LS's numbered lines carry a number: the statement after it.
        let body = |l: &str| match d {
            Dialect::FanucLs => l
                .split_once(':')
                .map_or(l, |(_, b)| b.trim_start())
                .to_string(),
            _ => l.to_string(),
        };
        let all: Vec<String> = text.lines().map(body).collect();
        let at: Vec<usize> = (g.comments.iter())
            .map(|c| {
                let want = comment_line(d, &c.text);
                all.iter()
                    .position(|l| *l == want)
                    .unwrap_or_else(|| panic!("{d:?}: {want} in\n{text}"))
            })
            .collect();
        // In the G-code's order, before the first motion; the operation's name before the tool
        // change it starts (line 13, `T1 M6`, a comment as no event is mapped).
        assert!(at.windows(2).all(|w| w[0] < w[1]), "{d:?}: {at:?}");
        assert!(*at.last().unwrap() < motion_lines(d, text)[0], "{d:?}");
        let tool = all
            .iter()
            .position(|l| l.contains("T1 M6 (line 13)"))
            .unwrap();
        assert!(at[6] < tool, "{d:?}");
        // Every move still there, as many as without the comments.
        let bare = Process {
            comments: &[],
            comments_before: &[],
            ..process
        };
        let plain = generate_with(&plan(d, &t, &m, &pulses, Targets::Joint), &bare).unwrap();
        assert_eq!(
            motion_lines(d, text).len(),
            motion_lines(d, &plain.files[0].text).len()
        );
        assert_eq!(
            text.lines().count(),
            plain.files[0].text.lines().count() + 7,
            "{d:?}"
        );
        if d == Dialect::FanucLs {
            // The corpus tests' independent LS reader: every position, as without them.
            let n = crate::ls_corpus::independent(text).len();
            assert_eq!(n, crate::ls_corpus::independent(&plain.files[0].text).len());
        }
    }
}

#[test]
fn a_comment_is_written_in_the_characters_and_length_its_language_takes() {
    let t = targets(2);
    let m = [Move::Rapid, Move::Feed(0.02)];
    let pulses = Pulses {
        per_deg: PULSES,
        external: Vec::new(),
    };
    let long = "Kontur ä; 50% (Schlichten) mit einem sehr langen Namen";
    let comments = [Comment {
        line: 1,
        text: long.into(),
    }];
    let process = Process {
        comments: &comments,
        comments_before: &[1],
        ..Default::default()
    };
    // Non-ASCII as `?`; LS's `;` (which ends its statement) as a blank; LS's text and INFORM's
    // line at most 32 characters.
    let cases = [
        (
            Dialect::Krl,
            "; Kontur ?; 50% (Schlichten) mit einem sehr langen Namen",
        ),
        (
            Dialect::Rapid,
            "    ! Kontur ?; 50% (Schlichten) mit einem sehr langen Namen",
        ),
        (Dialect::FanucLs, "! Kontur ?  50% (Schlichten) mit e ;"),
        (Dialect::Inform, "'Kontur ?; 50% (Schlichten) mit"),
    ];
    for (d, want) in cases {
        let w = generate_with(&plan(d, &t, &m, &pulses, Targets::Joint), &process).unwrap();
        let text = &w.files[0].text;
        let lines: Vec<&str> = text.lines().collect();
        let found = lines
            .iter()
            .position(|l| l.ends_with(want.trim_start_matches(' ')))
            .unwrap_or_else(|| panic!("{d:?}: {want} in\n{text}"));
        // Between the first move and the second, where it was placed.
        let motions = motion_lines(d, text);
        assert!(motions[0] < found && found < motions[1], "{d:?}: {text}");
        assert!(text.is_ascii(), "{d:?}");
    }
}
