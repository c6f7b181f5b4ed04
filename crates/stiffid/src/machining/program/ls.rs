//! FANUC LS: the `/POS` section's positions in joint representation,
//! `P[1]{ GP1: UF : 0, UT : 1, J1= 0.000 deg, J2= ... J6= ... deg };` over one or more lines.
//! Only group 1 (`GP1`) is read.

use super::{at, number_at, six, Found, JointTarget};
use crate::Result;

/// Every joint target of `text` (module docs).
pub(crate) fn targets(text: &str) -> Result<Vec<JointTarget>> {
    let mut out = Vec::new();
    let mut in_pos = false;
    // The open position: its line, the values found, whether in group 1.
    let mut open: Option<(u64, Found, bool)> = None;
    for (line, start, l) in super::lines(text) {
        let t = l.trim();
        if t.starts_with('/') {
            in_pos = t.starts_with("/POS");
            continue;
        }
        if !in_pos {
            continue;
        }
        if t.starts_with("P[") {
            if let Some((first, ..)) = open {
                return Err(at(first, "position without its closing '};'".into()));
            }
            open = Some((line, Default::default(), false));
        }
        let Some((first, found, group1)) = open.as_mut() else {
            continue;
        };
        for piece in split_keeping_offsets(l) {
            let (offset, item) = piece;
            let item_t = item.trim();
            if let Some(g) = item_t.strip_prefix("GP") {
                *group1 = g.trim_start().starts_with('1');
            }
            if !*group1 {
                continue;
            }
            if item_t.starts_with("X ") || item_t.starts_with("X=") || item_t.starts_with("CONFIG")
            {
                return Err(at(*first, "a Cartesian position (CONFIG, X, Y, Z ...); stiffid compensates positions in joint representation (J1= .. deg)".into()));
            }
            let Some(eq) = item.find('=') else { continue };
            let name = item[..eq].trim();
            let name = name.rsplit(':').next().unwrap_or(name).trim();
            let Some(k) = name.strip_prefix('J').and_then(|d| d.parse::<usize>().ok()) else {
                continue;
            };
            if !(1..=6).contains(&k) {
                continue;
            }
            let (v, span) = number_at(l, offset + eq + 1)
                .ok_or_else(|| at(line, format!("{name}: expected a number")))?;
            if !l[span.end..].trim_start().starts_with("deg") {
                return Err(at(line, format!("{name}: expected a value in deg")));
            }
            found[k - 1] = Some((v, start + span.start..start + span.end));
        }
        if t.ends_with("};") {
            if let Some((first, found, _)) = open.take() {
                out.push(six(first, found, "J")?);
            }
        }
    }
    if let Some((first, ..)) = open {
        return Err(at(first, "position without its closing '};'".into()));
    }
    Ok(out)
}

/// The comma-separated pieces of a line (also split at `{`) with their byte offsets.
fn split_keeping_offsets(l: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut from = 0;
    for (i, c) in l.char_indices() {
        if c == ',' || c == '{' {
            out.push((from, &l[from..i]));
            from = i + 1;
        }
    }
    out.push((from, &l[from..]));
    out
}
