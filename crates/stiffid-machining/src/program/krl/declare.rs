//! The data a KRL program declares, in the `.src` or its `.dat` (`DEFDAT`): its points
//! (`E6AXIS`, `AXIS` as joint targets; `E6POS`, `POS`, `FRAME` as Cartesian ones), its frame data
//! records (`FDAT`), and the lines of the `.src` that assign a declared point at run time.

use super::cartesian;
use super::frames::{fdat, Fdats};
use crate::program::{at, number_at, six, JointTarget};
use std::collections::HashMap;
use stiffid_core::{Error, Result};

/// A point declared: where (its line, and `of the .dat` for one there) and its joint target, or
/// why it is none.
pub(super) type Declared = HashMap<String, (String, std::result::Result<JointTarget, String>)>;

/// A number declared (`REAL`, `INT`, `BOOL`): where (`on line 4 of the .dat`), and its value
/// and whether an `INT`, or why it has none.
pub(super) type Number = (String, std::result::Result<super::numbers::Typed, String>);

/// What a program and its `.dat` declare.
#[derive(Debug, Default)]
pub(super) struct Declarations {
    /// The points, by upper-case name.
    pub points: Declared,
    /// The frame data records, by upper-case name.
    pub fdats: Fdats,
    /// The line of the `.src` that last assigns each declared point at run time.
    pub assigned: HashMap<String, u64>,
    /// The points each routine after the first sees: its own declarations, then the `.dat`'s.
    pub subs: Vec<Declared>,
    /// The arrays of points declared (`DECL E6POS XP[5]`), by upper-case name, with their size
    /// where it is a literal.
    pub arrays: HashMap<String, Option<usize>>,
    /// The module's points declared with a value (not a routine's own), by upper-case name:
    /// their type word and aggregate, as written.
    pub raw: HashMap<String, (String, String)>,
    /// The numbers (`REAL`, `INT`, `BOOL`) of the module and the global data lists, by
    /// upper-case name ([`super::numbers`]).
    pub nums: HashMap<String, Number>,
    /// The numbers each routine after the first declares itself (without a value).
    pub local_nums: Vec<std::collections::HashSet<String>>,
    /// Every number declared, by upper-case name: whether an `INT` (or `BOOL`), not a `REAL`.
    pub num_types: HashMap<String, bool>,
}

impl Declarations {
    /// The numbers the line `code` declares (its type word `kind`) `on` a line of the routine
    /// `sub` after the first (its own), or of the module.
    fn number(&mut self, code: &str, kind: &str, (on, sub): (&str, Option<usize>)) {
        for (name, value) in numbers(code, kind, on) {
            self.num_types.insert(name.clone(), kind != "REAL");
            match sub {
                Some(k) => {
                    self.local_nums.resize_with(k + 1, Default::default);
                    self.local_nums[k].insert(name);
                }
                None => _ = self.nums.entry(name).or_insert(value),
            }
        }
    }

    /// The points the routine `routine` sees (1 the first, 2 the next..; 0 before any).
    pub(super) fn of(&self, routine: usize) -> &Declared {
        match routine.checked_sub(2).and_then(|k| self.subs.get(k)) {
            Some(d) => d,
            None => &self.points,
        }
    }
}

/// Where a text is: the `.src` (its points read or refused as they are found), or its `.dat`
/// from byte `offset` of the program's text, or a global data list of the backup (a point there
/// that cannot be read is refused only by a motion to it).
#[derive(Debug, Clone, Copy)]
pub(super) enum Place<'a> {
    /// The program.
    Src,
    /// Its `.dat`, from this byte of the program's text (the `.src` then the `.dat`).
    Dat(usize),
    /// A global data list of the controller's backup, named as given, read from its own first
    /// byte: `$config.dat` (every declaration global, `true`), or another module's public data
    /// list (`DEFDAT name PUBLIC`: its `GLOBAL` declarations only, `false`).
    Global(&'a str, bool),
}

