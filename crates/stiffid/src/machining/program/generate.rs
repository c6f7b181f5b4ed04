//! New robot programs from joint targets: what a G-code path becomes for a robot controller
//! ([`generate`]), each target moved to at the path's own speed ([`Move`], from the G-code's
//! `F` words: [`moves`]).
//!
//! Every target is a joint target (module docs of [`super`]: unambiguous, no configuration
//! flags). The first target and rapid moves (`G0`) are joint motions at a rapid speed the
//! program states once in its header, to check for the cell; cutting moves go at the path's feed
//! where the dialect can say so with a joint target:
//! - FANUC LS (`.ls`): `/PROG NAME`, `/MN` with `J P[i] 20% CNT100 ;` for rapid moves and
//!   `L P[i] <feed>mm/sec CNT100 ;` for cutting moves (the controller turns a position in joint
//!   representation into the tool's Cartesian pose and moves there in a straight line at that
//!   speed; the feed rounded to whole mm/s, at least 1), `/POS` with each position in joint
//!   representation, `/END`;
//! - ABB RAPID (`.mod`): `MODULE NAME`, `PROC main()`, `MoveAbsJ [[..],[9E9,..]], SPEED, z1,
//!   tool0;` per target: a `MoveL` needs a `robtarget` with its `confdata`, so every move is
//!   axis-interpolated, its `speeddata` `[v_tcp, 500, 5000, 1000]` with `v_tcp` the path's feed
//!   in mm/s for cutting moves (the speed the controller gives the TCP of `tool0`, the flange,
//!   which moves as the tool while the tool's orientation stays fixed; approximate on an
//!   axis-interpolated move) and the constant `vrapid` (200 mm/s) for rapid moves;
//! - KUKA KRL (`.src`): `DEF NAME( )`, `PTP {A1 .., ..., A6 ..} C_PTP` per target, `END`: a
//!   `PTP` speed is a percentage of each axis's top speed (`$VEL_AXIS`), which no feed in mm/s
//!   fixes, so the program moves at the controller's `$VEL_AXIS` and `$ACC_AXIS` (set them for
//!   the cell before running) and names each target's speed in a comment (`; feed 30 mm/s`,
//!   `; rapid`) for a post-processor or the user to act on.
//!
//! Between two targets under a joint motion the controller interpolates the axis angles, so the
//! tool leaves the straight line between them by the joint interpolation's deviation; dense
//! targets (G-code arcs split to their chord tolerance, straight moves written in short steps)
//! keep it small. Each written program reads back ([`super::parse`]) to the same axis angles
//! within `10^-DECIMALS` deg.

use super::{Dialect, DECIMALS};
use crate::machining::gcode::{Motion, Point};
use crate::{Error, Result};
use std::fmt::Write;

/// How the robot moves to a target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Move {
    /// A joint motion at the program's rapid speed: the first target and rapid moves (`G0`).
    Rapid,
    /// A cutting move at the path's feed, m/s.
    Feed(f64),
}

/// The rapid speed of RAPID's `vrapid`, mm/s.
pub const RAPID_SPEED_MM_S: f64 = 200.0;
/// The joint speed of LS's rapid moves, percent of the axes' top speed.
pub const RAPID_PERCENT: u32 = 20;

/// How the robot moves to each point of a G-code path: the first point and rapid moves
/// [`Move::Rapid`], cutting moves at the feed in force.
///
/// # Errors
/// [`Error::Program`] naming the line of a cutting move with no feed rate (`F`) in force.
pub fn moves(points: &[Point]) -> Result<Vec<Move>> {
    points
        .iter()
        .enumerate()
        .map(|(i, p)| match (i, p.motion, p.feed) {
            (0, _, _) | (_, Motion::Rapid, _) => Ok(Move::Rapid),
            (_, Motion::Feed, Some(f)) => Ok(Move::Feed(f)),
            (_, Motion::Feed, None) => Err(Error::Program {
                line: p.line,
                message: "a cutting move without a feed rate (F) in force: a robot program written from the path moves at its feed".into(),
            }),
        })
        .collect()
}

