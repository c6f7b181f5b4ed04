//! ABB RAPID: `MoveAbsJ [[..],[..]], v100, z10, tool0;` (also `MoveAbsJ \Conc, ..`, and the
//! switches `\ID`, `\NoEOffs`, `\V`, `\T`, `\Z`, `\Inpos`, `\WObj`, `\TLoad`) to a literal or to a
//! `jointtarget` declared in the module: `CONST jointtarget j1 := [[0,0,0,0,30,0],[9E9,..]];`
//! (also `VAR`, `PERS`, `LOCAL`, `TASK`), over one line or several. RAPID is statement based
//! (`;` ends one) and case-insensitive; `!` starts a comment.
//!
//! The second bracket holds the external axes `eax_a` to `eax_f` (mm for a linear axis, deg for
//! a rotary one; `9E9` for an axis that is not used): read, and written back where they change.
//!
//! `MoveL` and `MoveJ` (also `\Conc`) to a `robtarget` literal or one declared in the module are
//! Cartesian targets, with their `tooldata` and `\WObj:=` `wobjdata` declared in the module
//! ([`super::cartesian`]); `MoveC` gives two, its circle point then its end point (the controller
//! moves on the circle through the previous target and them: each point is compensated, the arc
//! between is the circle through the compensated points). A point may also be `Offs` or
//! `RelTool` of one with constant arguments (module `offset`).
//!
//! Every motion of every routine is read where it is, inside loops, branches and error handlers
//! too (module `read`); a `PROC` of another module of the task is read where the module calls it
//! (modules `calls`, `called`); docs/programs/rapid.md is the guide, with ABB's manuals as the
//! source of each rule.

mod arguments;
mod arrays;
mod assign;
mod backup;
mod called;
mod calls;
mod cartesian;
pub(crate) mod confdata;
mod flow;
mod generate;
mod layout;
mod named;
mod names;
mod num;
mod numflow;
mod offset;
mod parameters;
mod percall;
mod place;
mod process;
mod read;
mod refusals;
mod shared;
pub(crate) mod speed;
mod state;
mod unroll;
pub use confdata::ConfData;

use super::cartesian::{literal, Frame};
use super::controller::{BoundComment, Controller, Generator, Read};
use super::descriptor::{AxisNames, Descriptor, FileName, NameRules};
use super::{at, number_at, six, JointTarget};
use nalgebra::{UnitQuaternion, Vector3};
use speed::RapidSpeeds;
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// A `jointtarget` or `robtarget` declared in the module: its target, or why it is none.
type Declared = HashMap<String, std::result::Result<JointTarget, String>>;

/// The module's declared data: targets, tools and work objects, speeds (by lower-case name),
/// and the statements that assign a declared target at run time.
#[derive(Default)]
struct Data {
    targets: Declared,
    frames: HashMap<String, Frame>,
    speeds: RapidSpeeds,
    assigned: HashMap<String, u64>,
    nums: num::Nums,
    renum: numflow::Renum,
    rebound: assign::Rebound,
    bound: assign::Bound,
    shadowed: parameters::Shadowed,
}

/// One statement: its line, and its bytes in the text.
struct Statement {
    line: u64,
    span: std::ops::Range<usize>,
}

/// Why a module without motions gives no target: what it holds instead.
fn no_motion(routines: &[(String, u64)]) -> String {
    let listed: Vec<String> = (routines.iter().take(5))
        .map(|(n, l)| format!("{n} (line {l})"))
        .collect();
    let holds = match routines.len() {
        0 => "no routine: a module of data (declarations only)".to_string(),
        n => format!(
            "{n} routine{} ({}{}) without a motion instruction: a module of data, I/O or communication, or one whose routines call the motions of another module",
            if n == 1 { "" } else { "s" },
            listed.join(", "),
            if n > 5 { ", .." } else { "" }
        ),
    };
    format!("no motion instruction in the module (MoveAbsJ, MoveL, MoveJ, MoveC); it holds {holds}: give stiffid the module with the path's motions")
}