/// The declarations of the `.src` `text`, of its `.dat` `data` and of the controller's global
/// data lists `globals` (each its name as given and its text: `$config.dat`, then the other
/// modules' public data lists, [`global_lists`]): a name declared in more than one is the
/// `.src`'s, else the `.dat`'s, else the first global list's, as KRL's local declaration hides
/// the module's and the module's the global one. A global point is compensated as any; its
/// compensated value is declared in the module ([`global`]), never in the global list.
///
/// # Errors
/// A malformed point of the `.src`, naming its line.
pub(super) fn declarations(
    text: &str,
    data: Option<&str>,
    globals: &[(&str, &str)],
) -> Result<Declarations> {
    let mut out = Declarations::default();
    let mut assignments = Vec::new();
    read(text, Place::Src, &mut out, &mut assignments)?;
    if let Some(d) = data {
        let mut own = Declarations::default();
        read(d, Place::Dat(text.len()), &mut own, &mut Vec::new())?;
        for sub in &mut out.subs {
            for (k, v) in &own.points {
                sub.entry(k.clone()).or_insert_with(|| v.clone());
            }
        }
        for (k, v) in own.points {
            out.points.entry(k).or_insert(v);
        }
        for (k, v) in own.fdats {
            out.fdats.entry(k).or_insert(v);
        }
        for (k, v) in own.arrays {
            out.arrays.entry(k).or_insert(v);
        }
        for (k, v) in own.raw {
            out.raw.entry(k).or_insert(v);
        }
        for (k, v) in own.nums {
            out.nums.entry(k).or_insert(v);
        }
        out.num_types.extend(own.num_types);
    }
    let mut seen = HashMap::new();
    for list in globals {
        global(&mut out, (text, data), *list, &mut seen)?;
    }
    out.assigned = assignments
        .into_iter()
        .filter(|(name, _)| out.points.contains_key(name) || out.num_types.contains_key(name))
        .rev()
        .collect();
    Ok(out)
}

/// The declarations of one text into `out`, its assignments into `assignments`.
fn read(
    text: &str,
    place: Place,
    out: &mut Declarations,
    assignments: &mut Vec<(String, u64)>,
) -> Result<()> {
    let (offset, file) = match place {
        Place::Src => (0, String::new()),
        Place::Dat(o) => (o, " of the .dat".to_string()),
        Place::Global(name, _) => (0, format!(" of {}", crate::program::file_name(name))),
    };
    // The routines of the .src met so far: a declaration in one after the first (the module's
    // main routine, whose motions are read) is local to it, seen by none of those motions.
    let mut routines = 0;
    for (line, start, l) in crate::program::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        let words = words(code);
        let first = words.iter().find(|w| *w != "GLOBAL").map(String::as_str);
        routines += usize::from(matches!(first, Some("DEF" | "DEFFCT")));
        let sub = match place {
            Place::Src if routines > 1 => Some(routines - 2),
            _ => None,
        };
        if let Some(k) = sub {
            out.subs.resize_with(k + 1, Declared::new);
        }
        let points = match sub {
            Some(k) => &mut out.subs[k],
            None => &mut out.points,
        };
        let w: Vec<&str> = words
            .iter()
            .map(String::as_str)
            .skip_while(|w| matches!(*w, "DECL" | "GLOBAL" | "CONST"))
            .collect();
        let declares = words.first().is_some_and(|f| f == "DECL") || w.len() < words.len();
        // A module's public data list gives the task its GLOBAL declarations only.
        if matches!(place, Place::Global(_, false)) && !words.iter().any(|w| w == "GLOBAL") {
            continue;
        }
        let on = format!("on line {line}{file}");
        match w.as_slice() {
            [kind @ ("REAL" | "INT" | "BOOL"), _, ..] => out.number(code, kind, (&on, sub)),
            [kind @ ("E6AXIS" | "AXIS" | "E6POS" | "POS" | "FRAME"), name, ..] => {
                let name = name.split(['[', ',']).next().unwrap_or(name).to_string();
                // `DECL POS a, b, c`: every name of a list declared without a value.
                if !code.contains('{') {
                    out.arrays.extend(arrays(code, kind));
                    for name in listed(code, kind) {
                        if sub.is_none() {
                            let raw = (kind.to_string(), String::new());
                            out.raw.entry(name.clone()).or_insert(raw);
                        }
                        let why =
                            format!("{name} is declared {on} without a value (set at run time)");
                        let value = twice(points, &name, &on, place, line)?.unwrap_or(Err(why));
                        points.insert(name, (on.clone(), value));
                    }
                    continue;
                }
                let value = match code.find('{') {
                    None => Err(format!(
                        "{name} is declared {on} without a value (set at run time)"
                    )),
                    Some(open) => match (aggregate_at(line, start + offset, code, open), place) {
                        (Ok(t), _) => Ok(declared_at(t, text, (start, offset), code, &name)),
                        (Err(e), Place::Src) => return Err(e),
                        (Err(e), _) => Err(format!("{name}, declared {on}: {}", message(e))),
                    },
                };
                let value = twice(points, &name, &on, place, line)?.unwrap_or(value);
                let raw = (sub.is_none().then(|| code.find('{')).flatten())
                    .map(|open| (name.clone(), (kind.to_string(), code[open..].to_string())));
                points.insert(name, (on, value));
                if let Some((name, raw)) = raw {
                    out.raw.entry(name).or_insert(raw);
                }
            }
            ["FDAT", name, ..] => {
                let value = match code.split_once('=') {
                    Some((_, v)) => fdat(v),
                    None => Err("declared without a value".into()),
                };
                out.fdats.insert(name.to_string(), (on, value));
            }
            [name, ..] if !declares && code.contains('=') => {
                // An element of an array of points given its value in the `.dat`:
                // `XP[1]={X ..}` (a literal index), a point of its own.
                if let (Place::Dat(_), Some(open)) = (place, code.find('{'))
                    && let Some(element) = element(name, &out.arrays)
                {
                    let key = element.clone().unwrap_or_else(|_| name.to_string());
                    let value = match element {
                        Ok(key) => match aggregate_at(line, start + offset, code, open) {
                            Ok(t) => Ok(declared_at(t, text, (start, offset), code, &key)),
                            Err(e) => Err(format!("{key}, given {on}: {}", message(e))),
                        },
                        Err(why) => Err(format!("{name}, given {on}: {why}")),
                    };
                    out.points.insert(key, (on, value));
                    continue;
                }
                let name = assigned(&w);
                assignments.push((name, line));
            }
            _ => {}
        }
    }
    Ok(())
}

