//! Calls and returns: LinuxCNC's `O<label> call [..]` / `endsub` / `return`, FANUC's and
//! Haas's `M98 P<n> [L<count>]` / `M99`, Haas's `M97 P<n> [L<count>]`, `G65 P<n> [L<count>]
//! A.. B..` (module docs of [`super`]).

use super::expr::{self, Cursor, Flavour};
use super::{shown, Frame, Kind, Run, MAX_DEPTH};
use stiffid_core::setup::GcodeDialect;

type Outcome = std::result::Result<(), String>;

/// Whether `code` (comments out) has an `M97`, `M98`, `M99` or `G65` word.
pub(super) fn call_words(code: &str) -> bool {
    let upper = code.to_ascii_uppercase();
    let b = upper.as_bytes();
    (0..b.len()).any(|i| {
        let word = |l: u8| b[i] == l && (i == 0 || !b[i - 1].is_ascii_alphabetic());
        (word(b'M') || word(b'G')) && {
            let n = crate::text::number_at(&upper, i + 1).map(|(v, _)| v);
            matches!(
                (b[i], n),
                (b'M', Some(97.0 | 98.0 | 99.0)) | (b'G', Some(65.0))
            )
        }
    })
}

/// G65's argument letters and their locals (argument specification I).
const ARGUMENTS: [(char, u32); 21] = [
    ('A', 1),
    ('B', 2),
    ('C', 3),
    ('I', 4),
    ('J', 5),
    ('K', 6),
    ('D', 7),
    ('E', 8),
    ('F', 9),
    ('H', 11),
    ('M', 13),
    ('Q', 17),
    ('R', 18),
    ('S', 19),
    ('T', 20),
    ('U', 21),
    ('V', 22),
    ('W', 23),
    ('X', 24),
    ('Y', 25),
    ('Z', 26),
];

/// A call (`M98`, `M97`, `G65`) or return (`M99`) in the block's `words`, made: `Ok(true)`.
pub(super) fn call(
    run: &mut Run,
    words: &[(char, f64)],
    line: u64,
) -> std::result::Result<bool, String> {
    let g65 = words.iter().any(|&(l, v)| l == 'G' && v == 65.0);
    let m = words
        .iter()
        .find(|&&(l, v)| l == 'M' && [97.0, 98.0, 99.0].contains(&v))
        .map(|w| w.1);
    if !g65 && m.is_none() {
        return Ok(false);
    }
    if run.flavour == Flavour::LinuxCnc {
        return Err("M97, M98, M99 and G65: FANUC's and Haas's subprogram calls, which this dialect reads as O-words (O100 call); the setup's [controller] dialect is \"linuxcnc\"".into());
    }
    let p = words.iter().find(|w| w.0 == 'P').map(|w| w.1);
    let l = words.iter().find(|w| w.0 == 'L').map(|w| w.1);
    let others: Vec<char> = words
        .iter()
        .map(|w| w.0)
        .filter(|c| !matches!(c, 'N' | 'P' | 'L' | 'M' | 'G'))
        .collect();
    if g65 {
        let args = macro_arguments(words)?;
        return enter(run, (Kind::Macro, p, l, line), &args, false).map(|_| true);
    }
    if !others.is_empty() || words.iter().filter(|w| matches!(w.0, 'G' | 'M')).count() > 1 {
        return Err(format!("M{}: a subprogram call or return with other words in its block: write it on a block of its own", m.unwrap_or(0.0)));
    }
    match m {
        Some(99.0) if p.is_some() => {
            Err("M99 P: a return to a block number, which stiffid does not follow".into())
        }
        Some(99.0) => fanuc_return(run),
        Some(97.0) if run.dialect != Some(GcodeDialect::Haas) => Err(
            "M97: Haas's local subprogram call; state [controller] dialect = \"haas\" in the setup"
                .into(),
        ),
        Some(v) => enter(run, (Kind::Shared, p, l, line), &[], v == 97.0).map(|_| true),
        None => Ok(false),
    }
}

/// G65's arguments as locals.
fn macro_arguments(words: &[(char, f64)]) -> std::result::Result<Vec<(u32, f64)>, String> {
    let mut args = Vec::new();
    for &(letter, value) in words {
        if matches!(letter, 'G' | 'P' | 'L' | 'N') {
            continue;
        }
        let Some(&(_, n)) = ARGUMENTS.iter().find(|a| a.0 == letter) else {
            return Err(format!(
                "G65 {letter}: not an argument of a macro call (A-F, H, I-K, M, Q-Z)"
            ));
        };
        if args.iter().any(|(k, _)| *k == n) {
            return Err(format!(
                "G65 {letter} twice: argument specification II (repeated I J K) is not read"
            ));
        }
        args.push((n, value));
    }
    Ok(args)
}

