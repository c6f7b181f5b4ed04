//! FANUC LS positions in Cartesian representation (module docs of [`super`]): `UF : n`,
//! `UT : n`, `CONFIG : '..'`, `X = .. mm` to `R = .. deg`.

use crate::program::cartesian::flags::Part;
use crate::program::cartesian::{within_limits, Cartesian, Flags, Frame};
use crate::program::ls::Config;
use crate::program::{at, Dialect};
use std::ops::Range;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// The pose's members in the order a target takes them, with their units.
pub(crate) const POSE: [(&str, &str); 6] = [
    ("X", "mm"),
    ("Y", "mm"),
    ("Z", "mm"),
    ("W", "deg"),
    ("P", "deg"),
    ("R", "deg"),
];

/// One value and its span in the text.
pub(crate) type Value = Option<(f64, Range<usize>)>;

/// `l` with every quoted text blanked (byte for byte), so that commas in `CONFIG : '..'` do not
/// split it.
pub(crate) fn masked(l: &str) -> String {
    let mut quoted = false;
    let mut out = String::with_capacity(l.len());
    for c in l.chars() {
        if c == '\'' {
            quoted = !quoted;
        }
        match quoted && c != '\'' {
            true => out.extend(std::iter::repeat_n(' ', c.len_utf8())),
            false => out.push(c),
        }
    }
    out
}

/// The `CONFIG : '..'` of line `l` (which starts at byte `start` of the text): the data and the
/// span of the text inside the quotes; `None` without one.
pub(crate) fn config(line: u64, start: usize, l: &str) -> Result<Option<(Flags, Range<usize>)>> {
    let Some(at_config) = l.find("CONFIG") else {
        return Ok(None);
    };
    let open = l[at_config..].find('\'').map(|o| at_config + o + 1);
    let close = open.and_then(|o| l[o..].find('\'').map(|c| o + c));
    let (Some(open), Some(close)) = (open, close) else {
        return Err(at(
            line,
            "CONFIG: expected its text in quotes, 'N U T, 0, 0, 0'".into(),
        ));
    };
    let flags = Config::parse(&l[open..close])
        .map(Flags::new)
        .map_err(|why| at(line, why))?;
    Ok(Some((flags, start + open..start + close)))
}

/// The user (`true`) or tool frame number a piece `UF : n` or `UT : n` gives.
pub(crate) fn frame_number(line: u64, piece: &str) -> Result<Option<(bool, u32)>> {
    let t = piece.trim();
    let user = match t.get(..2) {
        Some("UF") => true,
        Some("UT") => false,
        _ => return Ok(None),
    };
    let n = t[2..].trim_start().strip_prefix(':').map(str::trim);
    match n {
        Some("F") => Ok(Some((user, IN_FORCE))),
        Some(n) => match n.parse::<u32>() {
            Ok(n) if n <= MAX_FRAME => Ok(Some((user, n))),
            _ => Err(at(
                line,
                format!(
                    "{} : {}: expected a frame number, 0 to {MAX_FRAME}, or F (the frame in force)",
                    &t[..2],
                    short(n)
                ),
            )),
        },
        None => Err(at(
            line,
            format!("{}: expected ': n', a frame number", &t[..2]),
        )),
    }
}

/// The largest frame number a position names (a controller holds far fewer: `UFRAME[1..9]`, up
/// to 61 with the extended frames option).
pub(super) const MAX_FRAME: u32 = 999;

/// The number stiffid gives a position's `UF : F` or `UT : F`: the frame in force where its
/// motion runs (the one `UFRAME_NUM=`/`UTOOL_NUM=` selected before it, [`super::numbered`]), as
/// FANUC's position registers are by default. No frame the controller holds has it.
pub(crate) const IN_FORCE: u32 = u32::MAX;

/// The Cartesian target of a position read on `line`: its six pose values, its `CONFIG`, user
/// and tool frame numbers.
pub(crate) fn target(
    line: u64,
    pose: &[Value; 6],
    config: Option<(Flags, Range<usize>)>,
    (user, tool): (Option<u32>, Option<u32>),
) -> Result<Cartesian> {
    let values: Option<Vec<(f64, Range<usize>)>> = pose.iter().cloned().collect();
    let values = values.ok_or_else(|| {
        let missing: Vec<&str> = (POSE.iter().zip(pose))
            .filter(|(_, v)| v.is_none())
            .map(|((n, _), _)| *n)
            .collect();
        at(
            line,
            format!(
                "a Cartesian position without {}: give X, Y, Z, W, P and R",
                missing.join(", ")
            ),
        )
    })?;
    within_limits(line, &POSE.map(|(name, _)| name), &values)?;
    let mut c = Cartesian::new(Dialect::FanucLs, &values);
    if let Some((flags, span)) = config {
        c.flags = Some(flags);
        c.flag_spans = vec![(span, Part::new(()))];
    }
    let unknown = |name: &str| {
        Frame::Unknown(line, format!("a Cartesian position without {name}: its frame is the controller's, which the program does not say; give {name} : n"))
    };
    c.frame = match user {
        Some(0) => Frame::World,
        Some(n) => Frame::Numbered(line, n),
        None => unknown("UF"),
    };
    c.tool = match tool {
        Some(0) => Frame::World,
        Some(n) => Frame::Numbered(line, n),
        None => unknown("UT"),
    };
    Ok(c)
}
