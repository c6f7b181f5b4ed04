//! The value a robot position variable of the backup's `VAR.DAT` ([`super::var`]) gives its
//! copy in the job ([`super::variables`]): in pulses, the variable's six values after
//! `///TOOL n`, `///POSTYPE PULSE` and `///PULSE`; in Cartesian form (`"RECTAN"`), its six
//! values after `///TOOL n`, `///USER n` (in user coordinates), `///POSTYPE BASE`, `ROBOT` or
//! `USER` and `///RECTAN` and `///RCONF`, read as a Cartesian position of the job is
//! ([`super::rectan`]). The coordinates codes are those of Yaskawa's Ethernet server for a
//! position variable's data type (`16` base, `17` robot, `18` tool, `19` user coordinates); the
//! manipulator type is read where it is certain: all zero (no flip, upper arm, front, every
//! axis under 180 deg), or as the job lists the variable (`///RCONF` before `P00013=..`, the
//! values when the job was saved), since the order of the file's characters is not public.

use super::pos::{Form, Listed};
use super::rconf::Rconf;
use super::var::Variable;
use stiffid_core::common::limits::short;

/// A copy's value: the lines before its position, its six values (with their text), its form,
/// tool file, frame (`///POSTYPE`), user frame and manipulator type.
pub(super) struct Value {
    pub head: String,
    pub values: Vec<(f64, String)>,
    pub form: Form,
    pub tool: u32,
    pub frame: &'static str,
    pub user: Option<u32>,
    pub rconf: Option<Rconf>,
}

/// The value of the variable `v` (`VAR.DAT`'s line `vline` of `file`) as its copy declares it,
/// with line ends `eol`, checked against the job's own listing of it (`listed`).
///
/// # Errors
/// Why, in words, naming the file's line: a variable unused, of tool or unknown coordinates, of
/// more than six axes, whose manipulator type is not certain, or that the job lists otherwise.
pub(super) fn of(
    v: &Variable,
    (file, vline): (&str, u64),
    listed: Option<&Listed>,
    eol: &str,
) -> Result<Value, String> {
    let value = match v {
        Variable::Pulse { tool, values } => Value {
            head: format!("///TOOL {tool}{eol}///POSTYPE PULSE{eol}///PULSE{eol}"),
            values: values.iter().map(|(p, t)| (*p as f64, t.clone())).collect(),
            form: Form::Pulse,
            tool: *tool,
            frame: "PULSE",
            user: None,
            rconf: None,
        },
        Variable::Unused => {
            return Err(format!(
                "{file} line {vline}: the variable is UNUSED, it holds no position"
            ))
        }
        Variable::Other { form, coordinates } => {
            return Err(format!("{file} line {vline}: a \"{}\" variable (coordinates {}); stiffid reads position variables in pulses (\"PULSE\") and Cartesian form (\"RECTAN\")", short(form), short(coordinates)));
        }
        Variable::Rectan { .. } => rectan(v, (file, vline), listed, eol)?,
    };
    if let Some(l) = listed.filter(|l| !same(&value, l)) {
        return Err(format!("the job lists the variable (line {}, its value when the job was saved) with other values, frame or tool file than {file} line {vline}; which one the controller holds is not the files' to say: give the backup the job was saved with", l.line));
    }
    Ok(value)
}

/// Whether the job's listing `l` is the value `v`.
fn same(v: &Value, l: &Listed) -> bool {
    let frame = |f: &str| f.split_whitespace().next().unwrap_or("").to_string();
    let numbers = l.values.len() == 6
        && (l.values.iter().zip(&v.values)).all(|(a, (b, _))| a.parse::<f64>() == Ok(*b));
    let cartesian = v.form != Form::Rectan
        || (frame(&l.frame) == v.frame
            && (v.user.is_none() || l.user == v.user)
            && l.rconf.is_none_or(|r| Some(r) == v.rconf));
    l.form == v.form && l.tool.is_none_or(|t| t == v.tool) && numbers && cartesian
}

/// The value of a `"RECTAN"` variable `v` (module docs).
fn rectan(
    v: &Variable,
    (file, vline): (&str, u64),
    listed: Option<&Listed>,
    eol: &str,
) -> Result<Value, String> {
    let Variable::Rectan {
        user,
        tool,
        config,
        coordinates,
        values,
    } = v
    else {
        unreachable!("rectan() is given a RECTAN variable")
    };
    let at = format!("{file} line {vline}: a \"RECTAN\" variable");
    let frame = match coordinates {
        16 => "BASE",
        17 => "ROBOT",
        19 => "USER",
        18 => return Err(format!("{at} in tool coordinates (18): relative to where the tool is when the motion starts, which the job does not say (a shift amount, for SFTON); stiffid reads positions in base, robot or user coordinates")),
        n => return Err(format!("{at} in coordinates {n}, which stiffid does not know (16 base, 17 robot, 18 tool, 19 user coordinates)")),
    };
    if values.len() < 6 {
        return Err(format!(
            "{at} with {} values, expected X,Y,Z,Rx,Ry,Rz",
            values.len()
        ));
    }
    if let Some((_, extra)) = values[6..].iter().find(|(x, _)| *x != 0.0) {
        return Err(format!("{at} with a value after X,Y,Z,Rx,Ry,Rz ({}): a base or station axis's, or a seven-axis robot's; stiffid reads the six of a robot alone", short(extra)));
    }
    let zero = config.bytes().all(|b| b == b'0');
    let rconf = match (zero, listed.and_then(|l| l.rconf)) {
        (true, _) => Rconf([0; 6]),
        (false, Some(r)) => r,
        (false, None) => return Err(format!("{at} whose manipulator type is {} in an order that is not public, and the job does not list the variable with its ///RCONF (a job the controller saves lists the variables it moves to): give the job as the controller saved it", short(config))),
    };
    let user = (frame == "USER").then_some(*user);
    let numbers: Vec<String> = (0..config.len().max(8))
        .map(|k| rconf.0.get(k).map_or("0".into(), u8::to_string))
        .collect();
    let user_line = user.map_or(String::new(), |u| format!("///USER {u}{eol}"));
    Ok(Value {
        head: format!(
            "///TOOL {tool}{eol}{user_line}///POSTYPE {frame}{eol}///RECTAN{eol}///RCONF {}{eol}",
            numbers.join(",")
        ),
        values: values[..6].to_vec(),
        form: Form::Rectan,
        tool: *tool,
        frame,
        user,
        rconf: Some(rconf),
    })
}
