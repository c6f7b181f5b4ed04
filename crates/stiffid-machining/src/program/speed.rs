//! A robot program's programmed speeds: how the controller moves to each target at 100 %
//! override, as the program states it.
//!
//! - A joint motion (KRL `PTP`, `SPTP`; RAPID `MoveJ`, `MoveAbsJ`; LS `J`; INFORM `MOVJ`) moves
//!   the axes at a share of their own largest speeds, which the controller plans: it has no TCP
//!   speed ([`Speed::Joint`]); the arm may change configuration along it.
//! - A linear motion (KRL `LIN`, `SLIN`; RAPID `MoveL`; LS `L`; INFORM `MOVL`) moves the TCP
//!   along a line at a path speed ([`Speed::Path`]) or in a time ([`Speed::Duration`]):
//!   - KRL: `$VEL.CP = v` (m/s) or `BAS(#CP_PARAMS, v)` (the inline forms' `Vel= v m/s`) on a
//!     line before the motion, in force until the next; `WITH $VEL.CP = v` or
//!     `WITH $VEL = SVEL_CP(v, ..)` on the motion, for it alone;
//!   - RAPID: the speed argument, a predefined `speeddata` (`v5` to `v7000`, mm/s), one
//!     declared in the module (`CONST speeddata vcut := [25, 500, 5000, 1000];`, its first
//!     member `v_tcp`, mm/s) or a literal `[25, 500, 5000, 1000]`; the switch `\V:=` (mm/s)
//!     replaces it, `\T:=` (s) gives the time;
//!   - LS: `mm/sec`, `cm/min`, `inch/min`, or the time `sec`, `msec`;
//!   - INFORM: `V=` (mm/s).
//!
//!   Any other form (a variable, a register, an orientation speed `deg/sec` or `VR=`, RAPID
//!   `vmax`, KRL `BAS(#INITMOV)` or an expression, no speed set before the first linear motion)
//!   is [`Speed::Unread`]: stiffid does not evaluate it, and says why.
//!
//! Overrides (KRL `$OV_PRO`, RAPID `VelSet`, the pendant's) and the controller's own slowing
//! down (corners, acceleration) are not read: a move is taken at its programmed speed, the
//! fastest the program lets it go.

use super::{at, number_at, JointProgram};
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// The largest path speed read, mm/s (10 m/s: beyond every industrial arm's).
pub const MAX_PATH_SPEED_MM_S: f64 = 10_000.0;

/// The longest duration of one move read, s.
pub const MAX_DURATION_S: f64 = 3_600.0;

/// How the program moves to a target (module docs).
#[derive(Debug, Clone, PartialEq)]
pub enum Speed {
    /// A joint motion: the axes at a share of their largest speeds, no TCP speed.
    Joint,
    /// A linear motion at this TCP path speed, m/s.
    Path(f64),
    /// A linear motion that takes this time, s (RAPID `\T`, LS `sec`).
    Duration(f64),
    /// A linear motion whose speed the program gives in a form stiffid does not read: why.
    Unread(String),
}

impl JointProgram {
    /// Whether each target is reached by a joint motion ([`Speed::Joint`]), where the arm may
    /// change configuration; one per target.
    pub fn joint_moves(&self) -> Vec<bool> {
        self.targets
            .iter()
            .map(|t| t.speed == Speed::Joint)
            .collect()
    }
}

/// A path speed of `mm_s` (mm/s) stated on `line` by `what`, checked against its limits.
fn path(line: u64, what: &str, mm_s: f64) -> Result<Speed> {
    match mm_s > 0.0 && mm_s <= MAX_PATH_SPEED_MM_S {
        true => Ok(Speed::Path(mm_s * 1e-3)),
        false => Err(at(
            line,
            format!("{what}: a path speed of {mm_s} mm/s; expected one in (0, {MAX_PATH_SPEED_MM_S}] mm/s"),
        )),
    }
}

/// A move's time of `s` (s) stated on `line` by `what`, checked against its limits.
fn duration(line: u64, what: &str, s: f64) -> Result<Speed> {
    match s > 0.0 && s <= MAX_DURATION_S {
        true => Ok(Speed::Duration(s)),
        false => Err(at(
            line,
            format!("{what}: a move of {s} s; expected a time in (0, {MAX_DURATION_S}] s"),
        )),
    }
}

/// The number `text` is, whole (blanks around it aside), or `None` (a name, an expression).
fn literal(text: &str) -> Option<f64> {
    let (v, span) = number_at(text, 0)?;
    text[span.end..].trim().is_empty().then_some(v)
}

