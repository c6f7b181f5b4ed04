//! The tool files a Yaskawa controller holds by number, from its backup's `TOOL.CND` (the
//! condition file a DX200, YRC1000 or FS100 backup writes): per tool file a line `//TOOL n`,
//! `///NAME ..`, then its frame in the flange frame, `X,Y,Z,Rx,Ry,Rz` (mm, deg: turned about
//! the flange's fixed X, then Y, then Z, `Rz Ry Rx`), then its centre of gravity, weight and
//! inertia (not read).

use crate::program::Context;
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use std::collections::BTreeMap;
use stiffid_core::{Error, Result};

/// The file's name in a backup.
pub(crate) const FILE: &str = "TOOL.CND";

/// Tool files by number: the frame (flange frame, m) and where the file states it.
pub(super) type Tools = BTreeMap<u32, (Isometry3<f64>, String)>;

/// The tool files of the `context`'s backup's `TOOL.CND`; none without the file.
///
/// # Errors
/// [`Error::Parse`] naming the file and line of a `//TOOL` without a number or whose frame line
/// is not six numbers (a file cut off or edited).
pub(super) fn tools(context: &Context) -> Result<Tools> {
    let Some((name, text)) = context.backup_file(FILE) else {
        return Ok(Tools::new());
    };
    super::backupfile::whole(name, text)?;
    let failed = |line: u64, message: String| Error::Parse {
        source_name: name.to_string(),
        message: format!("line {line}: {message}"),
    };
    let mut out = Tools::new();
    let mut open: Option<(u32, u64)> = None;
    let mut blocks = 0;
    for (line, _, l) in crate::program::lines(text) {
        let t = l.trim();
        if let Some(n) = t.strip_prefix("//TOOL") {
            if let Some((n, at)) = open {
                return Err(no_frame(name, n, at));
            }
            blocks += 1;
            let n = n.trim().parse::<u32>().map_err(|_| {
                failed(
                    line,
                    format!("'{t}': expected //TOOL and a tool file number"),
                )
            })?;
            open = Some((n, line));
            continue;
        }
        if t.starts_with("///") || t.is_empty() {
            continue;
        }
        let Some((n, at)) = open.take() else {
            continue;
        };
        let v: Vec<f64> = (t.split(',').map(|w| w.trim().parse::<f64>()))
            .collect::<std::result::Result<_, _>>()
            .ok()
            .filter(|v: &Vec<f64>| v.len() == 6 && v.iter().all(|x| x.is_finite()))
            .ok_or_else(|| failed(line, format!("tool file {n} (line {at}): expected its frame, X,Y,Z,Rx,Ry,Rz (mm, deg), six numbers")))?;
        let rotation = UnitQuaternion::from_euler_angles(
            v[3].to_radians(),
            v[4].to_radians(),
            v[5].to_radians(),
        );
        let position = Translation3::new(v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e-3);
        let source = format!("{name} line {line} (tool file {n})");
        let frame = Isometry3::from_parts(position, rotation);
        super::backupfile::insert(&mut out, (name, line, "tool file"), (n, frame, source))?;
    }
    if let Some((n, at)) = open {
        return Err(no_frame(name, n, at));
    }
    let block = "//TOOL n, ///NAME .., then its frame X,Y,Z,Rx,Ry,Rz (mm, deg)";
    super::backupfile::some(name, blocks, ("tool file", block))?;
    Ok(out)
}

/// The error of tool file `n` of `name`, opened on line `at` with no frame line after it.
fn no_frame(name: &str, n: u32, at: u64) -> Error {
    Error::Parse {
        source_name: name.to_string(),
        message: format!("line {at}: tool file {n} with no frame line after its //TOOL and ///NAME lines: expected X,Y,Z,Rx,Ry,Rz (mm, deg), six numbers (a file cut off or edited)"),
    }
}
