//! A KUKA controller's backup ([`Context::backup`]): `$config.dat` (`KRC/R1/System/$config.dat`,
//! KUKA System Software's global data list) holds the tool and base tables, `TOOL_DATA[n] =
//! {X .., .., C ..}` in the flange frame and `BASE_DATA[n]` in the world frame (KSS 8.x SI
//! manual, "Tool and base data"): read as the frames a number selects, in place of the setup's
//! `[controller] tools` and `bases`, which may also give them only where they agree.

use super::frames::{compact, table_entry};
use crate::program::cartesian::{same, Frame};
use crate::program::Context;
use std::collections::HashMap;
use stiffid_core::{Error, Result};

/// The entries of the tool (`false`) and base (`true`) tables the backup's `$config.dat` gives,
/// by number; none without one.
///
/// # Errors
/// [`Error::InvalidField`] (`controller.tools`, `controller.bases`) where the setup's table gives
/// an entry another frame than `$config.dat`, naming both.
pub(super) fn tables(context: &Context) -> Result<HashMap<(bool, u32), Frame>> {
    let Some((file, text)) = context.backup_file("$config.dat") else {
        return Ok(HashMap::new());
    };
    let mut out = HashMap::new();
    for (line, _, l) in crate::program::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        let Some((base, Some(n), frame)) = table_entry(line, &compact(code), code) else {
            continue;
        };
        let setup = match base {
            true => context.bases.and_then(|b| b.get(n)),
            false => context.tool.and_then(|(_, t)| t.get(n)),
        };
        if let (Some(s), Frame::Stated(_, f)) = (setup, &frame)
            && !same(s, f)
        {
            let (table, kind) = match base {
                true => ("BASE_DATA", "bases"),
                false => ("TOOL_DATA", "tools"),
            };
            return Err(Error::InvalidField {
                field: format!("controller.{kind}"),
                message: format!("number {n}: {file} line {line} gives {table}[{n}] another frame than the setup's [controller] {kind} entry {n}; give it once (the backup's, or the setup's without the backup)"),
            });
        }
        out.insert((base, n), frame);
    }
    Ok(out)
}