/// The instruction's name: the statement's first word, lower case, up to a switch or argument.
fn first_word(body: &str) -> String {
    body.trim_start()
        .split(|c: char| c.is_whitespace() || matches!(c, '\\' | ',' | ';' | '(' | ':'))
        .next()
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Refuses a statement whose first word (`first`) RAPID cannot read: a character
/// other than a letter, a digit, `_`, a component's `.` or an index's `{}` (a header's `%%%`
/// and a byte-order mark aside), such as `Mov%eL`, `MoveL]` or `MovéL`, which the controller refuses to load;
/// passed over, a motion written so would be lost.
fn well_formed(line: u64, first: &str) -> Result<()> {
    // A byte-order mark opening the file (editors on Windows write one) is no character of it.
    let word = first.trim_start_matches('\u{feff}');
    let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '{' | '}');
    // `<SMT>`, the editor's placeholder of a statement: the controller loads a module holding
    // one and stops where the run reaches it (RAPID kernel, "Placeholders"); it moves nothing.
    let placeholder = word.trim_end_matches(';').eq_ignore_ascii_case("<SMT>");
    match word.starts_with('%') || placeholder || word.chars().all(allowed) {
        true => Ok(()),
        false => Err(at(
            line,
            format!(
                "'{}': not a RAPID statement (names are letters, digits and _)",
                short(first)
            ),
        )),
    }
}

/// `text` with every comment (`!` outside a string, to the line's end) blanked, byte for byte.
fn without_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let (mut in_string, mut in_comment) = (false, false);
    for c in text.chars() {
        match c {
            '\n' => (in_string, in_comment) = (false, false),
            '"' if !in_comment => in_string = !in_string,
            '!' if !in_string => in_comment = true,
            _ => {}
        }
        // A byte-order mark is blank, as a comment (the byte offsets kept).
        match in_comment || c == '\u{feff}' {
            true => out.extend(std::iter::repeat_n(' ', c.len_utf8())),
            false => out.push(c),
        }
    }
    out
}

/// Lines that are statements of their own, without a `;`: the module's structure.
fn is_header(line: &str) -> bool {
    let t = line.trim();
    let w: Vec<String> = t
        .split_whitespace()
        .take(3)
        .map(str::to_ascii_lowercase)
        .collect();
    let w: Vec<&str> = w
        .iter()
        .map(String::as_str)
        .skip_while(|w| matches!(*w, "local" | "task"))
        .collect();
    let first = w.first().map_or("", |f| f.split('(').next().unwrap_or(f));
    // A label (`skip:`, *RAPID kernel*: labels) is a statement of its own, without `;`.
    let label = t.strip_suffix(':').is_some_and(|l| {
        l.starts_with(|c: char| c.is_ascii_alphabetic())
            && l.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    });
    t.starts_with('%')
        || label
        || t.to_ascii_uppercase().ends_with("THEN")
        || matches!(
            first,
            "module"
                | "endmodule"
                | "proc"
                | "endproc"
                | "func"
                | "endfunc"
                | "trap"
                | "endtrap"
                | "record"
                | "endrecord"
                | "elseif"
                | "else"
                | "endif"
                | "for"
                | "endfor"
                | "while"
                | "endwhile"
                | "test"
                | "case"
                | "default"
                | "endtest"
                | "error"
                | "undo"
                | "backward"
        )
        || t.starts_with("VERSION:")
        || t.starts_with("LANGUAGE:")
}

/// The statements of `code` (comments blanked): each ends at a `;` outside a string, or is a
/// header line.
fn statements(code: &str) -> Vec<Statement> {
    let mut out = Vec::new();
    let mut open: Option<(u64, usize)> = None;
    // A routine's header whose parameter list runs on over the next lines: its line, first
    // byte and the parentheses still open.
    let mut header: Option<(u64, usize, i64)> = None;
    let depth = |t: &str| t.matches('(').count() as i64 - t.matches(')').count() as i64;
    for (line, start, l) in super::lines(code) {
        if let Some((first, from, open)) = header.take() {
            match open + depth(l) {
                left if left > 0 => header = Some((first, from, left)),
                _ => out.push(Statement {
                    line: first,
                    span: from..start + l.len(),
                }),
            }
            continue;
        }
        let mut in_string = false;
        for (i, c) in l.char_indices() {
            if open.is_none() {
                if c.is_whitespace() {
                    continue;
                }
                // An editor's statement placeholder stands alone on its line, without `;`.
                if is_header(&l[i..]) || l[i..].trim().eq_ignore_ascii_case("<SMT>") {
                    match depth(&l[i..]) {
                        left if left > 0 => header = Some((line, start + i, left)),
                        _ => out.push(Statement {
                            line,
                            span: start + i..start + l.len(),
                        }),
                    }
                    break;
                }
                open = Some((line, start + i));
            }
            match c {
                '"' => in_string = !in_string,
                ';' if !in_string => {
                    let (first, from) = open.take().unwrap_or((line, start + i));
                    out.push(Statement {
                        line: first,
                        span: from..start + i + 1,
                    });
                }
                _ => {}
            }
        }
    }
    if let Some((line, from)) = open {
        out.push(Statement {
            line,
            span: from..code.len(),
        });
    }
    out
}

