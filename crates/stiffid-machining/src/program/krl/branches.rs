//! Branches whose way the files decide: an `IF` whose condition, a `SWITCH` whose value (and
//! every `CASE`'s) reads only numbers known where it is ([`super::numbers`]) runs one branch
//! only, the one the controller takes; its other branches are never run, so their lines are
//! passed over as they are (not compensated, written back as read). A branch that reads a value
//! only the run gives is read on every path ([`crate::program::paths`]).

use super::numbers::Typed;
use std::collections::HashMap;

/// A branch construct open: decided by the files (`fixed`), or read on every path.
#[derive(Debug, Clone, Copy)]
struct Open {
    /// Whether the files decide it.
    fixed: bool,
    /// Whether the lines read now run (for a decided construct).
    taking: bool,
    /// Whether a branch of it ran already (or, in lines that never run, none will).
    taken: bool,
    /// The value a decided `SWITCH` selects on.
    value: f64,
    /// Its line and word.
    at: (u64, &'static str),
}

/// The branch constructs open in a routine, outermost first (module docs).
#[derive(Debug, Default)]
pub(super) struct Branches {
    open: Vec<Open>,
    /// Per `SWITCH` line, its `CASE` lines' selectors (`1, 2`).
    cases: HashMap<u64, Vec<String>>,
}

/// Evaluates an expression where it is read.
pub(super) type Eval<'a> = &'a dyn Fn(&str) -> Result<Typed, String>;

impl Branches {
    /// The branches of the module `text`.
    pub(super) fn new(text: &str) -> Self {
        let (mut cases, mut switches) = (HashMap::<u64, Vec<String>>::new(), Vec::new());
        for (line, _, l) in crate::program::lines(text) {
            let code = l.split(';').next().unwrap_or("").trim();
            let first = super::declare::words(code)
                .into_iter()
                .next()
                .unwrap_or_default();
            match first.as_str() {
                "SWITCH" => switches.push(line),
                "ENDSWITCH" => _ = switches.pop(),
                "CASE" => {
                    if let Some(s) = switches.last() {
                        let labels = code[4..].split(',').map(|c| c.trim().to_string());
                        cases.entry(*s).or_default().extend(labels);
                    }
                }
                _ => {}
            }
        }
        Branches {
            open: Vec::new(),
            cases,
        }
    }

    /// Whether the lines read now never run (a branch the files decide against).
    pub(super) fn dead(&self) -> bool {
        self.open.iter().any(|o| o.fixed && !o.taking)
    }

    /// A routine ends (`line`, the next `DEF` or the module's end): nothing open.
    ///
    /// # Errors
    /// Naming the line of a construct the files decide that is still open: its lines after it
    /// would be passed over (the controller refuses a module with it).
    pub(super) fn close_all(&mut self) -> stiffid_core::Result<()> {
        let open = self.open.iter().find(|o| o.fixed).map(|o| o.at);
        self.open.clear();
        match open {
            Some((line, word)) => Err(crate::program::at(line, format!("{word} without its END{word} before the routine ends (the controller refuses the module): close it"))),
            None => Ok(()),
        }
    }

    /// Whether the line (number `line`, code `code`, first word `first`) is taken here, not read
    /// further: a line of a branch that never runs, or a word of a construct the files decide.
    pub(super) fn pass(&mut self, line: u64, first: &str, code: &str, eval: Eval) -> bool {
        let dead = self.open.iter().any(|o| o.fixed && !o.taking);
        let word = if first == "IF" { "IF" } else { "SWITCH" };
        let never = Open {
            fixed: true,
            taking: false,
            taken: true,
            value: 0.0,
            at: (line, word),
        };
        let decided = |value: f64, taking: bool| Open {
            fixed: true,
            taking,
            taken: taking,
            value,
            at: (line, word),
        };
        let open = match first {
            "IF" | "SWITCH" if dead => Some(never),
            "IF" => eval(&condition(code))
                .ok()
                .map(|(v, _)| decided(v, v != 0.0)),
            "SWITCH" => self.switch(line, code, eval).map(|v| decided(v, false)),
            _ => None,
        };
        if let Some(o) = open {
            self.open.push(o);
            return true;
        }
        let top = self.open.last_mut().filter(|o| o.fixed);
        match (first, top) {
            ("IF" | "SWITCH", _) => {
                self.open.push(Open {
                    fixed: false,
                    ..never
                });
                false
            }
            ("ENDIF" | "ENDSWITCH", _) => self.open.pop().is_some_and(|o| o.fixed),
            ("ELSE" | "DEFAULT", Some(o)) => {
                (o.taking, o.taken) = (!o.taken, true);
                true
            }
            ("CASE", Some(o)) => {
                let hit =
                    (code.trim()[4..].split(',')).any(|c| eval(c).is_ok_and(|(v, _)| v == o.value));
                o.taking = !o.taken && hit;
                o.taken |= hit;
                true
            }
            _ => dead,
        }
    }

    /// The value a `SWITCH` (on `line`, its `code`) selects on, where it and every `CASE`'s
    /// selector are known.
    fn switch(&self, line: u64, code: &str, eval: Eval) -> Option<f64> {
        let v = eval(code.trim()[6..].trim()).ok()?.0;
        let cases = self.cases.get(&line)?;
        cases.iter().all(|c| eval(c).is_ok()).then_some(v)
    }
}

/// The condition of an `IF` line (`IF a == 1 THEN`): between `IF` and `THEN`.
fn condition(code: &str) -> String {
    let t = code.trim();
    let rest = &t[2..];
    let upper = rest.to_ascii_uppercase();
    match upper.rfind("THEN") {
        Some(at) => rest[..at].to_string(),
        None => rest.to_string(),
    }
}