/// The data a statement of words `w` (upper case) assigns (`XP1.Z = ..`: `XP1`; `FOR I = 1 TO
/// 5`: `I`).
fn assigned(w: &[&str]) -> String {
    let name = match w {
        ["FOR", var, ..] => var,
        [name, ..] => name,
        [] => "",
    };
    name.split(['.', '[']).next().unwrap_or(name).to_string()
}

/// Why `name`, declared `on` `line` of `place`, has no sure value when `points` holds it
/// already: KRL refuses a name declared twice in one module, so neither value is sure.
///
/// # Errors
/// A name of the `.src` declared twice, naming the line.
fn twice(
    points: &Declared,
    name: &str,
    on: &str,
    place: Place,
    line: u64,
) -> Result<Option<std::result::Result<JointTarget, String>>> {
    let Some((first, _)) = points.get(name) else {
        return Ok(None);
    };
    let why = format!("{name} is declared twice, {first} and {on}: the controller refuses a name declared twice in one module; declare it once");
    match place {
        Place::Src => Err(at(line, why)),
        _ => Ok(Some(Err(why))),
    }
}

/// The names a declaration without a value lists after its type word `kind` (`DECL POS a, b[3],
/// c`: `A`, `B`, `C`), upper case; a comma inside an array's brackets parts no names.
pub(super) fn listed(code: &str, kind: &str) -> Vec<String> {
    let upper = code.to_ascii_uppercase();
    let Some(at) = find_word(&upper, kind) else {
        return Vec::new();
    };
    let (mut names, mut depth, mut current) = (Vec::new(), 0usize, String::new());
    for c in upper[at + kind.len()..].chars() {
        match c {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            ',' if depth == 0 => names.push(std::mem::take(&mut current)),
            _ if depth == 0 => current.push(c),
            _ => {}
        }
    }
    names.push(current);
    names
        .into_iter()
        .map(|n| n.trim().to_string())
        .filter(|n| n.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_' || c == '$'))
        .collect()
}

/// The arrays a declaration without a value declares after its type word `kind` (`DECL E6POS
/// XP[5], XQ`: `XP` of 5), upper case, each with its size where it is a literal.
fn arrays(code: &str, kind: &str) -> Vec<(String, Option<usize>)> {
    let upper = code.to_ascii_uppercase();
    let Some(at) = find_word(&upper, kind) else {
        return Vec::new();
    };
    let rest = &upper[at + kind.len()..];
    let mut out = Vec::new();
    for (open, _) in rest.match_indices('[') {
        let name = rest[..open].trim_end();
        let name = name.rsplit([',', ' ', '\t']).next().unwrap_or("").trim();
        let size = rest[open + 1..].split(']').next().unwrap_or("").trim();
        if !name.is_empty() && !name.contains(['[', ']']) {
            out.push((name.to_string(), size.parse().ok()));
        }
    }
    out
}

/// The point an element of a declared array names (`XP[1]`, as found in the upper-case word
/// `word`): its key (`XP[1]`), or why it names none (an index that is no literal number or
/// outside the array); `None` when `word` is no element of an array of `arrays`.
pub(super) fn element(
    word: &str,
    arrays: &HashMap<String, Option<usize>>,
) -> Option<std::result::Result<String, String>> {
    let (base, rest) = word.split_once('[')?;
    let size = arrays.get(base.trim())?;
    let index = rest.split(']').next().unwrap_or("").trim();
    Some(match (index.parse::<usize>(), size) {
        (Ok(k), Some(n)) if k == 0 || k > *n => Err(format!(
            "index {k} outside the array {base}[{n}] (KRL counts from 1)"
        )),
        (Ok(k), _) => Ok(format!("{}[{k}]", base.trim())),
        (Err(_), _) => Err(format!(
            "an element of the array {base} chosen by an index the run gives ({index}); its value is the controller's: move to an element by its number, or to a point of its own"
        )),
    })
}

/// The byte of the first whole word `word` in `text`.
fn find_word(text: &str, word: &str) -> Option<usize> {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$';
    text.match_indices(word)
        .map(|(i, _)| i)
        .find(|&i| !text[..i].ends_with(ident) && !text[i + word.len()..].starts_with(ident))
}

/// The global data lists of the controller's backup in `context` (each its name as given and
/// its text), but the module's own `.dat` `data`: `$config.dat` first, then every other `.dat`
/// that opens `DEFDAT name PUBLIC` (KSS 8.x SI manual, "Data lists": a public data list's
/// `GLOBAL` declarations are the task's), in the order given.
pub(super) fn global_lists<'a>(
    context: &crate::program::Context<'a>,
    data: Option<&str>,
) -> Vec<(&'a str, &'a str)> {
    let mut lists: Vec<(&'a str, &'a str)> =
        context.backup_file("$config.dat").into_iter().collect();
    let public = |text: &str| {
        (text.lines().map(|l| l.split(';').next().unwrap_or("")))
            .find(|l| {
                l.split_whitespace()
                    .next()
                    .is_some_and(|w| w.eq_ignore_ascii_case("DEFDAT"))
            })
            .is_some_and(|l| {
                l.split_whitespace()
                    .any(|w| w.eq_ignore_ascii_case("PUBLIC"))
            })
    };
    for (name, text) in context.backup_with(|n| n.to_ascii_lowercase().ends_with(".dat")) {
        let own = data.is_some_and(|d| d == text);
        if !own && !name.to_ascii_lowercase().ends_with("$config.dat") && public(text) {
            lists.push((name, text));
        }
    }
    lists
}