/// The data declared in the module ([`Data`]).
fn declarations(code: &str, statements: &[Statement]) -> Result<Data> {
    let mut declared = Declared::new();
    let mut frames = HashMap::new();
    let mut speeds = RapidSpeeds::new();
    let mut assignments = Vec::new();
    let mut names = HashMap::new();
    let mut numbers = num::Reading::default();
    for s in statements {
        let body = &code[s.span.clone()];
        let lower = body.to_ascii_lowercase();
        let words = words_of(&lower);
        let twice = refusals::declared_twice(s.line, &words, &mut names);
        numbers.statement(&words, body, s.line);
        parameters::declare(s.line, body, (&mut declared, &mut frames));
        match words.as_slice() {
            ["const" | "var" | "pers", "jointtarget", name, ..] => {
                let (name, value) = joint_declared(code, s, name, &mut declared)?;
                declared.insert(name, value);
            }
            ["const" | "var" | "pers", "speeddata", name, ..] => {
                let name = name.trim_end_matches(';');
                let v_tcp = (body.find(":=").filter(|_| !name.contains('{')))
                    .and_then(|eq| literal::parse(code, s.span.start + eq + 2))
                    .and_then(|(node, _)| node.numbers(4))
                    .map(|v| (v[0].0, s.line));
                let why = || {
                    format!("speeddata {name} is declared on line {} without a literal value or as an array: its speed is the controller's", s.line)
                };
                speeds.insert(name.to_string(), v_tcp.ok_or_else(why));
            }
            ["const" | "var" | "pers", kind, name, ..] if cartesian::is_data(kind) => {
                let name = name.trim_end_matches(';');
                if let (Some((array, _)), Some(eq), "robtarget") =
                    (name.split_once('{'), body.find(":="), *kind)
                {
                    arrays::declare((array, "robtarget"), (code, s, eq), &mut declared);
                    continue;
                }
                let Some(eq) = body.find(":=").filter(|_| !name.contains('{')) else {
                    let why = format!("{kind} {name} is declared on line {} without a value or as an array: declare each with its value", s.line);
                    match *kind {
                        "robtarget" => _ = declared.insert(name.to_string(), Err(why)),
                        _ => _ = frames.insert(name.to_string(), Frame::Unknown(s.line, why)),
                    }
                    continue;
                };
                let from = s.span.start + eq + 2;
                match *kind {
                    "robtarget" => {
                        let target = cartesian::robtarget(s.line, code, from)?;
                        let target = declared_at(target, code, s, name);
                        declared.insert(name.to_string(), Ok(target));
                    }
                    _ => {
                        let frame = cartesian::frame(kind, name, s.line, code, from);
                        frames.insert(name.to_string(), frame);
                    }
                }
            }
            [first, ..] if body.contains(":=") && !matches!(*first, "const" | "var" | "pers") => {
                let name = first.split(['.', '{']).next().unwrap_or(first);
                assignments.push((name.to_string(), s.line));
            }
            _ => {}
        }
        match twice {
            Some(("speeddata", name, why)) => _ = speeds.insert(name, Err(why)),
            Some(("jointtarget" | "robtarget", name, why)) => _ = declared.insert(name, Err(why)),
            Some((_, name, why)) => _ = frames.insert(name, Frame::Unknown(s.line, why)),
            None => {}
        }
    }
    let (nums, renum) = numbers.finish(&assignments, (code, statements));
    let known = |name: &String| {
        declared.contains_key(name) || frames.contains_key(name) || speeds.contains_key(name)
    };
    let assigned = assignments
        .into_iter()
        .filter(|(name, _)| known(name))
        .rev()
        .collect();
    let assigned: HashMap<String, u64> = assigned;
    for (name, line) in &assigned {
        let why = format!("{name} is assigned on line {line}, so its value at the motion is the controller's, not the module's");
        if let Some(f) = frames.get_mut(name) {
            *f = Frame::Unknown(*line, why.clone());
        }
        if let Some(v) = speeds.get_mut(name) {
            *v = Err(why);
        }
    }
    Ok(Data {
        targets: declared,
        frames,
        speeds,
        assigned,
        nums,
        renum,
        ..Data::default()
    })
}

