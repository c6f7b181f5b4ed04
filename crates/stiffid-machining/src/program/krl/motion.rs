//! One KRL motion line's targets (module docs of [`super`]): `PTP`, `LIN`, `SPTP`, `SLIN` to
//! an aggregate or a declared point, `CIRC`/`SCIRC` to an auxiliary point and an end point;
//! every other motion refused naming the line.

use super::assign::{Value, Values};
use super::declare::{aggregate_at, Declarations};
use crate::program::points::Point;
use crate::program::{at, JointTarget};
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// What a motion line reads against: the declarations, and whether a `.dat` was given.
pub(super) struct Context<'a> {
    /// The declarations of the `.src` and its `.dat`.
    pub declared: &'a Declarations,
    /// Whether the `.dat` was read.
    pub data: bool,
    /// The routine of the line: 1 the module's first (`DEF`), 2 the next..
    pub routine: usize,
}

/// What a line moves to.
pub(super) enum Found {
    /// No motion.
    Nothing,
    /// The motion's targets.
    Targets(Vec<JointTarget>),
    /// A motion to a point whose value only the run gives: why, and the point when declared.
    RunTime(String, Option<Point>),
    /// A joint motion to the home position, passed through: what it is.
    Home(String),
}

/// A target, or why only the run gives it (and its declared point).
type Target = std::result::Result<(JointTarget, usize), (String, Option<Point>)>;

/// The targets of a motion line (one, or for `CIRC` the auxiliary point then the end point),
/// [`Found::Nothing`] for a line that is no motion; every motion outside the subset refused
/// naming the line.
pub(super) fn motion(
    (line, start): (u64, usize),
    code: &str,
    first: &str,
    (context, values): (&Context, &Values),
) -> Result<Found> {
    let refuse = |what: &str| Err(at(line, format!("{first}: {what}")));
    let circle = match first {
        "PTP" | "LIN" | "SPTP" | "SLIN" => false,
        "CIRC" | "SCIRC" => true,
        "PTP_REL" | "LIN_REL" | "SPTP_REL" | "SLIN_REL" | "CIRC_REL" | "SCIRC_REL" => {
            return refuse("a relative motion; stiffid compensates absolute joint targets: write the absolute target")
        }
        "SPL" | "SPLINE" | "PTP_SPLINE" | "ENDSPLINE" | "SLIN_SPL" | "SCIRC_SPL" => {
            return refuse("a spline; its path bends through all its points, not along the compensated ones: write it as LIN or PTP motions")
        }
        "ASYPTP" | "ASYCONT" => {
            return refuse("an asynchronous motion of external axes; not compensated: remove it")
        }
        "RSI_MOVECORR" | "ST_MOVECORR" => {
            return refuse("a motion the Robot Sensor Interface commands from its sensor, not the program's targets; stiffid does not compensate it: write the path as PTP/LIN motions")
        }
        _ => return Ok(Found::Nothing),
    };
    // `PTP $AXIS_ACT` (RoboDK's KUKA posts begin with it) and `LIN $POS_ACT`: a motion to where
    // the robot stands, which moves nothing.
    let target = code.trim_start()[first.len()..].trim();
    if !circle
        && ["$AXIS_ACT", "$POS_ACT"]
            .iter()
            .any(|v| target.eq_ignore_ascii_case(v))
    {
        return Ok(Found::Nothing);
    }
    // The home position (`XHOME`, `HOME` of the inline forms and `$config.dat`, `$H_POS`): a
    // joint motion there passes through as the controller holds it, not compensated.
    let name = target
        .split(|c: char| c.is_whitespace() || c == ',')
        .next()
        .unwrap_or("");
    if matches!(first, "PTP" | "SPTP")
        && ["XHOME", "HOME", "$H_POS"]
            .iter()
            .any(|h| name.eq_ignore_ascii_case(h))
    {
        return Ok(Found::Home(format!("{first} {name}: the home position, passed through as the controller holds it: not compensated, not checked")));
    }
    let mut from = code.len() - code.trim_start()[first.len()..].len();
    let mut out = Vec::with_capacity(2);
    for k in 0..=usize::from(circle) {
        let (target, after) = match one((line, start), code, from, (first, context), values)? {
            Ok(found) => found,
            Err((why, point)) => return Ok(Found::RunTime(format!("{first} {why}"), point)),
        };
        out.push(target);
        from = after;
        if circle && k == 0 {
            let rest = &code[from..];
            let comma = rest.trim_start().strip_prefix(',').ok_or_else(|| {
                at(
                    line,
                    format!("{first}: expected the auxiliary point, a comma, then the end point"),
                )
            })?;
            from = code.len() - comma.len();
        }
    }
    check_after(line, first, &code[from..])?;
    out[0].via = circle;
    if circle && out.iter().any(|t| t.cartesian.is_none()) {
        return refuse(
            "a circle through axis angles; KRL's CIRC takes Cartesian points (POS, E6POS, FRAME)",
        );
    }
    Ok(Found::Targets(out))
}

