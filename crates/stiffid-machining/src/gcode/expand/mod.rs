//! A program with subprograms, parameters and control flow expanded into the blocks the
//! controller runs, in the order it runs them (docs/programs/gcode.md, "Subprograms,
//! parameters and control flow"):
//! - LinuxCNC O-words (manual, "O Codes"): `O.. sub` .. `endsub` called by `O.. call [..]`
//!   (arguments `#1`..`#30`), `return`, `if`/`elseif`/`else`/`endif`, `while`/`endwhile`,
//!   `do`/`while`, `break`, `continue`, `repeat [n]`/`endrepeat`.
//! - FANUC and Haas: `M98 P<n> [L<count>]` to the program `O<n>` of the same file, returning at
//!   `M99`; Haas's `M97 P<n> [L<count>]` to the block `N<n>` of the file; `G65 P<n> [L<count>]
//!   A.. B..` to the macro `O<n>` with its arguments as locals (`A`=`#1`, `B`=`#2`, `C`=`#3`,
//!   `I`=`#4`, ..: argument specification I); `IF [..] GOTO n`, `IF [..] THEN #i = ..`,
//!   `GOTO n`, `WHILE [..] DO m` .. `END m` (module `flow`).
//! - Parameters and expressions (modules `params`, `expr`): each block's values written as
//!   numbers, assignments applied after their block.
//!
//! The expanded text maps each of its lines to the line of the program it comes from: points,
//! warnings and refusals name the program's lines. Calls nest at most [`MAX_DEPTH`] deep
//! (recursion included) and at most [`MAX_EXECUTED`] blocks are executed (a loop that does not
//! end): past either, refused naming the line. A program that needs none of this is not
//! expanded (`None`): it is read and written as found.

mod calls;
mod expr;
mod flow;
mod line;
mod params;

use super::at;
use expr::Flavour;
use line::{classify, code, Stmt};
use std::collections::{HashMap, HashSet};
use stiffid_core::setup::GcodeDialect;
use stiffid_core::Result;

/// The deepest nesting of calls (LinuxCNC's `INTERP_SUB_ROUTINE_LEVELS`, FANUC's and Haas's
/// subprogram nesting).
pub(crate) const MAX_DEPTH: usize = 10;
/// The most blocks executed while expanding (every line run, loops counted each time).
pub(crate) const MAX_EXECUTED: usize = 1_000_000;

/// The program as the controller runs it: the text of the blocks executed, and for each of its
/// lines (1-based, in order) the program's line.
pub(crate) struct Expanded {
    pub(crate) text: String,
    pub(crate) lines: Vec<u64>,
}

/// A call in progress.
struct Frame {
    /// The line of the call (for messages), and where execution goes on after the return.
    line: u64,
    ret: usize,
    kind: Kind,
    /// Where the called part starts (again for an `L` count), and the times it runs again.
    start: usize,
    again: u32,
    /// The first line of the program the call runs in (its `N` numbers).
    program: usize,
}

#[derive(Clone, PartialEq)]
enum Kind {
    /// LinuxCNC's `O<label> call`: returns at its `endsub` or `return`, with its own locals.
    Sub(String),
    /// `M98` or `M97`: returns at `M99`, sharing the caller's locals.
    Shared,
    /// `G65`: returns at `M99`, with its own locals.
    Macro,
}

struct Run<'a> {
    lines: Vec<(u64, &'a str)>,
    codes: Vec<String>,
    pc: usize,
    text: String,
    map: Vec<u64>,
    store: params::Store,
    flavour: Flavour,
    dialect: Option<GcodeDialect>,
    stack: Vec<Frame>,
    executed: usize,
    /// LinuxCNC `repeat` counts in force, per call depth and label.
    repeats: HashMap<(usize, String), f64>,
    /// FANUC program numbers and the line index of each, LinuxCNC subs by label.
    programs: HashMap<u32, usize>,
    subs: HashMap<String, usize>,
    /// The labels of LinuxCNC `do` loops (their `while` ends them).
    do_labels: HashSet<String>,
    /// The loops and branches whose end was found when they were first entered (a loop or
    /// branch without its end is refused naming it, module `flow`).
    ends_found: HashSet<usize>,
    /// The main program's own number line (`O1000` before its first block).
    own_header: Option<usize>,
    ended: bool,
}

/// The program `text` expanded (module docs) for `dialect`, or `None` when it has no
/// subprogram, parameter or control flow.
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line: a construct the dialect does not read, a
/// call to a subprogram not in the file, a parameter the controller sets at run time or read
/// before it is set, calls nested deeper than [`MAX_DEPTH`], more than [`MAX_EXECUTED`]
/// blocks executed, a malformed expression.
pub(crate) fn expand(text: &str, dialect: Option<GcodeDialect>) -> Result<Option<Expanded>> {
    let flavour = match dialect {
        Some(GcodeDialect::LinuxCnc) => Flavour::LinuxCnc,
        Some(GcodeDialect::Fanuc | GcodeDialect::Haas) => Flavour::Fanuc,
        Some(GcodeDialect::Grbl) | None => Flavour::Unstated,
    };
    let lines: Vec<(u64, &str)> = crate::text::lines(text).map(|(n, _, l)| (n, l)).collect();
    let codes: Vec<String> = lines.iter().map(|(_, l)| code(l)).collect();
    let Some(first) = needs(&codes) else {
        return Ok(None);
    };
    if dialect == Some(GcodeDialect::Grbl) {
        return Err(at(lines[first].0, "grbl reads no parameters, expressions, subprograms or control flow (the setup's [controller] dialect is \"grbl\"); have the post write plain blocks".into()));
    }
    let mut run = Run {
        lines,
        codes,
        pc: 0,
        text: String::with_capacity(text.len()),
        map: Vec::new(),
        store: params::Store::new(flavour),
        flavour,
        dialect,
        stack: Vec::new(),
        executed: 0,
        repeats: HashMap::new(),
        programs: HashMap::new(),
        subs: HashMap::new(),
        do_labels: HashSet::new(),
        ends_found: HashSet::new(),
        own_header: None,
        ended: false,
    };
    run.scan();
    run.run()?;
    Ok(Some(Expanded {
        text: run.text,
        lines: run.map,
    }))
}