/// The points and frame data records of a global data list of the controller (`file`, its
/// name as given, and its `text`: `$config.dat`, or another module's public data list, whose
/// `GLOBAL` declarations only) that the program (`src` and its `.dat`) does not declare itself, into
/// `out`. Each point is the program's own copy once compensated: a local declaration of the
/// same line without `GLOBAL` (KSS 8.x SI manual, "Data lists": a module's own data hides the
/// global data of that name), in the module's `.dat` after its `DEFDAT` line, or without a
/// `.dat` in the `.src` after its first `DEF` line (the routine's declaration part);
/// unchanged, it is not declared. A point two global lists declare (`seen`: where each global
/// point read so far is declared) is ambiguous: the controller refuses the name declared twice,
/// and a motion to it is refused naming both places (where the program does not hide it).
///
/// # Errors
/// Those of [`read`] (none for a data list read as `$config.dat`).
fn global(
    out: &mut Declarations,
    (src, data): (&str, Option<&str>),
    (file, text): (&str, &str),
    seen: &mut HashMap<String, String>,
) -> Result<()> {
    let mut found = Declarations::default();
    let config = crate::program::file_name(file).eq_ignore_ascii_case("$config.dat");
    read(
        text,
        Place::Global(file, config),
        &mut found,
        &mut Vec::new(),
    )?;
    let insert = match data {
        Some(d) => src.len() + after_line(d, "DEFDAT"),
        None => after_line(src, "DEF"),
    };
    for (k, (on, v)) in found.points {
        if let Some(first) = seen.get(&k) {
            let why = format!("{k} is declared GLOBAL twice, {first} and {on}: the controller refuses a global name declared twice; give the backup one declaration of it");
            let from_first = |d: &Declared| d.get(&k).is_some_and(|(o, _)| o == first);
            for d in std::iter::once(&mut out.points).chain(out.subs.iter_mut()) {
                if from_first(d) {
                    d.insert(k.clone(), (on.clone(), Err(why.clone())));
                }
            }
            continue;
        }
        seen.insert(k.clone(), on.clone());
        let v = v.and_then(|t| copied(t, (file, text), insert));
        for sub in &mut out.subs {
            sub.entry(k.clone())
                .or_insert_with(|| (on.clone(), v.clone()));
        }
        out.points.entry(k).or_insert((on, v));
    }
    for (k, v) in found.fdats {
        out.fdats.entry(k).or_insert(v);
    }
    for (k, v) in found.nums {
        let key = format!("={k}");
        match seen.get(&key) {
            Some(first) if out.nums.get(&k).is_some_and(|(o, _)| o == first) => {
                let why = format!("{k} is declared GLOBAL twice, {first} and {}: the controller refuses a global name declared twice; give the backup one declaration of it", v.0);
                out.nums.insert(k, (v.0.clone(), Err(why)));
            }
            Some(_) => {}
            None => {
                seen.insert(key, v.0.clone());
                out.nums.entry(k).or_insert(v);
            }
        }
    }
    for (k, v) in found.num_types {
        out.num_types.entry(k).or_insert(v);
    }
    for (k, v) in found.raw {
        out.raw.entry(k).or_insert(v);
    }
    Ok(())
}