/// `text` without blanks, upper case: a KRL statement's words as the controller reads them.
fn compact(text: &str) -> String {
    let kept = text.chars().filter(|c| !c.is_whitespace());
    kept.collect::<String>().to_ascii_uppercase()
}

/// The KRL path speed in force while a program is read line by line (module docs).
pub struct Krl {
    in_force: Speed,
}

impl Default for Krl {
    fn default() -> Self {
        Self::new()
    }
}

impl Krl {
    /// Before any line: no speed set.
    pub fn new() -> Self {
        let why = "no $VEL.CP set before it in the program: its speed is the controller's";
        Krl {
            in_force: Speed::Unread(why.into()),
        }
    }

    /// Reads the line `code` (its comment removed) if it sets the path speed; whether it did.
    ///
    /// # Errors
    /// A literal speed outside (0, 10] m/s, naming the line.
    pub fn set(&mut self, line: u64, code: &str) -> Result<bool> {
        let c = compact(code);
        // The value as written: after the `=` or the `,`, up to a closing `)`.
        let value = |after: char| {
            let v = code.split_once(after).map_or("", |(_, v)| v.trim());
            v.strip_suffix(')').unwrap_or(v).trim()
        };
        let speed = if c.starts_with("$VEL.CP=") {
            krl_value(line, "$VEL.CP", value('='))?
        } else if c.starts_with("BAS(#CP_PARAMS,") {
            krl_value(line, "BAS(#CP_PARAMS)", value(','))?
        } else if c.starts_with("$VEL=") {
            Speed::Unread(format!(
                "line {line} sets $VEL as a whole, which stiffid does not read: set $VEL.CP"
            ))
        } else if c.starts_with("BAS(#INITMOV") || c.starts_with("BAS(#VEL_CP") {
            Speed::Unread(format!("line {line} sets the path speed by {}, to the controller's value: set $VEL.CP after it", short(code.trim())))
        } else {
            return Ok(false);
        };
        self.in_force = speed;
        Ok(true)
    }

    /// The speed of the motion `first` (`PTP`, `LIN`, ..) on the line `code`: its own
    /// `WITH $VEL..`, else the one in force.
    ///
    /// # Errors
    /// A literal speed outside (0, 10] m/s, naming the line.
    pub fn motion(&self, line: u64, first: &str, code: &str) -> Result<Speed> {
        if matches!(first, "PTP" | "SPTP") {
            return Ok(Speed::Joint);
        }
        let c = compact(code);
        let own = c.split_once("WITH").map(|(_, w)| w).and_then(|w| {
            let v = (w.split_once("$VEL.CP=").map(|(_, v)| v))
                .or_else(|| w.split_once("$VEL=SVEL_CP(").map(|(_, v)| v))?;
            Some(v.split([',', ')']).next().unwrap_or(v))
        });
        match own {
            Some(v) => krl_value(line, "WITH $VEL", v),
            None => Ok(self.in_force.clone()),
        }
    }
}

/// A KRL speed `value` (m/s) set on `line` by `what`: a literal, checked, or unread.
fn krl_value(line: u64, what: &str, value: &str) -> Result<Speed> {
    match literal(value) {
        Some(v) => path(line, &format!("{what} = {value} m/s"), v * 1e3),
        None => Ok(Speed::Unread(format!(
            "line {line} sets {what} to '{}', which stiffid does not evaluate",
            short(value)
        ))),
    }
}

/// RAPID's predefined `speeddata` (their `v_tcp`, mm/s, is the number in the name).
const RAPID_PREDEFINED: [u32; 25] = [
    5, 10, 20, 30, 40, 50, 60, 80, 100, 150, 200, 300, 400, 500, 600, 800, 1000, 1500, 2000, 2500,
    3000, 4000, 5000, 6000, 7000,
];

/// A RAPID module's `speeddata` by lower-case name: its `v_tcp` (mm/s) and declaration's line,
/// or why it has none in the file.
pub type RapidSpeeds = HashMap<String, std::result::Result<(f64, u64), String>>;