/// The target at or after blanks from byte `from` of `code`: an aggregate or a declared point,
/// and the byte after it.
fn one(
    (line, start): (u64, usize),
    code: &str,
    from: usize,
    (first, context): (&str, &Context),
    values: &Values,
) -> Result<Target> {
    let rest = code[from..].trim_start();
    let open = code.len() - rest.len();
    if rest.starts_with('{') {
        let close = code[open..]
            .find('}')
            .map(|c| open + c)
            .ok_or_else(|| at(line, "aggregate without its closing '}' on the line".into()))?;
        return Ok(Ok((aggregate_at(line, start, code, open)?, close + 1)));
    }
    let name: String = rest
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '$' | '[' | ']'))
        .collect();
    let upper = indexed(&name.to_ascii_uppercase(), context, values);
    let declared = context.declared;
    let points = declared.of(context.routine);
    let element = super::declare::element(&upper, &declared.arrays);
    let base = upper.split('[').next().unwrap_or(&upper);
    let point = || match points.get(&upper) {
        Some((_, Ok(t))) => t.point.as_deref().cloned(),
        _ => None,
    };
    let assigned = match element {
        Some(_) => declared.assigned.get(base).map(|l| Value::Assigned(*l)),
        None => values.get(&upper).cloned(),
    };
    match assigned {
        Some(Value::Assigned(on)) => return Ok(Err((format!("{name}: {name} is assigned on line {on}, so its value at the motion is the controller's, not the file's: give the motion its own declared point"), point()))),
        Some(Value::Unknown(why)) => return Ok(Err((format!("{name}: {name} {why}"), point()))),
        Some(Value::Number(..)) => return Err(at(line, format!("{first} {name}: a number (REAL, INT, BOOL), not a point"))),
        Some(Value::Known(_, _, t)) => {
            let reference = start + open..start + open + name.len();
            return Ok(Ok((t.moved_to(line, false).named_at(reference), open + name.len())));
        }
        None => {}
    }
    let upper = match element {
        Some(Ok(key)) if !points.contains_key(&key) => {
            return Err(at(line, format!("{first} {name}: the array {base} is declared, but no value of this element is given in the .dat (it is set at run time): give the element its value in the .dat")))
        }
        Some(Ok(key)) => key,
        Some(Err(why)) if !points.contains_key(&upper) => {
            return Ok(Err((format!("{name}: {why}"), None)))
        }
        _ => upper,
    };
    let target = match points.get(&upper) {
        Some((_, Ok(t))) => t.moved_to(line, false).named_at(start + open..start + open + name.len()),
        Some((_, Err(why))) => return Err(at(line, format!("{first} {name}: {why}"))),
        None if name.is_empty() => return Err(at(line, format!("{first}: expected a point or an aggregate {{..}}"))),
        None if upper == "XHOME" => return Err(at(line, format!("{first} {name}: a path motion to the home position, which the controller holds and stiffid does not compensate: move there with PTP"))),
        None if name.starts_with('$') => return Ok(Err((format!("{name}: a system variable, whose value is the controller's at run time: give the motion a point declared in the .src or its .dat"), None))),
        None if context.data => return Err(at(line, format!("{first} {name}: not a point declared in the .src, its .dat or a global data list of the backup given with the program ($config.dat, another module's PUBLIC .dat: none declares it, or none was given): give the controller's backup with the program (--backup), or declare the point in the .dat as E6POS or E6AXIS"))),
        None => return Err(at(line, format!("{first} {name}: not a point declared in the .src, and no .dat beside it (the .src's stem with .dat) nor a global data list of the backup ($config.dat, another module's PUBLIC .dat) declares it: give the .dat beside the .src or the controller's backup (--backup), or declare the point in the .dat as E6POS or E6AXIS"))),
    };
    Ok(Ok((target, open + name.len())))
}

/// Refuses a word after a motion's target(s), up to its `WITH` clause, that is not an
/// approximation: a geometric operator, an offset, a circle's angle (`CA`), or anything else
/// (`LIN XP1 C_DIS XX`, which the controller refuses to load).
pub(super) fn check_after(line: u64, first: &str, after: &str) -> Result<()> {
    let extra = after
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter(|w| !w.is_empty())
        .take_while(|w| !w.eq_ignore_ascii_case("WITH"))
        .find(|w| {
            let w = w.to_ascii_uppercase();
            !matches!(w.as_str(), "C_PTP" | "C_DIS" | "C_VEL" | "C_ORI" | "C_SPL")
        });
    match extra {
        Some(w) if w.eq_ignore_ascii_case("CA") => Err(at(line, format!("{first}: CA, a circular angle: the motion ends elsewhere than its end point, on the circle; write the end point the controller reaches"))),
        Some(w) => Err(at(line, format!("{first}: '{}' after the target is not followed (a geometric operator, an offset or an option): write the motion to its absolute target", short(w)))),
        None => Ok(()),
    }
}

/// The element `upper` (`XP[I]`) of an array of points with its index a number known here (a
/// `FOR` loop's variable unrolled, [`super::numbers`]) written as its literal (`XP[2]`); any
/// other name as it is.
fn indexed(upper: &str, context: &Context, values: &Values) -> String {
    let Some((base, rest)) = upper.split_once('[') else {
        return upper.to_string();
    };
    let index = rest.split(']').next().unwrap_or("").trim();
    if index.parse::<usize>().is_ok() || !context.declared.arrays.contains_key(base.trim()) {
        return upper.to_string();
    }
    let (declared, routine) = (context.declared, context.routine);
    let lookup = |n: &str| {
        let n = n.to_ascii_uppercase();
        Some(super::known::number(declared, &n, routine, values))
    };
    match super::numbers::evaluate(index, &lookup) {
        Ok((v, true)) if v >= 0.0 => format!("{}[{v}]", base.trim()),
        _ => upper.to_string(),
    }
}