/// The byte of `text` after the first line whose first word is `word` (case-insensitive), 0
/// without one.
pub(super) fn after_line(text: &str, word: &str) -> usize {
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        at += line.len();
        let first = line.split_whitespace().next().unwrap_or("");
        if first.eq_ignore_ascii_case(word) {
            return at;
        }
    }
    0
}

/// The point `t` of a global data list (`file`, its `text`) as the program declares its copy at byte
/// `insert` ([`global`]): its declaration's line without the word `GLOBAL`.
fn copied(
    t: JointTarget,
    (file, text): (&str, &str),
    insert: usize,
) -> std::result::Result<JointTarget, String> {
    let Some(p) = t.point.as_deref().cloned() else {
        return Err(format!("declared in {file} on a line whose name stiffid does not find before its value: declare it in the module's .dat"));
    };
    let line = &text[p.declaration.clone()];
    let upper = line.to_ascii_uppercase();
    let name_at = p.name.start - p.declaration.start;
    let (copy, removed) = match upper[..name_at].find("GLOBAL ") {
        Some(g) => (format!("{}{}", &line[..g], &line[g + 7..]), 7),
        None => (line.to_string(), 0),
    };
    let copy = match copy.ends_with('\n') {
        true => copy,
        false => copy + "\n",
    };
    let at = p.declaration.start + removed;
    let name = p.name.start - at..p.name.end - at;
    let foreign = crate::program::points::Foreign {
        text: copy,
        at,
        computed: false,
    };
    Ok(t.declared_elsewhere(foreign, name, insert))
}

/// The point `t` declared on the line at byte `start` of `text` (`offset`: where `text` begins
/// in the program's), `code` the line's code, `name` its upper-case name.
fn declared_at(
    t: JointTarget,
    text: &str,
    (start, offset): (usize, usize),
    code: &str,
    name: &str,
) -> JointTarget {
    let upper = code.to_ascii_uppercase();
    let at = upper.find('{').unwrap_or(upper.len());
    let Some(n) = upper[..at].rfind(name) else {
        return t;
    };
    let end = text[start..]
        .find('\n')
        .map_or(text.len(), |e| start + e + 1);
    let name = start + offset + n..start + offset + n + name.len();
    t.declared_at(start + offset..end + offset, name)
}

/// An error's message without its line.
fn message(e: Error) -> String {
    match e {
        Error::Program { message, .. } => message,
        other => other.to_string(),
    }
}
/// The joint target of the aggregate opening at byte `open` of `code` (which starts at byte
/// `start` of the text).
pub(super) fn aggregate_at(
    line: u64,
    start: usize,
    code: &str,
    open: usize,
) -> Result<JointTarget> {
    let close = code[open..]
        .find('}')
        .map(|c| open + c)
        .ok_or_else(|| at(line, "aggregate without its closing '}' on the line".into()))?;
    aggregate(line, start, code, open + 1, close)
}

