//! One block applied to the state: modes, motions, canned cycles, the points it makes.

use super::arc::arc;
use super::words::{check_words, Word};
use super::{at, cycles, external_values, may_move, Block, GCode, Motion, Point, State};
use nalgebra::UnitQuaternion;
use std::ops::Range;
use stiffid_core::Result;

pub(super) const SUBSET: &str = "G0-G4, G17-G21, G40, G49, G80-G83, G90, G91, G94, G98, G99";

/// `s.motion` after `G80` ended a canned cycle: no motion in force until `G0`-`G3`.
pub(super) const NO_MOTION: u8 = 80;

pub(super) fn block(
    line: u64,
    span: Range<usize>,
    words: &[Word],
    s: &mut State,
    out: &mut GCode,
    tolerance: f64,
) -> Result<()> {
    let mut target = [None; 3];
    let mut centre = [None; 3];
    let mut radius = None;
    let mut motion_given = None;
    let mut drop = Vec::new();
    let mut abc_given = false;
    let mut external_given = false;
    let mut external_words = Vec::new();
    check_words(line, words, s)?;
    let mut feed_given = None;
    let mut cycle_words = cycles::Words::default();
    let inch_before = s.inch;
    for w in words {
        let v = w.value;
        match w.letter {
            'G' => {
                let g = v.round();
                if (v - g).abs() > 1e-9 || !(0.0..100.0).contains(&g) {
                    return Err(at(line, format!("G{v}: not in the supported subset ({SUBSET})")));
                }
                match g as u8 {
                    g @ 0..=3 => motion_given = Some((g, w.span.clone())),
                    g @ 81..=83 => {
                        motion_given = Some((g, w.span.clone()));
                        drop.push(w.span.clone());
                    }
                    g @ (98 | 99) => {
                        s.retract_to_r = g == 99;
                        drop.push(w.span.clone());
                    }
                    80 if s.motion >= 81 => s.motion = NO_MOTION,
                    g @ (41 | 42) => return Err(at(line, format!("G{g}: cutter radius compensation belongs to the CAM post: post the path of the tool centre (compensation in the computer, G40)"))),
                    g @ 17..=19 => s.plane = g,
                    20 => s.inch = true,
                    21 => s.inch = false,
                    90 => s.incremental = false,
                    91 => s.incremental = true,
                    4 | 40 | 49 | 80 | 94 => {}
                    _ => return Err(at(line, format!("G{g}: not in the supported subset ({SUBSET})"))),
                }
            }
            'X' | 'Y' | 'Z' => {
                target[(w.letter as u8 - b'X') as usize] = Some(v);
                drop.push(w.span.clone());
            }
            'I' | 'J' | 'K' => {
                centre[(w.letter as u8 - b'I') as usize] = Some(v);
                drop.push(w.span.clone());
            }
            'R' => {
                radius = Some(v);
                drop.push(w.span.clone());
            }
            l @ ('U' | 'V' | 'W' | 'A' | 'B' | 'C') if s.external.0.contains(&l) => {
                let k = s.external.0.iter().position(|e| *e == l).unwrap_or(0);
                let v = match (l, s.inch) {
                    ('U' | 'V' | 'W', true) => v * 25.4,
                    _ => v,
                };
                s.e[k] = match (s.incremental, s.e[k]) {
                    (false, _) => Some(v),
                    (true, Some(before)) => Some(before + v),
                    (true, None) => return Err(at(line, format!("{l}: an increment (G91) before the axis has a value: give it in G90 first"))),
                };
                external_given = true;
                external_words.push(w.span.clone());
            }
            'A' | 'B' | 'C' => {
                if !s.rotary {
                    return Err(at(line, format!("{}: rotary words need the header comment (stiffid: rotary = abc)", w.letter)));
                }
                if !(-360.0..=360.0).contains(&v) {
                    return Err(at(line, format!("{}{}: expected a tool angle from -360 to 360 deg", w.letter, stiffid_core::common::words::number(v))));
                }
                s.abc[(w.letter as u8 - b'A') as usize] = v;
                abc_given = true;
            }
            'T' => {
                if v < 0.0 || v.fract() != 0.0 || v > 1e6 {
                    return Err(at(line, format!("T{v}: expected a tool number 0..1000000")));
                }
                s.tool_number = Some(v as u32);
            }
            'F' => feed_given = Some(v),
            'Q' => {
                cycle_words.peck = Some(v);
                drop.push(w.span.clone());
            }
            'P' => cycle_words.dwell = Some((v, w.span.clone())),
            'S' | 'M' | 'N' | 'O' | 'H' | 'D' => {}
            other => return Err(at(line, format!("'{other}': not a word of the supported subset (G M T F S N O P Q X Y Z I J K R, A B C with rotary = abc, U V W A B C mapped by external = LETTERS)"))),
        }
    }
    if let Some((g, _)) = &motion_given {
        if *g >= 81 && s.motion < 81 {
            s.cycle = cycles::Modal::starting_at(s.position.z);
        }
        s.motion = *g;
    }
    if let Some(f) = feed_given {
        s.feed = Some(f * if s.inch { 25.4e-3 } else { 1e-3 } / 60.0);
        s.feed_line = line;
    } else if s.inch != inch_before && s.feed.is_some() {
        return Err(at(line, format!("G{}: the units change while the feed rate F of line {} is in force, and controllers differ on whether it follows them: give F again in this block", if s.inch { 20 } else { 21 }, s.feed_line)));
    }
    if s.motion >= 81 && s.motion != NO_MOTION {
        cycle_words.xyz = target;
        cycle_words.retract = radius;
        cycle_words.given = motion_given.is_some();
        let centre_given = centre.iter().any(Option::is_some);
        return cycles::block(
            line,
            span,
            cycle_words,
            centre_given || abc_given || external_given,
            drop,
            s,
            out,
        );
    }
    if cycle_words.peck.is_some() {
        return Err(at(line, "Q: a peck depth outside a G83 cycle".into()));
    }
    let arc_only = s.motion >= 2 && (centre.iter().any(Option::is_some) || radius.is_some());
    let moves = target.iter().any(Option::is_some) || abc_given || external_given || arc_only;
    if external_given && s.motion >= 2 {
        return Err(at(line, "an external axis moving along an arc: the cell's axes and the arc would not stay together; split the arc into G1 moves".into()));
    }
    if !moves {
        if centre.iter().any(Option::is_some) || radius.is_some() {
            return Err(at(line, "I, J, K or R without an end point".into()));
        }
        return Ok(());
    }
    if s.motion == NO_MOTION {
        return Err(at(line, "a motion after G80 without G0, G1, G2 or G3: controllers differ on the motion in force after a canned cycle; give it".into()));
    }
    let tool = may_move(line, s)?;
    let external = external_values(line, s)?;
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    let mut end = s.position;
    for k in 0..3 {
        if let Some(v) = target[k] {
            end[k] = if s.incremental {
                end[k] + v * scale
            } else {
                v * scale
            };
        }
    }
    if !end.iter().all(|v| v.abs() <= 100.0) {
        return Err(at(line, "position beyond 100 m".into()));
    }
    let [a, b, c] = s.abc.map(f64::to_radians);
    let orientation = UnitQuaternion::from_euler_angles(a, b, c) * tool;
    let first = out.points.len();
    let positions = match s.motion {
        2 | 3 => arc(
            line,
            s,
            end,
            centre.map(|c| c.map(|v| v * scale)),
            radius.map(|r| r * scale),
            tolerance,
        )?,
        _ => vec![end],
    };
    for p in positions {
        out.points.push(Point {
            line,
            position: p,
            orientation,
            motion: if s.motion == 0 {
                Motion::Rapid
            } else {
                Motion::Feed
            },
            tool_number: s.tool_number,
            operation: s.operation.clone(),
            feed: s.feed,
            cycle: None,
            external: external.clone(),
        });
    }
    s.position = end;
    let arc_word = motion_given.filter(|(g, _)| *g >= 2).map(|(_, span)| span);
    out.blocks.push(Block {
        line: span,
        points: first..out.points.len(),
        drop,
        external_words,
        arc_word,
        inch: s.inch,
        incremental: s.incremental,
        cycle: None,
    });
    Ok(())
}