/// The words of a statement (lower case), `LOCAL` and `TASK` skipped.
fn words_of(lower: &str) -> Vec<&str> {
    (lower.split(|c: char| c.is_whitespace() || c == ':' || c == '='))
        .filter(|w| !w.is_empty())
        .skip_while(|w| matches!(*w, "local" | "task"))
        .collect()
}

/// The `jointtarget` `name` (lower case, as written after its type) the statement `s` of `code`
/// declares: its name and its target, or why it has none (an array's elements into `declared`).
fn joint_declared(
    code: &str,
    s: &Statement,
    name: &str,
    declared: &mut Declared,
) -> Result<(String, std::result::Result<JointTarget, String>)> {
    let body = &code[s.span.clone()];
    let name = name.trim_end_matches(';');
    let (name, array) = match name.split_once('{') {
        Some((n, _)) => (n, true),
        None => (name, false),
    };
    let value = match (array, body.find(":=")) {
        (true, Some(eq)) => {
            arrays::declare((name, "jointtarget"), (code, s, eq), declared);
            Err(format!(
                "{name} is an array of jointtargets (line {}): move to one of its elements",
                s.line
            ))
        }
        (true, None) => Err(format!(
            "{name} is an array of jointtargets (line {}) declared without a value",
            s.line
        )),
        (false, None) => Err(format!(
            "{name} is declared on line {} without a value (set at run time)",
            s.line
        )),
        (false, Some(eq)) => Ok(declared_at(
            literal(s.line, code, s.span.start + eq + 2)?,
            code,
            s,
            name,
        )),
    };
    Ok((name.to_string(), value))
}

/// `t` declared by the statement `s` of `code` as `name` (lower case), where the statement has
/// its lines to itself (its declaration then copied whole when a second point is needed).
fn declared_at(t: JointTarget, code: &str, s: &Statement, name: &str) -> JointTarget {
    let begin = code[..s.span.start].rfind('\n').map_or(0, |i| i + 1);
    let end = (code[s.span.end..].find('\n')).map_or(code.len(), |i| s.span.end + i + 1);
    if !code[begin..s.span.start].trim().is_empty() || !code[s.span.end..end].trim().is_empty() {
        return t;
    }
    let lower = code[s.span.clone()].to_ascii_lowercase();
    let eq = lower.find(":=").unwrap_or(lower.len());
    match lower[..eq].rfind(name) {
        Some(at) => {
            let n = s.span.start + at;
            t.declared_at(begin..end, n..n + name.len())
        }
        None => t,
    }
}

/// The joint target of the literal `[[j1,..,j6],[..]]` at or after byte `from` of `code`.
fn literal(line: u64, code: &str, from: usize) -> Result<JointTarget> {
    let rest = &code[from..];
    let open = from + rest.len() - rest.trim_start().len();
    if !code[open..].starts_with("[[") {
        return Err(at(
            line,
            "jointtarget: expected a literal [[j1,..,j6],[e1,..,e6]]".into(),
        ));
    }
    let mut found: [Option<(f64, std::ops::Range<usize>)>; 6] = Default::default();
    let mut from = open + 2;
    for (k, slot) in found.iter_mut().enumerate() {
        let (v, span) = number_at(code, from).ok_or_else(|| {
            at(
                line,
                format!(
                    "jointtarget: expected 6 numbers in its first bracket, axis {} is not one",
                    k + 1
                ),
            )
        })?;
        let rest = code[span.end..].trim_start();
        let sep = if k < 5 { ',' } else { ']' };
        if !rest.starts_with(sep) {
            return Err(at(
                line,
                format!("jointtarget: expected '{sep}' after axis {}", k + 1),
            ));
        }
        from = code.len() - rest.len() + 1;
        *slot = Some((v, span));
    }
    let target = six(line, found, "rax_")?;
    let bad = |what: &str| {
        at(
            line,
            format!("jointtarget: expected its external axes [eax_a,..,eax_f] after the robot's axes, {what}"),
        )
    };
    let rest = code[from..].trim_start();
    let Some(rest) = rest.strip_prefix(',').map(str::trim_start) else {
        return Err(bad("not ','"));
    };
    if !rest.starts_with('[') {
        return Err(bad("not '['"));
    }
    let mut from = code.len() - rest.len() + 1;
    let mut external = Vec::with_capacity(6);
    for k in 0..6 {
        let name = format!("eax_{}", (b'a' + k as u8) as char);
        let (v, span) =
            number_at(code, from).ok_or_else(|| bad(&format!("{name} is not a number")))?;
        let rest = code[span.end..].trim_start();
        let sep = if k < 5 { ',' } else { ']' };
        if !rest.starts_with(sep) {
            return Err(bad(&format!("expected '{sep}' after {name}")));
        }
        from = code.len() - rest.len() + 1;
        external.push((v < 8.9e9).then_some((v, span)));
    }
    Ok(target.with_external(external))
}

