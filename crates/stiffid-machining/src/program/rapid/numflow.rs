//! `num` data a module assigns (`dz := 50;`, `dz := dz + 10;`, `Incr n;`, `Decr n;`,
//! `Add n, 5;`, `Clear n;`, *RAPID kernel*: assignments; *RAPID Instructions*), followed along
//! every path of the routine that assigns them: at a motion, the value the last assignments
//! before it give on every path (arithmetic of numbers and `num` data the module states, module
//! `num`). Where the paths disagree (an assignment in one branch only), inside a loop that
//! assigns it (on every pass after the first it holds the last pass's value), at a routine's
//! start or after a call of a routine that assigns it (the run's), in a routine with a `GOTO`,
//! or set otherwise (a component, a procedure's parameter, a read from the pendant), its value
//! is the run's: the motion that reads it is refused naming the line that sets it. A datum whose
//! name a `FOR` loop's variable takes is not followed (the loop's variable hides it).

use super::{calls, first_word, is_header, Statement};
use std::collections::{BTreeMap, HashMap, HashSet};

/// The values in force of the `num` data a module assigns (lower-case name), along the path.
pub(super) type Values = BTreeMap<String, Result<f64, String>>;

/// The instructions that set their first argument from the ones after it.
const STEPS: &[&str] = &["incr", "decr", "add", "clear"];

/// The module's `num` data followed along its paths (module docs): each one's assignments (line
/// and routine), its declared value, and the routines with a `GOTO`.
#[derive(Debug, Default)]
pub(super) struct Renum {
    names: HashMap<String, Vec<(u64, String)>>,
    base: HashMap<String, Result<f64, String>>,
    jumping: HashSet<String>,
    /// Every datum a statement of the module sets, with the first such line.
    pub(super) set_on: HashMap<String, u64>,
}

impl Renum {
    /// The `num` data of the module `code` (its `statements`) that only whole assignments and
    /// `Incr`/`Decr`/`Add`/`Clear` in its `PROC`s set (`set`: every statement that sets one,
    /// module `num`), their values as the module declares them (`declared`, its `constants`
    /// never set); every other datum set, the run's wherever it is read.
    pub(super) fn of(
        (code, statements): (&str, &[Statement]),
        (declared, constants): (&HashMap<String, Result<f64, String>>, &[String]),
        set: &[(String, u64)],
    ) -> Renum {
        let mut out = Renum::default();
        let (mut routine, mut plain) = (String::new(), false);
        let mut whole: Vec<(String, u64, String)> = Vec::new();
        let mut set: Vec<(String, u64)> = set.to_vec();
        // A `FOR` loop's variable hides a datum of its name within the loop (module `unroll`).
        let mut loop_vars: Vec<String> = Vec::new();
        for s in statements {
            let body = &code[s.span.clone()];
            let first = first_word(body);
            if let Some(name) = calls::routine(body) {
                routine = name.to_ascii_lowercase();
                plain = calls::procedure(body).is_some();
                continue;
            }
            if first == "for" {
                let var = body.split_whitespace().nth(1).unwrap_or("");
                loop_vars.push(var.to_ascii_lowercase());
            }
            match first.as_str() {
                "error" | "undo" | "backward" if is_header(body) => plain = false,
                _ if jumps(body, &first, s.line) => _ = out.jumping.insert(routine.clone()),
                _ => {}
            }
            if let Some(at) = (first == "if" && !is_header(body))
                .then(|| super::flow::compact_instruction(body))
                .flatten()
            {
                let inner = &body[at..];
                if let Some((name, _)) = set_here(inner, &first_word(inner)) {
                    set.push((name, s.line));
                }
                continue;
            }
            if let (Some((name, _)), true) = (set_here(body, &first), plain) {
                whole.push((name, s.line, routine.clone()));
            }
        }
        let other: HashSet<&String> = (set.iter())
            .filter(|(n, l)| !whole.iter().any(|(m, k, _)| m == n && k == l))
            .map(|(n, _)| n)
            .collect();
        for (name, line, r) in &whole {
            let followed = !other.contains(name) && !constants.contains(name);
            if let (true, Some(Ok(_))) = (followed, declared.get(name)) {
                out.names
                    .entry(name.clone())
                    .or_default()
                    .push((*line, r.clone()));
            }
        }
        for (name, line) in
            (set.iter().map(|(n, l)| (n, l))).chain(whole.iter().map(|(n, l, _)| (n, l)))
        {
            out.set_on.entry(name.clone()).or_insert(*line);
            if constants.contains(name) || out.base.contains_key(name) {
                continue;
            }
            let value = match (out.names.contains_key(name), declared.get(name)) {
                (true, Some(v)) => v.clone(),
                _ => Err(format!("num {name} is set on line {line}, so its value is the controller's as the module runs")),
            };
            out.base.insert(name.clone(), value);
        }
        for var in &loop_vars {
            out.names.remove(var);
            out.base.remove(var);
        }
        out
    }

    /// The `nums` with the `values` in force laid over the declared ones of the data followed.
    pub(super) fn lay(&self, values: &Values, nums: &mut HashMap<String, Result<f64, String>>) {
        for (name, base) in &self.base {
            let v = values.get(name).unwrap_or(base);
            nums.insert(name.clone(), v.clone());
        }
    }