/// A program named `name` (letters, digits and `_`, starting with a letter; at most 24 characters)
/// in `dialect` that visits `q_deg` (axis angles q1..q6, deg) in order, moving to each as `moves`
/// says (one per target; module docs).
///
/// # Errors
/// [`Error::InvalidField`] for a name the controllers do not accept (`name`); no target, more
/// than [`super::MAX_TARGETS`] or a value that is not finite (`q_deg`); a count of moves other
/// than the targets' or a feed that is not positive and finite (`moves`).
pub fn generate(
    dialect: Dialect,
    name: &str,
    q_deg: &[[f64; 6]],
    moves: &[Move],
) -> Result<String> {
    let valid = name.len() <= 24
        && name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !valid {
        return Err(Error::InvalidField {
            field: "name".into(),
            message: format!("{name:?}: expected a program name of letters, digits and _, starting with a letter, at most 24 characters"),
        });
    }
    if q_deg.is_empty()
        || q_deg.len() > super::MAX_TARGETS
        || q_deg.iter().flatten().any(|v| !v.is_finite())
    {
        return Err(Error::InvalidField {
            field: "q_deg".into(),
            message: format!(
                "expected 1 to {} targets of 6 finite axis angles",
                super::MAX_TARGETS
            ),
        });
    }
    let bad_feed = moves
        .iter()
        .any(|m| matches!(m, Move::Feed(f) if !(f.is_finite() && *f > 0.0)));
    if moves.len() != q_deg.len() || bad_feed {
        return Err(Error::InvalidField {
            field: "moves".into(),
            message: format!(
                "expected one move per target ({}), each feed above 0 and finite",
                q_deg.len()
            ),
        });
    }
    Ok(match dialect {
        Dialect::Krl => krl(name, q_deg, moves),
        Dialect::Rapid => rapid(name, q_deg, moves),
        Dialect::FanucLs => ls(name, q_deg, moves),
    })
}

