//! FANUC ASCII variable files (`.VA`, the text a controller's backup writes beside each binary
//! variable file: `SYSFRAME.VA`, `POSREG.VA`): the entries of one position array, as a
//! controller of the R-30iA and R-30iB families writes them. A variable opens with a line
//! `[*SYSTEM*]$MNUTOOL  Storage: CMOS  Access: RW  : ARRAY[1,10] OF POSITION`; each of its
//! entries with `[g,n] =` (motion group `g`, number `n`), a comment in quotes, and either
//! `Uninitialized` or the position: `Group: g`, `Config: N U T, 0, 0, 0`, then `X: .. Y: ..
//! Z: ..` (mm) and `W: .. P: .. R: ..` (deg) over the lines after it (numbers as FANUC writes
//! them: `-.364`).

use stiffid_core::{Error, Result};

/// One entry of a position array: its motion group and number, the line it opens on, and its
/// `X`, `Y`, `Z` (mm), `W`, `P`, `R` (deg); `None` for an entry `Uninitialized`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Entry {
    pub group: u32,
    pub number: u32,
    pub line: u64,
    pub pose: Option<[f64; 6]>,
}

/// The names of the six values, in order.
const NAMES: [&str; 6] = ["X:", "Y:", "Z:", "W:", "P:", "R:"];

/// The entries of variable `variable` (`$MNUTOOL`) in the file `name` of text `text`, in the
/// file's order; none when it does not hold the variable.
///
/// # Errors
/// [`Error::Parse`] naming the file and line of an entry that is neither `Uninitialized` nor
/// six finite numbers `X:` to `R:` (a file cut off or edited), or a position in joint form.
pub(crate) fn entries(name: &str, text: &str, variable: &str) -> Result<Vec<Entry>> {
    let mut out: Vec<Entry> = Vec::new();
    let mut inside = false;
    let mut open: Option<(Entry, [Option<f64>; 6], bool)> = None;
    let failed = |line: u64, message: String| Error::Parse {
        source_name: name.to_string(),
        message: format!("line {line}: {message}"),
    };
    let mut close = |open: Option<(Entry, [Option<f64>; 6], bool)>| -> Result<()> {
        let Some((mut e, values, uninitialized)) = open else {
            return Ok(());
        };
        if !uninitialized {
            let pose = values.iter().copied().collect::<Option<Vec<f64>>>();
            let pose = pose.filter(|p| p.iter().all(|v| v.is_finite()));
            let pose = pose.ok_or_else(|| failed(e.line, format!("{variable}[{},{}]: expected X:, Y:, Z: (mm) and W:, P:, R: (deg), each a number, or Uninitialized (is the file cut off?)", e.group, e.number)))?;
            e.pose = Some([pose[0], pose[1], pose[2], pose[3], pose[4], pose[5]]);
        }
        out.push(e);
        Ok(())
    };
    for (line, _, l) in crate::program::lines(text) {
        let t = l.trim();
        if t.starts_with("[*") || (t.starts_with('[') && t.contains("]$")) {
            close(open.take())?;
            let declared = t.split_once(']').map(|(_, r)| r).unwrap_or("");
            inside = declared.split_whitespace().next() == Some(variable);
            continue;
        }
        if !inside {
            continue;
        }
        if let Some((group, number, rest)) = index(t) {
            close(open.take())?;
            let entry = Entry {
                group,
                number,
                line,
                pose: None,
            };
            open = Some((entry, [None; 6], rest.contains("Uninitialized")));
            continue;
        }
        let Some((e, values, _)) = open.as_mut() else {
            continue;
        };
        if t.starts_with("J1") || t.contains(" J1 ") {
            return Err(failed(line, format!("{variable}[{},{}]: a position in joint form; stiffid reads these frames as X, Y, Z, W, P, R", e.group, e.number)));
        }
        read_values(t, values).map_err(|why| failed(line, why))?;
    }
    close(open.take())?;
    Ok(out)
}

/// The group, number and the rest of an entry's opening line `[g,n] = ..`, if `t` is one.
fn index(t: &str) -> Option<(u32, u32, &str)> {
    let inner = t.strip_prefix('[')?;
    let (inside, rest) = inner.split_once(']')?;
    let rest = rest.trim_start().strip_prefix('=')?;
    let (g, n) = inside.split_once(',')?;
    Some((g.trim().parse().ok()?, n.trim().parse().ok()?, rest))
}

/// The values `X:` .. `R:` of line `t` into `values`.
fn read_values(t: &str, values: &mut [Option<f64>; 6]) -> std::result::Result<(), String> {
    let words: Vec<&str> = t.split_whitespace().collect();
    for (i, w) in words.iter().enumerate() {
        let Some(k) = NAMES.iter().position(|n| w.starts_with(n)) else {
            continue;
        };
        let glued = &w[2..];
        let number = match glued.is_empty() {
            true => words.get(i + 1).copied().unwrap_or(""),
            false => glued,
        };
        let v = number
            .parse::<f64>()
            .map_err(|_| format!("{}: expected a number, found '{number}'", NAMES[k]))?;
        values[k] = Some(v);
    }
    Ok(())
}