    /// The datum `name` set by another module of the task (`why`): the run's wherever it is read.
    pub(super) fn set_elsewhere(&mut self, name: &str, why: &str) {
        self.names.remove(name);
        self.base.insert(name.to_string(), Err(why.to_string()));
    }

    /// Whether the module sets no `num`.
    pub(super) fn is_empty(&self) -> bool {
        self.base.is_empty()
    }

    /// The values at the start of `routine` (lower case) on `line`: every datum followed holds
    /// what the run set before (a routine runs again, `main` in every cycle).
    pub(super) fn at_start(&self, routine: &str, line: u64) -> Values {
        (self.names.iter())
            .map(|(name, list)| {
                let why = format!("num {name} is set on line {}, and at the start of the routine on line {line} ({routine}) it holds what the run set before; set it in the routine before the motion", list[0].0);
                (name.clone(), Err(why))
            })
            .collect()
    }

    /// The values after a call of a routine on `line` from `routine`: a datum another routine
    /// assigns is the run's (`values` keeps the others).
    pub(super) fn after_call(
        &self,
        (called, line): (&str, u64),
        routine: &str,
        values: &mut Values,
    ) {
        for (name, list) in &self.names {
            if let Some((l, _)) = list.iter().find(|(_, r)| r != routine) {
                values.insert(name.clone(), Err(format!("num {name} is set on line {l}, outside this routine, and the call of {called} on line {line} may run it: its value after the call is the run's")));
            }
        }
    }

    /// The values at the start of a loop whose body is `statements[k + 1..]` up to its end
    /// (`code`): a datum the body sets holds the last pass's value on every pass after the first.
    pub(super) fn at_loop(
        &self,
        (code, statements): (&str, &[Statement]),
        k: usize,
        values: &mut Values,
    ) {
        let open = statements[k].line;
        let mut depth = 0;
        for s in &statements[k..] {
            let body = &code[s.span.clone()];
            let first = first_word(body);
            match first.as_str() {
                "while" | "for" => depth += 1,
                "endwhile" | "endfor" => depth -= 1,
                _ => {}
            }
            if depth == 0 {
                break;
            }
            if let Some((name, _)) =
                set_here(body, &first).filter(|(n, _)| self.names.contains_key(n))
            {
                let why = format!("num {name} is set on line {} inside the loop on line {open}: on every pass after the first it holds the last pass's value; set it before the loop", s.line);
                values.insert(name, Err(why));
            }
        }
    }

    /// Reads the statement `body` on `line` (first word `first`) of `routine`: the value it gives
    /// a datum followed, from the `values` in force and the other `nums`, into `values`.
    pub(super) fn statement(
        &self,
        (body, first, line): (&str, &str, u64),
        routine: &str,
        nums: &HashMap<String, Result<f64, String>>,
        values: &mut Values,
    ) {
        let Some((name, expr)) = set_here(body, first).filter(|(n, _)| self.names.contains_key(n))
        else {
            return;
        };
        let value = match self.jumping.contains(routine) {
            true => Err(format!("num {name} is set on line {line} in a routine with a GOTO: which statement ran before the motion is the run's")),
            false => super::num::value(&expr, &|n| values.get(n).or_else(|| nums.get(n)).cloned())
                .map_err(|why| format!("num {name} is set on line {line} to a value the run gives: {why}")),
        };
        values.insert(name, value);
    }
}

/// Whether the statement `body` on `line` (first word `first`) jumps or is a label one may jump
/// to: a `GOTO`, also in a compact `IF`, or a label (`again:`).
pub(super) fn jumps(body: &str, first: &str, line: u64) -> bool {
    let t = body.trim();
    let label = t
        .strip_suffix(':')
        .is_some_and(|l| !l.is_empty() && l.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'));
    first == "goto"
        || label
        || (first == "if" && super::flow::in_compact_if(body, line, |w| w == "goto").is_some())
}

/// The `num` a statement sets (lower case) and the expression of its new value, for a whole
/// assignment (`n := expr;`) or `Incr`, `Decr`, `Add`, `Clear`; `None` for any other.
fn set_here(body: &str, first: &str) -> Option<(String, String)> {
    let t = body.trim_start().trim_end().trim_end_matches(';');
    let rest = t.get(first.len()..)?.trim_start();
    if STEPS.contains(&first) {
        let mut args = rest.splitn(2, ',');
        let name = args.next()?.trim().to_ascii_lowercase();
        let plain = name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        let by = args.next().map(str::trim).unwrap_or("");
        let expr = match first {
            "incr" => format!("{name} + 1"),
            "decr" => format!("{name} - 1"),
            "add" => format!("{name} + ({by})"),
            _ => "0".to_string(),
        };
        return (plain && !name.is_empty()).then_some((name, expr));
    }
    let expr = rest.strip_prefix(":=")?;
    let name = t[..first.len()].to_ascii_lowercase();
    let plain = name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    plain.then(|| (name, expr.trim().to_string()))
}