/// A feed in m/s as mm/s with at most 3 decimals (trailing zeros dropped).
fn mm_s(feed: f64) -> String {
    let s = format!("{:.3}", feed * 1e3);
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `x` with [`DECIMALS`] decimals, a negative zero without its sign.
fn v(x: f64) -> String {
    let s = format!("{x:.DECIMALS$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

fn krl(name: &str, q: &[[f64; 6]], moves: &[Move]) -> String {
    let mut s = format!(
        "DEF {name}( )\n; written by stiffid: compensated joint targets\n\
         ; PTP to joint targets moves at the controller's $VEL_AXIS and $ACC_AXIS: set them for\n\
         ; the cell. The path's speed to each target is in its comment (feed in mm/s, or rapid).\n"
    );
    for (t, m) in q.iter().zip(moves) {
        let axes: Vec<String> = (0..6).map(|k| format!("A{} {}", k + 1, v(t[k]))).collect();
        let speed = match m {
            Move::Rapid => "rapid".to_string(),
            Move::Feed(f) => format!("feed {} mm/s", mm_s(*f)),
        };
        let _ = writeln!(s, "PTP {{{}}} C_PTP ; {speed}", axes.join(", "));
    }
    s + "END\n"
}

fn rapid(name: &str, q: &[[f64; 6]], moves: &[Move]) -> String {
    let mut s = format!(
        "MODULE {name}\n  ! written by stiffid: compensated joint targets; cutting moves at the path's\n  \
         ! feed (v_tcp, mm/s), rapid moves at vrapid: check it for the cell\n  \
         CONST speeddata vrapid := [{},500,5000,1000];\n  PROC main()\n",
        mm_s(RAPID_SPEED_MM_S * 1e-3)
    );
    for (t, m) in q.iter().zip(moves) {
        let axes: Vec<String> = t.iter().map(|x| v(*x)).collect();
        let speed = match m {
            Move::Rapid => "vrapid".to_string(),
            Move::Feed(f) => format!("[{},500,5000,1000]", mm_s(*f)),
        };
        let _ = writeln!(
            s,
            "    MoveAbsJ [[{}],[9E9,9E9,9E9,9E9,9E9,9E9]], {speed}, z1, tool0;",
            axes.join(",")
        );
    }
    s + "  ENDPROC\nENDMODULE\n"
}

fn ls(name: &str, q: &[[f64; 6]], moves: &[Move]) -> String {
    let mut s = format!(
        "/PROG  {name}\n/ATTR\nCOMMENT\t\t= \"stiffid compensated\";\nDEFAULT_GROUP\t= 1,*,*,*,*;\n/MN\n\
         {:>4}:  ! rapid moves J at {RAPID_PERCENT}%: check for the cell ;\n",
        1
    );
    for (i, m) in (1..=q.len()).zip(moves) {
        let _ = match m {
            Move::Rapid => writeln!(s, "{:>4}:J P[{i}] {RAPID_PERCENT}% CNT100 ;", i + 1),
            Move::Feed(f) => writeln!(
                s,
                "{:>4}:L P[{i}] {}mm/sec CNT100 ;",
                i + 1,
                (f * 1e3).round().max(1.0)
            ),
        };
    }
    s += "/POS\n";
    for (i, t) in q.iter().enumerate() {
        let _ = write!(
            s,
            "P[{}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {} deg,\tJ2= {} deg,\tJ3= {} deg,\n\tJ4= {} deg,\tJ5= {} deg,\tJ6= {} deg\n}};\n",
            i + 1,
            v(t[0]),
            v(t[1]),
            v(t[2]),
            v(t[3]),
            v(t[4]),
            v(t[5])
        );
    }
    s + "/END\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_dialect_reads_back_to_its_targets_and_states_each_speed() {
        let q = [
            [0.0, -90.5, 12.25, 180.0, -45.123456789, 1e-9],
            [10.0, 20.0, -30.0, 40.0, 50.0, -360.0],
        ];
        let moves = [Move::Rapid, Move::Feed(0.03)];
        for d in [Dialect::Krl, Dialect::Rapid, Dialect::FanucLs] {
            let text = generate(d, "POCKET", &q, &moves).unwrap();
            let read = super::super::parse(&text, d).unwrap();
            assert_eq!(read.targets.len(), 2, "{d:?}");
            for (t, e) in read.targets.iter().zip(&q) {
                for (a, b) in t.q_deg.iter().zip(e) {
                    assert!((a - b).abs() <= 1e-9, "{d:?}: {:?}", t.q_deg);
                }
            }
            let second = text.lines().nth(read.targets[1].line as usize - 1).unwrap();
            let expected = match d {
                Dialect::Krl => "C_PTP ; feed 30 mm/s",
                Dialect::Rapid => "], [30,500,5000,1000], z1, tool0;",
                Dialect::FanucLs => "",
            };
            assert!(second.ends_with(expected), "{d:?}: {second}");
        }
        let ls = generate(Dialect::FanucLs, "POCKET", &q, &moves).unwrap();
        assert!(
            ls.contains("   2:J P[1] 20% CNT100 ;\n   3:L P[2] 30mm/sec CNT100 ;\n"),
            "{ls}"
        );
        let rapid = generate(Dialect::Rapid, "POCKET", &q, &moves).unwrap();
        assert!(
            rapid.contains("CONST speeddata vrapid := [200,500,5000,1000];"),
            "{rapid}"
        );
        assert!(rapid.contains("]], vrapid, z1, tool0;"), "{rapid}");
        assert!(generate(Dialect::Krl, "1x", &q, &moves).is_err());
        assert!(generate(Dialect::Krl, "P", &[], &[]).is_err());
        assert!(generate(Dialect::Krl, "P", &[[f64::NAN; 6]], &[Move::Rapid]).is_err());
        assert!(generate(Dialect::Krl, "P", &q, &[Move::Rapid]).is_err());
        assert!(generate(Dialect::Krl, "P", &q, &[Move::Rapid, Move::Feed(0.0)]).is_err());
    }
}
