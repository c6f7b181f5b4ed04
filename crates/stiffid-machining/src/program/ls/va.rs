//! FANUC ASCII variable files (`.VA`, the text a controller's backup writes beside each binary
//! variable file: `SYSFRAME.VA`, `POSREG.VA`): the entries of one position array, as a
//! controller of the R-30iA and R-30iB families writes them. A variable opens with a line
//! `[*SYSTEM*]$MNUTOOL  Storage: CMOS  Access: RW  : ARRAY[1,10] OF POSITION` (`[*POSREG*]$POSREG
//! .. OF Position Reg`); each of its entries with `[g,n] =` (motion group `g`, number `n`), a
//! comment in quotes, and either `Uninitialized` or the position: in Cartesian form `Group: g`,
//! `Config: N U T, 0, 0, 0`, then `X: .. Y: .. Z: ..` (mm) and `W: .. P: .. R: ..` (deg) over
//! the lines after it; in joint form `Group: g` on the entry's line, then `J1 = .. deg` to
//! `J6 = .. deg`; in either, the group's extended axes `EXT1: .. mm` (or `deg`) after them
//! (numbers as FANUC writes them: `-.364`). An entry's values that are not all numbers (`EXT1:
//! ******** mm`, a file cut off) are said in [`Entry::value`]: only a reader that uses the entry
//! refuses it.

/// A position of an entry: Cartesian (`X`..`R`, mm and deg, and its `Config` text) or joint
/// (`J1`..`J6`, deg); then its extended axes `EXT1`.., each its value and unit.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Value {
    /// `X`, `Y`, `Z` (mm), `W`, `P`, `R` (deg), the `Config` text (`N U T, 0, 0, 0`).
    Cartesian([f64; 6], String),
    /// `J1`..`J6`, deg.
    Joint([f64; 6]),
}

/// One entry of a position array: its motion group and number, the line it opens on, its
/// value (`None`: `Uninitialized`; the error: the line where its values do not read and why)
/// and its extended axes' values with their units.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Entry {
    pub group: u32,
    pub number: u32,
    pub line: u64,
    pub value: Result<Option<Value>, (u64, String)>,
    pub extended: Vec<(f64, &'static str)>,
}

/// The backup's file `file` (`SYSFRAME.VA`, `POSREG.VA`: its name as given and its text), if it
/// holds one.
///
/// # Errors
/// [`stiffid_core::Error::Parse`] naming both, two files of that name whose texts differ (two
/// backups given together): which one the controller holds is not the backup's to say.
pub(crate) fn the_file<'a>(
    context: &crate::program::Context<'a>,
    file: &str,
) -> stiffid_core::Result<Option<(&'a str, &'a str)>> {
    let found = context.backup_with(|name| name.eq_ignore_ascii_case(file));
    match found.iter().find(|(_, t)| *t != found[0].1) {
        Some((other, _)) => Err(stiffid_core::Error::Parse {
            source_name: other.to_string(),
            message: format!("a second {file} that differs from {}: one controller holds one; give the backup of the controller the program runs on", found[0].0),
        }),
        None => Ok(found.first().copied()),
    }
}

/// The names of the six Cartesian values, in order.
const NAMES: [&str; 6] = ["X:", "Y:", "Z:", "W:", "P:", "R:"];

