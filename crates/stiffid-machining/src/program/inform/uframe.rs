//! The user frames a Yaskawa controller holds by number, from its backup's `UFRAME.CND` (the
//! condition file a DX100, DX200, YRC1000 or FS100 backup writes): per user frame a line
//! `//UFRAME n`, then `///NAME ..`, `///TOOL ..`, `///GROUP ..`, `///PULSE` and the three points
//! it was taught with (`////RORG`, `////RXX`, `////RXY`, in pulses: not read), and its frame
//! in base coordinates, `////BUSER X,Y,Z,Rx,Ry,Rz` (mm, deg: turned about the base's fixed X,
//! then Y, then Z, `Rz Ry Rx`, as a position's `Rx,Ry,Rz`). A block without `////BUSER` gives no
//! frame.

use crate::program::Context;
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use std::collections::BTreeMap;
use stiffid_core::{Error, Result};

/// The file's name in a backup.
pub(crate) const FILE: &str = "UFRAME.CND";

/// User frames by number: the frame (the controller's base coordinates, m) and where the file
/// states it.
pub(super) type Frames = BTreeMap<u32, (Isometry3<f64>, String)>;

/// The user frames of the `context`'s backup's `UFRAME.CND`; none without the file.
///
/// # Errors
/// [`Error::Parse`] naming the file and line of a `//UFRAME` without a number, a `////BUSER`
/// outside a block or whose frame is not six numbers (a file cut off or edited).
pub(super) fn frames(context: &Context) -> Result<Frames> {
    let Some((name, text)) = context.backup_file(FILE) else {
        return Ok(Frames::new());
    };
    super::backupfile::whole(name, text)?;
    let failed = |line: u64, message: String| Error::Parse {
        source_name: name.to_string(),
        message: format!("line {line}: {message}"),
    };
    let mut out = Frames::new();
    let mut open: Option<u32> = None;
    let mut blocks = 0;
    for (line, _, l) in crate::program::lines(text) {
        let t = l.trim();
        if let Some(n) = t.strip_prefix("//UFRAME") {
            blocks += 1;
            let n = n.trim().parse::<u32>().map_err(|_| {
                failed(
                    line,
                    format!("'{t}': expected //UFRAME and a user frame number"),
                )
            })?;
            open = Some(n);
            continue;
        }
        let Some(values) = t.trim_start_matches('/').strip_prefix("BUSER") else {
            continue;
        };
        let n = open.ok_or_else(|| failed(line, "////BUSER before any //UFRAME n".into()))?;
        let v: Vec<f64> = (values.split(',').map(|w| w.trim().parse::<f64>()))
            .collect::<std::result::Result<_, _>>()
            .ok()
            .filter(|v: &Vec<f64>| v.len() == 6 && v.iter().all(|x| x.is_finite()))
            .ok_or_else(|| failed(line, format!("user frame {n}: expected its frame after ////BUSER, X,Y,Z,Rx,Ry,Rz (mm, deg), six numbers")))?;
        let rotation = UnitQuaternion::from_euler_angles(
            v[3].to_radians(),
            v[4].to_radians(),
            v[5].to_radians(),
        );
        let position = Translation3::new(v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e-3);
        let source = format!("{name} line {line} (user frame {n})");
        let frame = Isometry3::from_parts(position, rotation);
        super::backupfile::insert(&mut out, (name, line, "user frame"), (n, frame, source))?;
    }
    let block = "//UFRAME n, ///NAME .. and its frame in base coordinates, ////BUSER X,Y,Z,Rx,Ry,Rz (mm, deg)";
    super::backupfile::some(name, blocks, ("user frame", block))?;
    Ok(out)
}
