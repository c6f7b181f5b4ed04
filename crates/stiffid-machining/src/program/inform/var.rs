//! The robot position variables (`P000`..) a Yaskawa controller holds, from its backup's
//! `VAR.DAT` (the variable file a DX100, DX200, YRC1000 or FS100 backup writes): after
//! `//VAR`, `///PFNUM` (the axes of a robot's variable first) and the byte, integer, double,
//! real and string variables, the section `///P` holds one line per position variable in
//! order from `P000`: `"UNUSED"`, or the form in quotes and its fields,
//! `"PULSE"0,0,4,000000000000000000000000,0,0,-112054,-2215,-42236,531,25813,-48404,0,0`.
//! The second field is the variable's user frame number, the third its tool file number, the
//! fourth its manipulator type (`///RCONF`'s numbers, one character each), the sixth its
//! coordinates (`0` pulses, `16` base, `17` robot, `18` tool, `19` user coordinates: the codes
//! of Yaskawa's Ethernet server for a position variable's data type), then the axis values (six
//! robot axes and two more). Read from public controller backups: the
//! same variables a job of the backup lists in its `//POS` (`///TOOL 4`, `P00008=-112054,..`)
//! hold the same values and tool file there; OTHack1A/YASKAWA_Tools (`docs/posvar.py`) reads
//! the file so.

use crate::program::Context;
use stiffid_core::common::limits::short;
use stiffid_core::{Error, Result};

/// The file's name in a backup.
pub(super) const FILE: &str = "VAR.DAT";

/// One position variable as the file holds it.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Variable {
    /// `"UNUSED"`: the variable holds no position.
    Unused,
    /// `"PULSE"`: its tool file and six axis values in whole pulses, with their text.
    Pulse {
        tool: u32,
        values: Vec<(i64, String)>,
    },
    /// `"RECTAN"`: its user frame and tool file, manipulator type (the characters of its
    /// fourth field), coordinates (its sixth) and axis values with their text (six, and the
    /// two after them).
    Rectan {
        user: u32,
        tool: u32,
        config: String,
        coordinates: u32,
        values: Vec<(f64, String)>,
    },
    /// Another form: the form and its coordinates field, not read further.
    Other { form: String, coordinates: String },
}

/// The position variables of a backup: the file's name as given, and per variable its line
/// and value, in order from `P000`.
pub(super) struct Variables<'a> {
    pub file: &'a str,
    pub list: Vec<(u64, Variable)>,
}

/// The position variables of the `context`'s backup's `VAR.DAT`; `None` without the file.
///
/// # Errors
/// [`Error::Parse`] naming the file (and line): two `VAR.DAT` files that differ, a file
/// without a `///P` section, a `///PFNUM` whose robot has other than six axes, a line of
/// `///P` that does not read (a file cut off or edited).
pub(super) fn read<'a>(context: &Context<'a>) -> Result<Option<Variables<'a>>> {
    let files = context.backup_with(|n| n.eq_ignore_ascii_case(FILE));
    let Some(&(file, text)) = files.first() else {
        return Ok(None);
    };
    let failed = |message: String| Error::Parse {
        source_name: file.to_string(),
        message,
    };
    if let Some((other, _)) = files.iter().find(|(_, t)| *t != text) {
        return Err(failed(format!("the backup holds two VAR.DAT files that differ ({file} and {other}): one controller holds one set of variables; give the backup of the controller the job runs on")));
    }
    super::backupfile::whole(file, text)?;
    let mut list = Vec::new();
    let (mut in_p, mut after_p) = (false, false);
    for (line, _, l) in crate::program::lines(text) {
        let t = l.trim();
        if let Some(axes) = t.strip_prefix("///PFNUM") {
            let robot = axes.split(',').next().map(str::trim);
            if robot != Some("6") {
                return Err(failed(format!("line {line}: '{}': the variables are of a robot with {} axes; stiffid reads a six-axis robot's", short(t), robot.unwrap_or("no"))));
            }
        }
        if t.starts_with("//") {
            if in_p {
                after_p = true;
                break;
            }
            in_p = t == "///P";
            continue;
        }
        if in_p {
            let v = variable(t).map_err(|why| {
                let p = list.len();
                failed(format!("line {line}: P{p:03} '{}': {why}", short(t)))
            })?;
            list.push((line, v));
        }
    }
    if !in_p && list.is_empty() {
        return Err(failed(
            "no ///P section (the position variables): not a whole VAR.DAT (is the file cut off?)"
                .into(),
        ));
    }
    if !after_p {
        return Err(failed("the file ends in its ///P section, without the sections a controller writes after it (///BP, ///EX): not a whole VAR.DAT (is the file cut off?)".into()));
    }
    Ok(Some(Variables { file, list }))
}

/// One line of `///P` (module docs): `Err` saying why it does not read.
fn variable(t: &str) -> std::result::Result<Variable, String> {
    let rest = t
        .strip_prefix('"')
        .ok_or("expected a form in quotes (\"PULSE\", \"UNUSED\")")?;
    let (form, body) = rest.split_once('"').ok_or("expected a form in quotes")?;
    if form == "UNUSED" {
        return match body.trim().is_empty() {
            true => Ok(Variable::Unused),
            false => Err("\"UNUSED\" with values after it".into()),
        };
    }
    let fields: Vec<&str> = body.split(',').map(str::trim).collect();
    if fields.len() < 12 {
        return Err(format!(
            "expected six fields and the axis values, found {} fields",
            fields.len()
        ));
    }
    if form == "RECTAN" {
        return rectan(&fields);
    }
    if form != "PULSE" {
        let coordinates = fields[5].to_string();
        return Ok(Variable::Other {
            form: form.into(),
            coordinates,
        });
    }
    let tool = number(fields[2], "a tool file number")?;
    let mut values = Vec::with_capacity(fields.len() - 6);
    for f in &fields[6..] {
        let v = f
            .parse::<i64>()
            .map_err(|_| format!("'{}': expected a whole number of pulses", short(f)))?;
        values.push((v, (*f).to_string()));
    }
    if let Some((_, extra)) = values[6..].iter().find(|(v, _)| *v != 0) {
        return Err(format!("an axis value after the robot's six ({extra}): a variable of more than six axes, which stiffid does not read"));
    }
    values.truncate(6);
    Ok(Variable::Pulse { tool, values })
}

/// A whole number field, `Err` naming what was `expected`.
fn number(field: &str, expected: &str) -> std::result::Result<u32, String> {
    (field.parse::<u32>()).map_err(|_| format!("'{}': expected {expected}", short(field)))
}

/// The fields of a `"RECTAN"` line (module docs).
fn rectan(fields: &[&str]) -> std::result::Result<Variable, String> {
    let user = number(fields[1], "a user frame number")?;
    let tool = number(fields[2], "a tool file number")?;
    let coordinates = number(fields[5], "a coordinates code")?;
    let config = fields[3];
    if config.is_empty() || config.len() > 24 || !config.bytes().all(|b| b == b'0' || b == b'1') {
        return Err(format!(
            "'{}': expected the manipulator type as at most 24 characters 0 and 1",
            short(config)
        ));
    }
    let mut values = Vec::with_capacity(fields.len() - 6);
    for f in &fields[6..] {
        match f.parse::<f64>() {
            Ok(v) if v.is_finite() => values.push((v, (*f).to_string())),
            _ => return Err(format!("'{}': expected a number", short(f))),
        }
    }
    Ok(Variable::Rectan {
        user,
        tool,
        config: config.to_string(),
        coordinates,
        values,
    })
}