/// A call of `kind` to the program (`M98`, `G65`) or block (`M97`) `P`, `L` times.
fn enter(
    run: &mut Run,
    (kind, p, l, line): (Kind, Option<f64>, Option<f64>, u64),
    args: &[(u32, f64)],
    local: bool,
) -> Outcome {
    let Some(p) = p.filter(|p| p.fract() == 0.0 && *p >= 0.0) else {
        return Err("a call without its program number P".into());
    };
    let times = match l {
        None => 1,
        Some(l) if l.fract() == 0.0 && (0.0..=9999.0).contains(&l) => l as u32,
        Some(l) => return Err(format!("L{l}: expected a repeat count 0..9999")),
    };
    let p = p as u32;
    if kind != Kind::Macro && !local && p > 9999 && run.dialect == Some(GcodeDialect::Fanuc) {
        return Err(format!("M98 P{p}: FANUC reads the digits of P beyond the last four as a repeat count; write M98 P{} L{}", p % 10000, p / 10000));
    }
    let (start, program) = match local {
        true => {
            let (from, to) = run.program_range();
            let found = (from..run.codes.len().max(to))
                .find(|&i| super::line::sequence(&run.codes[i]).0 == Some(p));
            let at = found.ok_or_else(|| format!("M97 P{p}: no block N{p} in this file"))?;
            (at, run.stack.last().map_or(0, |f| f.program))
        }
        false => {
            let at = *run.programs.get(&p).ok_or_else(|| format!("P{p}: the program O{p} is not in this file (a program in the controller's memory, which stiffid cannot read): put it in the file after the main program's M30"))?;
            (at + 1, at)
        }
    };
    if times == 0 {
        run.pc += 1;
        return Ok(());
    }
    push(
        run,
        Frame {
            line,
            ret: run.pc + 1,
            kind: kind.clone(),
            start,
            again: times - 1,
            program,
        },
    )?;
    if kind == Kind::Macro {
        run.store.push(args);
    }
    run.pc = start;
    Ok(())
}

fn push(run: &mut Run, frame: Frame) -> Outcome {
    if run.stack.len() >= MAX_DEPTH {
        return Err(format!("calls nested deeper than {MAX_DEPTH} (a recursion that does not end?); the controller refuses them too"));
    }
    run.stack.push(frame);
    Ok(())
}

/// `M99`: back to the caller (or the called part again, for an `L` count).
fn fanuc_return(run: &mut Run) -> std::result::Result<bool, String> {
    let Some(f) = run.stack.last_mut() else {
        return Err("M99 in the main program: the controller runs the program again from its start, forever; end it with M30".into());
    };
    if matches!(f.kind, Kind::Sub(_)) {
        return Err("M99 in a LinuxCNC subprogram: end it with its endsub".into());
    }
    if f.again > 0 {
        f.again -= 1;
        run.pc = f.start;
        return Ok(true);
    }
    if let Some(f) = run.stack.pop() {
        if f.kind == Kind::Macro {
            run.store.pop();
        }
        run.pc = f.ret;
    }
    Ok(true)
}

impl Run<'_> {
    /// `O<label> call [a] [b] ..`: the sub with `#1`, `#2`, .. set (the others 0).
    pub(super) fn o_call(&mut self, label: &str, rest: &str) -> Outcome {
        let mut c = Cursor::new(rest, 0);
        let mut args = Vec::new();
        while c.peek().is_some() {
            let v = expr::real_value(&mut c, &self.store, self.flavour)?;
            args.push((args.len() as u32 + 1, v));
            if args.len() > 30 {
                return Err(format!("{} call: more than 30 arguments", shown(label)));
            }
        }
        let Some(&start) = self.subs.get(label) else {
            return Err(format!("{0} call: no {0} sub in this file (a subroutine file of the controller's, which stiffid cannot read): put the sub in the file", shown(label)));
        };
        let line = self.lines[self.pc].0;
        push(
            self,
            Frame {
                line,
                ret: self.pc + 1,
                kind: Kind::Sub(label.to_string()),
                start: start + 1,
                again: 0,
                program: 0,
            },
        )?;
        self.store.push(&args);
        self.pc = start + 1;
        Ok(())
    }

    /// `O<label> endsub` or `return`: back to the caller.
    pub(super) fn o_return(&mut self, label: &str) -> Outcome {
        if !self.in_call(&Kind::Sub(label.to_string())) {
            return Err(format!(
                "{}: a return from a sub that was not called",
                shown(label)
            ));
        }
        if let Some(f) = self.stack.pop() {
            self.store.pop();
            self.pc = f.ret;
        }
        Ok(())
    }
}