/// The motion instruction (lower case) an arc welding instruction moves as (the *Application
/// manual, Arc and Arc Sensor*: `ArcL`, `ArcLStart`, `ArcLEnd` linear as `MoveL`, `ArcC`,
/// `ArcCStart`, `ArcCEnd` circular as `MoveC`, each with its seam and weld data after the
/// speed); any other as it is.
pub(super) fn as_move(first: &str) -> &str {
    match first {
        "arcl" | "arclstart" | "arclend" => "movel",
        "arcc" | "arccstart" | "arccend" => "movec",
        other => other,
    }
}

/// The targets of a motion statement (`MoveC`: its circle point then its end point), none for
/// a statement that is no motion; every motion outside the subset refused naming the line.
fn motion(s: &Statement, code: &str, first: &str, data: &Data) -> Result<Vec<JointTarget>> {
    let line = s.line;
    let name = &code[s.span.clone()].trim_start()[..first.len()];
    // An arc welding motion (its seam and weld data between the speed and the zone): the linear
    // or circular motion it is, the process on.
    let (first, process) = match as_move(first) {
        m if m != first => (m, 2),
        m => (m, 0),
    };
    let cartesian = matches!(first, "movel" | "movej" | "movec");
    if first != "moveabsj" && !cartesian {
        if !flow::is_motion(first) {
            return Ok(Vec::new());
        }
        let why = refusals::unfollowed(first);
        return Err(at(line, format!("{name}: {why}")));
    }
    // Past the name: an optional switch such as `\Conc`, then the target.
    let mut from = s.span.start + code[s.span.clone()].len()
        - code[s.span.clone()].trim_start().len()
        + name.len();
    let after_name = code[from..s.span.end].trim_start();
    if after_name.starts_with('\\') {
        let comma = after_name
            .find(',')
            .ok_or_else(|| at(line, format!("{name}: expected ',' after its switch")))?;
        from = s.span.end - after_name.len() + comma + 1;
    } else if let Some(rest) = after_name.strip_prefix(',') {
        from = s.span.end - rest.len();
    }
    let kind = if cartesian {
        "robtarget"
    } else {
        "jointtarget"
    };
    let named = |ident: &str| named::target(data, (line, name), (kind, cartesian), ident);
    if cartesian {
        let end = s.span.end - usize::from(code[..s.span.end].ends_with(';'));
        let args = &code[from..end];
        let points = if first == "movec" { 2 } else { 1 };
        let joined = arguments::switches_joined(args);
        let argument = arguments::top_level(&joined)
            .get(points)
            .map(|r| &joined[r.clone()]);
        let mut targets = cartesian::motion(
            line,
            (code, from, args),
            (points, process),
            &named,
            (&data.frames, &data.nums),
        )
        .map_err(|e| match e {
            stiffid_core::Error::Program { line, message } if !message.starts_with(name) => {
                at(line, format!("{name}: {message}"))
            }
            other => other,
        })?;
        let speed = match speed::speed(line, first, argument, &data.speeds)? {
            super::speed::Speed::Duration(_) if points == 2 => super::speed::Speed::Unread(format!("{name} \\T: the time of the whole circle, which stiffid does not share between its two points")),
            other => other,
        };
        for t in &mut targets {
            t.speed = speed.clone();
        }
        return Ok(targets);
    }
    let target_text = code[from..s.span.end].trim_start();
    if target_text.starts_with("[[") {
        return literal(line, code, from).map(|t| vec![joint(t)]);
    }
    let ident: String = target_text
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    let next = target_text[ident.len()..].trim_start();
    let element = (next.starts_with('{').then(|| next.find('}')).flatten())
        .filter(|&c| next[c + 1..].trim_start().starts_with([',', '\\']));
    if let (Some(close), false) = (element, ident.is_empty()) {
        let text = &target_text[..target_text.len() - next.len() + close + 1];
        return named(text).map(|t| vec![joint(t)]);
    }
    if ident.is_empty() || next.starts_with(['{', '(', '.']) {
        let what = match next.chars().next() {
            Some('(') => format!("{ident}(..), a function"),
            Some('{') => format!("{ident}{{..}}, an array element"),
            Some('.') => format!("{ident}.., a component"),
            _ => "an expression".to_string(),
        };
        return Err(at(line, format!("{name}: the target is {what} the controller computes; stiffid compensates literals and jointtargets declared in the module")));
    }
    let at = s.span.end - target_text.len();
    named(&ident).map(|t| vec![joint(at_reference(t, at..at + ident.len()))])
}