/// The index of the first line that needs expanding, if any: a `#` or `[` outside comments, an
/// O-word or FANUC statement, `M97`/`M98`/`M99`/`G65`.
fn needs(codes: &[String]) -> Option<usize> {
    let none = params::Store::new(Flavour::Unstated);
    codes.iter().position(|c| {
        if c.contains(['#', '[']) {
            return true;
        }
        match classify(c, &none, Flavour::Unstated) {
            Ok(Stmt::Block | Stmt::Header(_)) => calls::call_words(c),
            _ => true,
        }
    })
}

impl Run<'_> {
    /// The program numbers, subs and `do` labels of the file.
    fn scan(&mut self) {
        let mut blocks = false;
        for (i, c) in self.codes.iter().enumerate() {
            match classify(c, &self.store, self.flavour) {
                Ok(Stmt::Header(n)) => {
                    if !blocks && self.own_header.is_none() {
                        self.own_header = Some(i);
                    }
                    self.programs.entry(n).or_insert(i);
                }
                Ok(Stmt::OWord { label, keyword, .. }) => match keyword.as_str() {
                    "sub" => {
                        self.subs.entry(label).or_insert(i);
                    }
                    "do" => {
                        self.do_labels.insert(label);
                    }
                    _ => {}
                },
                _ => {}
            }
            blocks |= !c.trim().is_empty() && !c.trim_start().starts_with('%');
        }
    }

    /// Executes the program from its first line (module docs).
    fn run(&mut self) -> Result<()> {
        while self.pc < self.lines.len() && !self.ended {
            self.executed += 1;
            let line = self.lines[self.pc].0;
            if self.executed > MAX_EXECUTED {
                return Err(self.err(line, format!("more than {MAX_EXECUTED} blocks executed: a loop that does not end, or a program too long to expand")));
            }
            self.step().map_err(|m| self.err(line, m))?;
        }
        if let Some(f) = self.stack.last() {
            let end = match f.kind {
                Kind::Sub(_) => "its endsub",
                _ => "M99",
            };
            return Err(at(
                f.line,
                format!("the subprogram called here runs to the end of the file without {end}"),
            ));
        }
        Ok(())
    }

    /// The line at `pc` executed: `pc` moved on.
    fn step(&mut self) -> std::result::Result<(), String> {
        let pc = self.pc;
        let code = self.codes[pc].clone();
        match classify(&code, &self.store, self.flavour)? {
            Stmt::OWord {
                label,
                keyword,
                rest,
            } => self.o_word(&label, &keyword, rest),
            Stmt::Header(n) => self.header(n),
            Stmt::Block => self.block(),
            other => self.fanuc(other),
        }
    }

    /// A program number line reached.
    fn header(&mut self, n: u32) -> std::result::Result<(), String> {
        if self.own_header == Some(self.pc) {
            self.emit(self.pc, self.lines[self.pc].1.to_string());
            self.pc += 1;
            return Ok(());
        }
        if self.stack.is_empty() {
            // The main program ends where the file's next program starts.
            self.ended = true;
            return Ok(());
        }
        Err(format!(
            "the subprogram runs into the program O{n} without M99"
        ))
    }

    /// A block: its values substituted, its assignments applied, a call or return made, or it
    /// written to the expanded text.
    fn block(&mut self) -> std::result::Result<(), String> {
        let (n, l) = self.lines[self.pc];
        if l.trim_start().starts_with('%') {
            // The tape's mark: a second one ends the program (LinuxCNC, FANUC).
            self.ended = !self.map.is_empty();
            self.emit(self.pc, l.to_string());
            self.pc += 1;
            return Ok(());
        }
        let sub = line::substitute(l, &self.store, self.flavour)?;
        for (p, value) in &sub.assignments {
            self.store.set(p, *value)?;
        }
        if calls::call(self, &sub.words, n)? {
            return Ok(());
        }
        let ends = sub
            .words
            .iter()
            .any(|(l, v)| *l == 'M' && (*v == 2.0 || *v == 30.0));
        if !sub.text.trim().is_empty() {
            self.emit(self.pc, sub.text);
        }
        self.ended = ends;
        self.pc += 1;
        Ok(())
    }

    fn emit(&mut self, pc: usize, text: String) {
        self.text.push_str(&text);
        self.text.push('\n');
        self.map.push(self.lines[pc].0);
    }

    /// The error on `line` with the calls it is in.
    fn err(&self, line: u64, message: String) -> stiffid_core::Error {
        let calls: Vec<String> = self
            .stack
            .iter()
            .rev()
            .map(|f| f.line.to_string())
            .collect();
        match calls.is_empty() {
            true => at(line, message),
            false => at(
                line,
                format!(
                    "{message} (in the subprogram called on line {})",
                    calls.join(", called on line ")
                ),
            ),
        }
    }
}

/// An O-word's label as written: `O100`, `O<name>`.
fn shown(label: &str) -> String {
    match label
        .chars()
        .all(|c| c.is_ascii_digit() || c == '.' || c == '-')
    {
        true => format!("O{label}"),
        false => format!("O<{label}>"),
    }
}

#[cfg(test)]
mod tests;
