//! An LS program's motion group mask (`/ATTR`'s `DEFAULT_GROUP = 1,*,*,*,*;`: `1` for each group
//! the program holds, `*` for the others; FANUC R-30iB Operator's Manual, "program header"):
//! a program whose motions or positions use a group its mask does not hold is one the controller
//! does not load, refused naming the mask's line. A program without the line is read as holding
//! the groups its positions give.

use crate::program::{at, lines};
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// Checks program `text`'s mask against its motions (`motions`: whether it has any) and the
/// groups its positions give (module docs).
///
/// # Errors
/// Naming the `DEFAULT_GROUP` line: a mask that does not hold group 1 in a program with
/// motions, or group 2 in one whose positions give `GP2`; a mask that is not `1` or `*` per
/// group.
pub(super) fn check(text: &str, motions: bool) -> Result<()> {
    let Some((line, mask)) = default_group(text) else {
        return Ok(());
    };
    let shown = || short(mask).to_string();
    let groups: Vec<&str> = mask.split(',').map(str::trim).collect();
    if groups.iter().any(|g| !matches!(*g, "1" | "*")) {
        return Err(at(
            line,
            format!(
                "DEFAULT_GROUP = {}: expected 1 or * for each motion group (1,*,*,*,*)",
                shown()
            ),
        ));
    }
    let holds = |g: usize| groups.get(g) == Some(&"1");
    if motions && !holds(0) {
        return Err(at(line, format!("DEFAULT_GROUP = {}: the program holds no motion group 1 (the robot), yet it has motions; stiffid reads motion group 1 as the robot: compensate a program of group 1", shown())));
    }
    let mut in_pos = false;
    for (l, _, t) in lines(text) {
        let t = t.trim();
        if t.starts_with('/') {
            in_pos = t.starts_with("/POS");
            continue;
        }
        let group = [("GP1", 0), ("GP2", 1)]
            .into_iter()
            .find(|(g, _)| t.starts_with(g));
        if let (true, Some((g, k))) = (in_pos, group)
            && !holds(k)
        {
            return Err(at(line, format!("DEFAULT_GROUP = {}: the program does not hold motion group {}, yet its position on line {l} gives {g}; the controller does not load such a program: give the mask its groups", shown(), k + 1)));
        }
    }
    Ok(())
}

/// The line and the mask (between `=` and `;`) of `/ATTR`'s `DEFAULT_GROUP`, if the program
/// states one.
fn default_group(text: &str) -> Option<(u64, &str)> {
    for (line, _, l) in lines(text) {
        let t = l.trim();
        if t.starts_with("/MN") {
            return None;
        }
        if let Some(rest) = t.strip_prefix("DEFAULT_GROUP") {
            let rest = rest.trim_start().strip_prefix('=')?;
            return Some((line, rest.trim().trim_end_matches(';').trim()));
        }
    }
    None
}