/// A `MoveAbsJ`'s target: a joint motion.
fn joint(target: JointTarget) -> JointTarget {
    JointTarget {
        speed: super::speed::Speed::Joint,
        ..target
    }
}

/// ABB RAPID (module docs).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rapid;

impl Rapid {
    /// The extensions of a task's modules in an ABB backup.
    pub(crate) const BACKUP: &'static [&'static str] = &["mod", "modx", "sys", "sysx", "prg"];
}

impl Controller for Rapid {
    type Flags = ConfData;
    const LANGUAGE: &'static Descriptor = &Descriptor {
        key: "rapid",
        title: "ABB RAPID",
        extensions: &["mod", "modx", "prg"],
        data_files: &[],
        motions: "MoveAbsJ to a jointtarget, MoveL, MoveJ or MoveC to a robtarget",
        joint_forms: "jointtarget",
        part_forms: Some("robtargets with a wobjdata equal to [workpiece]"),
        external_axes: AxisNames::Lettered("eax_"),
        unused_axis: " (9E9: not used)",
        zero_is_no_axis: false,
        // A module's name is not its file's: no line declares the file's.
        names: NameRules {
            declared_by: None,
            file: FileName::NotFile,
            max_length: 32,
            default_length: 32,
            reserved: names::RESERVED,
        },
        bound_comment: BoundComment::EndOfLine {
            marker: '!',
            statement: Some(';'),
        },
        motion_words: &["MoveJ ", "MoveL ", "MoveC ", "MoveAbsJ "],
        frame_numbers: (0, 0),
        axis_3_from_horizontal: false,
    };

    fn read(&self, text: &str) -> Result<Read> {
        read::targets(text, &super::Context::default())
    }
    fn read_in(&self, text: &str, context: &super::Context) -> Result<Read> {
        read::targets(text, context)
    }
    fn rotation(&self, n: &[f64]) -> UnitQuaternion<f64> {
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(n[3], n[4], n[5], n[6]))
    }
    /// The quaternion with a non-negative `q1`.
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64> {
        let q = r.quaternion();
        let s = if q.w < 0.0 { -1.0 } else { 1.0 };
        vec![p.x, p.y, p.z, s * q.w, s * q.i, s * q.j, s * q.k]
    }
    fn generator(&self) -> Option<&'static dyn Generator> {
        Some(&Rapid)
    }
    /// The modules of an ABB backup's task (`RAPID/TASK1/PROGMOD/*.mod`, `SYSMOD/*.sys`).
    fn backup_extensions(&self) -> &'static [&'static str] {
        Rapid::BACKUP
    }
}

/// `t` named at `reference` (bytes of the text) where no reference names it yet: a point an
/// assignment gave (`p2 := p1;`) stays named where the assignment names it, so that a second
/// value renames it there.
fn at_reference(t: JointTarget, reference: std::ops::Range<usize>) -> JointTarget {
    match t.point.as_ref().is_some_and(|p| p.reference.is_some()) {
        true => t,
        false => t.named_at(reference),
    }
}