/// An entry being read: the entry, its values so far (six Cartesian, six joint), whether it is
/// `Uninitialized`, its `Config` text, its extended axes, the first value that did not read.
#[derive(Default)]
struct Open {
    group: u32,
    number: u32,
    line: u64,
    cartesian: [Option<f64>; 6],
    joint: [Option<f64>; 6],
    uninitialized: bool,
    config: Option<String>,
    extended: Vec<(f64, &'static str)>,
    bad: Option<(u64, String)>,
}

impl Open {
    /// The entry read, saying why where its values do not read (`variable` names it).
    fn close(self, variable: &str) -> Entry {
        let whole = |v: &[Option<f64>; 6]| {
            let all: Option<Vec<f64>> = v.iter().copied().collect();
            all.filter(|a| a.iter().all(|x| x.is_finite()))
                .map(|a| [a[0], a[1], a[2], a[3], a[4], a[5]])
        };
        let given = |v: &[Option<f64>; 6]| v.iter().any(Option::is_some);
        let name = format!("{variable}[{},{}]", self.group, self.number);
        let value = match (&self.bad, self.uninitialized) {
            (Some((line, why)), _) => Err((*line, format!("{name}: {why}"))),
            (None, true) => Ok(None),
            (None, false) if given(&self.joint) => whole(&self.joint)
                .map(|j| Some(Value::Joint(j)))
                .ok_or_else(|| (self.line, format!("{name}: expected J1 to J6 (deg), each a number (is the file cut off?)"))),
            (None, false) => whole(&self.cartesian)
                .map(|p| Some(Value::Cartesian(p, self.config.clone().unwrap_or_default())))
                .ok_or_else(|| (self.line, format!("{name}: expected X:, Y:, Z: (mm) and W:, P:, R: (deg), each a number, or Uninitialized (is the file cut off?)"))),
        };
        Entry {
            group: self.group,
            number: self.number,
            line: self.line,
            value,
            extended: self.extended,
        }
    }
}

/// Whether `text` opens variable `variable` (`$POSREG`, `$MNUTOOL`) on a line of its own, as a
/// backup's ASCII variable file does.
pub(crate) fn declares(text: &str, variable: &str) -> bool {
    crate::program::lines(text).any(|(_, _, l)| {
        let t = l.trim();
        t.starts_with('[')
            && t.split_once(']')
                .is_some_and(|(_, r)| r.split_whitespace().next() == Some(variable))
    })
}

/// The entries of variable `variable` (`$MNUTOOL`, `$POSREG`) in `text`, in the file's order;
/// none when it does not hold the variable. An entry whose values do not read says why in
/// [`Entry::value`].
pub(crate) fn entries(text: &str, variable: &str) -> Vec<Entry> {
    let mut out: Vec<Entry> = Vec::new();
    let mut inside = false;
    let mut open: Option<Open> = None;
    // The array's size as its opening line declares it (`ARRAY[1,200]`: groups, numbers).
    let mut size: Option<(u64, (u32, u32))> = None;
    for (line, _, l) in crate::program::lines(text) {
        let t = l.trim();
        if t.starts_with("[*") || (t.starts_with('[') && t.contains("]$")) {
            out.extend(open.take().map(|o| o.close(variable)));
            let declared = t.split_once(']').map(|(_, r)| r).unwrap_or("");
            inside = declared.split_whitespace().next() == Some(variable);
            size = array_size(declared).map(|s| (line, s));
            continue;
        }
        if !inside {
            continue;
        }
        if let Some((group, number, rest)) = index(t) {
            out.extend(open.take().map(|o| o.close(variable)));
            let beyond =
                size.filter(|(_, (g, n))| group == 0 || number == 0 || group > *g || number > *n);
            open = Some(Open {
                group,
                number,
                line,
                uninitialized: rest.contains("Uninitialized"),
                bad: beyond.map(|(at, (g, n))| (line, format!("beyond the ARRAY[{g},{n}] line {at} declares (a file edited or cut and joined)"))),
                ..Open::default()
            });
            continue;
        }
        let Some(o) = open.as_mut() else {
            continue;
        };
        if let Err(why) = read_line(t, o) {
            o.bad.get_or_insert((line, why));
        }
    }
    out.extend(open.take().map(|o| o.close(variable)));
    twice(&mut out, variable);
    out
}

/// Each entry of `entries` whose group and number the file gives twice made a refusal naming
/// both lines: which one the controller holds is not the file's to say (a file edited or two
/// pasted together).
fn twice(entries: &mut [Entry], variable: &str) {
    let mut first: std::collections::HashMap<(u32, u32), u64> = Default::default();
    let mut lines: Vec<Option<(u64, u64)>> = vec![None; entries.len()];
    for (k, e) in entries.iter().enumerate() {
        if let Some(f) = first.get(&(e.group, e.number)) {
            lines[k] = Some((*f, e.line));
        } else {
            first.insert((e.group, e.number), e.line);
        }
    }
    for (k, both) in lines.iter().enumerate() {
        let Some((a, b)) = *both else { continue };
        let (g, n) = (entries[k].group, entries[k].number);
        for e in entries.iter_mut().filter(|e| (e.group, e.number) == (g, n)) {
            e.value = Err((b, format!("{variable}[{g},{n}]: given on line {a} and again on line {b}; which one the controller holds is not the file's to say (a file edited or two files joined): keep one")));
        }
    }
}

/// The groups and numbers of the array a variable's opening line declares (`: ARRAY[1,200] OF
/// Position Reg`), if it says.
fn array_size(declared: &str) -> Option<(u32, u32)> {
    let (_, after) = declared.split_once("ARRAY[")?;
    let (g, n) = after.split_once(']')?.0.split_once(',')?;
    Some((g.trim().parse().ok()?, n.trim().parse().ok()?))
}

/// The group, number and the rest of an entry's opening line `[g,n] = ..`, if `t` is one.
fn index(t: &str) -> Option<(u32, u32, &str)> {
    let inner = t.strip_prefix('[')?;
    let (inside, rest) = inner.split_once(']')?;
    let rest = rest.trim_start().strip_prefix('=')?;
    let (g, n) = inside.split_once(',')?;
    Some((g.trim().parse().ok()?, n.trim().parse().ok()?, rest))
}

/// The values of line `t` into the entry `o`: `Config: ..`, `X:` .. `R:`, `J1 =` .. `J6 =`,
/// `EXTn:`.
fn read_values_into(words: &[&str], o: &mut Open) -> std::result::Result<(), String> {
    let number = |i: usize, glued: &str| -> std::result::Result<f64, String> {
        let text = match glued.is_empty() {
            true => words.get(i + 1).copied().unwrap_or(""),
            false => glued,
        };
        text.parse::<f64>()
            .map_err(|_| format!("{}: expected a number, found '{text}'", words[i]))
    };
    for (i, w) in words.iter().enumerate() {
        if let Some(k) = NAMES.iter().position(|n| w.starts_with(n)) {
            o.cartesian[k] = Some(number(i, &w[2..])?);
        } else if let Some(k) = joint_axis(w).filter(|_| words.get(i + 1) == Some(&"=")) {
            o.joint[k] = Some(number(i + 1, "")?);
        } else if let Some(k) = (w.strip_prefix("EXT"))
            .and_then(|r| r.strip_suffix(':'))
            .and_then(|d| d.parse::<usize>().ok())
        {
            let v = number(i, "")?;
            let unit = match words.get(i + 2).copied() {
                Some("mm") => "mm",
                Some("deg") => "deg",
                other => {
                    return Err(format!(
                        "{w}: expected a value in mm or deg, found '{}'",
                        other.unwrap_or("")
                    ))
                }
            };
            if o.extended.len() + 1 != k {
                return Err(format!("{w}: expected EXT{}", o.extended.len() + 1));
            }
            o.extended.push((v, unit));
        }
    }
    Ok(())
}

/// The index (0-based) of a joint axis word `J1`..`J6`.
fn joint_axis(w: &str) -> Option<usize> {
    let k: usize = w.strip_prefix('J')?.parse().ok()?;
    (1..=6).contains(&k).then(|| k - 1)
}

/// Line `t` of an entry read into `o`: its `Config` (to the end of the line) or its values.
fn read_line(t: &str, o: &mut Open) -> std::result::Result<(), String> {
    if let Some((_, config)) = t.split_once("Config:") {
        o.config = Some(config.trim().to_string());
        return Ok(());
    }
    let words: Vec<&str> = t.split_whitespace().collect();
    read_values_into(&words, o)
}