/// The target of the aggregate between `from` and `to` of `code` (which starts at byte `start`).
fn aggregate(line: u64, start: usize, code: &str, from: usize, to: usize) -> Result<JointTarget> {
    let inner = &code[from..to];
    // An optional type: `{E6AXIS: A1 0, ...}`.
    let skip = inner.find(':').map_or(0, |c| c + 1);
    let mut found: [Option<(f64, std::ops::Range<usize>)>; 6] = Default::default();
    let mut external: Vec<Option<(f64, std::ops::Range<usize>)>> = Vec::new();
    let mut pose: Vec<(String, usize)> = Vec::new();
    let mut at_byte = from + skip;
    for item in code[from + skip..to].split(',') {
        let name_start = at_byte + item.len() - item.trim_start().len();
        let trimmed = item.trim();
        let name: String = trimmed
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect();
        let upper = name.to_ascii_uppercase();
        if cartesian::is_member(&upper) {
            pose.push((upper, name_start + name.len()));
            at_byte += item.len() + 1;
            continue;
        }
        let slot = |prefix: char| {
            upper
                .strip_prefix(prefix)
                .and_then(|d| d.parse::<usize>().ok())
                .filter(|k| (1..=6).contains(k))
        };
        let item_end = at_byte + item.len();
        let value = || {
            let (v, span) = number_at(code, name_start + name.len())
                .filter(|(_, s)| code[s.end..item_end].trim().is_empty())
                .ok_or_else(|| {
                    at(
                        line,
                        format!(
                            "{name}: expected a number, found '{}'",
                            stiffid_core::common::limits::short(trimmed[name.len()..].trim())
                        ),
                    )
                })?;
            Ok::<_, Error>((v, start + span.start..start + span.end))
        };
        if let Some(k) = slot('A') {
            if found[k - 1].is_some() {
                return Err(at(line, format!("{name} given twice")));
            }
            found[k - 1] = Some(value()?);
        } else if let Some(k) = slot('E') {
            if external.len() < k {
                external.resize(k, None);
            }
            if external[k - 1].is_some() {
                return Err(at(line, format!("{name} given twice")));
            }
            external[k - 1] = Some(value()?);
        }
        at_byte += item.len() + 1;
    }
    if !pose.is_empty() {
        if found.iter().any(Option::is_some) {
            return Err(at(
                line,
                "an aggregate with both axis angles (A1..) and a Cartesian pose (X..): give one"
                    .into(),
            ));
        }
        let c = cartesian::target(line, start, code, &pose)?;
        return Ok(JointTarget::cartesian(line, c).with_external(external));
    }
    six(line, found, "A").map(|t| t.with_external(external)).map_err(|e| match e {
        Error::Program { line, message } => Error::Program {
            line,
            message: format!("{message}: KRL keeps the axes a partial aggregate leaves out where the robot is, which the file does not say; give all six"),
        },
        other => other,
    })
}

/// The upper-case words of a line's code.
pub(super) fn words(code: &str) -> Vec<String> {
    code.split(|c: char| c.is_whitespace() || c == '=' || c == '{' || c == '(')
        .filter(|w| !w.is_empty())
        .map(str::to_ascii_uppercase)
        .collect()
}

/// The numbers a declaration line (`code`, its type word `kind`: `REAL`, `INT`, `BOOL`)
/// declares, by upper-case name, each with its value or why it has none (`on`: where).
pub(super) fn numbers(code: &str, kind: &str, on: &str) -> Vec<(String, Number)> {
    let Some((lhs, rhs)) = code.split_once('=') else {
        return (listed(code, kind).into_iter())
            .filter(|n| !n.contains('['))
            .map(|n| {
                let why = format!("{n} is declared {on} without a value (set at run time)");
                (n, (on.to_string(), Err(why)))
            })
            .collect();
    };
    let name = lhs
        .split_whitespace()
        .last()
        .unwrap_or("")
        .to_ascii_uppercase();
    if name.is_empty() || name.contains('[') {
        return Vec::new();
    }
    let none = |_: &str| None;
    let value = match (super::numbers::evaluate(rhs, &none), kind) {
        (Ok((v, _)), "REAL") => Ok((v, false)),
        (Ok((v, _)), "INT") if v.fract() == 0.0 => Ok((v, true)),
        (Ok((v, true)), "BOOL") if v == 0.0 || v == 1.0 => Ok((v, true)),
        _ => Err(format!(
            "{name} is declared {on} with '{}', which stiffid does not read as a {kind}",
            stiffid_core::common::limits::short(rhs.trim())
        )),
    };
    vec![(name, (on.to_string(), value))]
}