/// The speed of the RAPID motion `first` (`movel`, `movej`, `moveabsj`) whose speed argument
/// is `argument` (`v100`, `vcut\V:=120`, `v100\T:=2`), with the module's `declared` speeds.
///
/// # Errors
/// A literal speed or time outside its limits, naming the line.
pub fn rapid(
    line: u64,
    first: &str,
    argument: Option<&str>,
    declared: &RapidSpeeds,
) -> Result<Speed> {
    if first != "movel" {
        return Ok(Speed::Joint);
    }
    let Some(argument) = argument else {
        return Ok(Speed::Unread("no speed argument".into()));
    };
    let name = argument.split('\\').next().unwrap_or("").trim();
    let switch = |key: &str| {
        (argument.split('\\').skip(1)).find_map(|s| {
            let (k, v) = s.split_once(":=")?;
            k.trim().eq_ignore_ascii_case(key).then(|| v.trim())
        })
    };
    let unread = |v: &str| {
        Speed::Unread(format!(
            "{}: a variable or expression, which stiffid does not evaluate",
            short(v)
        ))
    };
    if let Some(t) = switch("T") {
        let what = format!("\\T:={t}");
        return literal(t).map_or(Ok(unread(&what)), |s| duration(line, &what, s));
    }
    if let Some(v) = switch("V") {
        let what = format!("\\V:={v}");
        return literal(v).map_or(Ok(unread(&what)), |mm_s| path(line, &what, mm_s));
    }
    if name.starts_with('[') {
        let v_tcp = super::cartesian::literal::parse(name, 0).and_then(|(n, _)| n.numbers(4));
        return match v_tcp {
            Some(v) => path(line, &format!("speeddata {name}"), v[0].0),
            None => Ok(unread(name)),
        };
    }
    let key = name.to_ascii_lowercase();
    if let Some(d) = declared.get(&key) {
        return match d {
            Ok((mm_s, from)) => path(line, &format!("speeddata {name} (line {from})"), *mm_s),
            Err(why) => Ok(Speed::Unread(why.clone())),
        };
    }
    let predefined = (key.strip_prefix('v'))
        .and_then(|n| n.parse::<u32>().ok())
        .filter(|n| RAPID_PREDEFINED.contains(n));
    match (predefined, key.as_str()) {
        (Some(mm_s), _) => path(line, name, f64::from(mm_s)),
        (None, "vmax") => Ok(Speed::Unread(
            "vmax: the robot's largest TCP speed, which the module does not state".into(),
        )),
        _ => Ok(Speed::Unread(format!(
            "{}: not a speeddata declared in this module nor a predefined one (v5 to v7000)",
            short(name)
        ))),
    }
}

/// The speed of the LS motion `letter` (`J`, `L`) whose speed word is `word` (`100mm/sec`).
///
/// # Errors
/// A literal speed or time outside its limits, naming the line.
pub fn ls(line: u64, letter: &str, word: &str) -> Result<Speed> {
    if letter == "J" {
        return Ok(Speed::Joint);
    }
    let Some((v, span)) = number_at(word, 0).filter(|(_, s)| s.start == 0) else {
        let why = match word.to_ascii_uppercase().starts_with("R[") || word.contains('[') {
            true => "the speed is held in a register on the controller",
            false => "a speed stiffid does not read",
        };
        return Ok(Speed::Unread(format!("{}: {why}", short(word))));
    };
    match word[span.end..].to_ascii_lowercase().as_str() {
        "mm/sec" => path(line, word, v),
        "cm/min" => path(line, word, v * 10.0 / 60.0),
        "inch/min" => path(line, word, v * 25.4 / 60.0),
        "sec" => duration(line, word, v),
        "msec" => duration(line, word, v * 1e-3),
        "deg/sec" => Ok(Speed::Unread(format!(
            "{word}: an orientation speed; the TCP's is the controller's"
        ))),
        _ => Ok(Speed::Unread(format!(
            "{}: a speed unit stiffid does not read (mm/sec, cm/min, inch/min, sec, msec)",
            short(word)
        ))),
    }
}

/// The speed of the INFORM motion `word` (`MOVJ`, `MOVL`) with its `tags` (`V=100.0`).
///
/// # Errors
/// A literal speed outside its limits, naming the line.
pub fn inform(line: u64, word: &str, tags: &[&str]) -> Result<Speed> {
    if word.eq_ignore_ascii_case("MOVJ") {
        return Ok(Speed::Joint);
    }
    let tag = |name: &str| {
        (tags.iter()).find_map(|t| {
            t.get(..name.len())
                .filter(|h| h.eq_ignore_ascii_case(name))
                .map(|_| &t[name.len()..])
        })
    };
    match (tag("V="), tag("VR="), tag("VE=")) {
        (Some(v), _, _) => match literal(v) {
            Some(mm_s) => path(line, &format!("V={v}"), mm_s),
            None => Ok(Speed::Unread(format!(
                "V={}: the speed is held in a variable on the controller",
                short(v)
            ))),
        },
        (None, Some(v), _) => Ok(Speed::Unread(format!(
            "VR={}: an orientation speed; the TCP's is the controller's",
            short(v)
        ))),
        (None, None, Some(v)) => Ok(Speed::Unread(format!(
            "VE={}: an external axis's speed; the TCP's is the controller's",
            short(v)
        ))),
        _ => Ok(Speed::Unread(
            "no V= tag: the speed is the controller's".into(),
        )),
    }
}
