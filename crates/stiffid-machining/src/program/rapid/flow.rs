//! RAPID's program flow around motions (ABB, *Technical reference manual - RAPID Instructions,
//! Functions and Data types*: `IF`, `WHILE`, `FOR`, `TEST`, `GOTO`, and the `ERROR` handler of
//! *RAPID overview*): which words are motions, the constructs open at a statement, and the
//! routine's jumps (a `GOTO`, or a `RETURN`, `EXIT`, `ExitCycle` or `RAISE` a construct holds),
//! which the reader refuses where a state it follows would depend on them (module `read`).

use crate::program::at;
use stiffid_core::Result;

/// The constructs open around a statement of the routine being read, and its `GOTO`s.
#[derive(Debug, Default)]
pub(super) struct Flow {
    /// Each open construct's name as RAPID writes it (`WHILE`) and its line, outermost first.
    open: Vec<(&'static str, u64)>,
    /// The routine's jumps: each `GOTO`, and each `RETURN`, `EXIT`, `ExitCycle` or `RAISE` a
    /// construct holds (it may skip the motions after it), as written, with its line.
    jumps: Vec<(String, u64)>,
}

/// Whether a word (lower case) names a motion instruction (*RAPID Instructions* and the process
/// options' manuals): every `Move*` (a routine of the cell's named so is taken as one too),
/// `SearchL`/`SearchC`/`SearchExtJ`, `TriggL`/`TriggJ`/`TriggC` (and their `IOs` forms), the
/// arc welding `ArcL*`/`ArcC*`, spot welding `SpotL`/`SpotJ`/`SpotML`/`SpotMJ`, painting
/// `PaintL`/`PaintC`, continuous application `CapL`/`CapC`, dispensing `DispL`/`DispC`; the
/// motions whose path the program does not hold: Externally Guided Motion's `EGMRunJoint`,
/// `EGMRunPose`, `EGMMoveL`, `EGMMoveC` (*Application manual - Externally Guided Motion*), the
/// independent axes' `IndAMove`/`IndCMove`/`IndDMove`/`IndRMove`, `ContactL`, and the recorded
/// path's `PathRecMoveBwd`/`PathRecMoveFwd`/`StepBwdPath`, and Force Control's pressing motions
/// `FCPress1LStart`, `FCPressL`, `FCPressC`, `FCPressEnd`, `FCPressLEnd` (*Application manual -
/// Force control*: the path follows the contact force).
pub(super) fn is_motion(word: &str) -> bool {
    word.starts_with("move")
        || word.starts_with("arcl")
        || word.starts_with("arcc")
        || matches!(
            word,
            "searchl"
                | "searchc"
                | "searchextj"
                | "triggl"
                | "triggj"
                | "triggc"
                | "trigglios"
                | "triggjios"
                | "spotl"
                | "spotj"
                | "spotml"
                | "spotmj"
                | "paintl"
                | "paintc"
                | "capl"
                | "capc"
                | "displ"
                | "dispc"
                | "egmrunjoint"
                | "egmrunpose"
                | "egmmovel"
                | "egmmovec"
                | "indamove"
                | "indcmove"
                | "inddmove"
                | "indrmove"
                | "contactl"
                | "pathrecmovebwd"
                | "pathrecmovefwd"
                | "stepbwdpath"
                | "fcpress1lstart"
                | "fcpressl"
                | "fcpressc"
                | "fcpressend"
                | "fcpresslend"
        )
}

impl Flow {
    /// A new routine (`PROC`, `FUNC`, `TRAP`): nothing open, no `GOTO`.
    pub(super) fn routine(&mut self) {
        *self = Flow::default();
    }

    /// Takes a statement whose first word (lower case) is `first`, on `line`; `header` whether
    /// it is a line of the module's structure (`IF .. THEN`, `WHILE .. DO`, `ENDIF`).
    pub(super) fn statement(&mut self, first: &str, header: bool, line: u64) {
        let opens = match first {
            "if" if header => Some("IF"),
            "while" => Some("WHILE"),
            "for" => Some("FOR"),
            "test" => Some("TEST"),
            "error" => Some("ERROR handler"),
            "undo" => Some("UNDO handler"),
            "backward" => Some("BACKWARD handler"),
            _ => None,
        };
        if let Some(name) = opens {
            self.open.push((name, line));
        }
        if matches!(first, "endif" | "endwhile" | "endfor" | "endtest") {
            self.open.pop();
        }
        let branch = (self.open.iter()).any(|(c, _)| !c.ends_with("handler"));
        let leaves = is_leave(first) && branch;
        if first == "goto" || leaves {
            self.jump(&first.to_ascii_uppercase(), line);
        }
    }

    /// Takes a jump (`GOTO`, a conditional `RETURN`..) on `line`.
    pub(super) fn jump(&mut self, name: &str, line: u64) {
        self.jumps.push((name.to_string(), line));
    }

    /// Refuses a jump of the routine that holds the motions, the first on `first_motion`.
    pub(super) fn check_jumps(&self, routine: &str, first_motion: u64) -> Result<()> {
        match self.jumps.first() {
            None => Ok(()),
            Some((name, l)) => Err(at(
                *l,
                format!("{name} in {routine}, whose motions start on line {first_motion}: a jump, or a routine left on a condition, makes the motions the controller runs not the file's; write the path as straight-line code"),
            )),
        }
    }
}

/// Whether a word (lower case) leaves the routine (`RETURN`, `EXIT`, `ExitCycle`, `RAISE`).
pub(super) fn is_leave(word: &str) -> bool {
    matches!(word, "return" | "exit" | "exitcycle" | "raise")
}

/// Whether a word (lower case) jumps (`GOTO`) or leaves the routine ([`is_leave`]).
pub(super) fn is_jump(word: &str) -> bool {
    word == "goto" || is_leave(word)
}

/// The first word of a compact `IF` statement (`statement`, its text, starting on `line`)
/// outside parentheses, brackets and strings, not an operand (followed by an operator), that
/// `wanted` (lower case) takes, its line and its byte in `statement`.
pub(super) fn in_compact_if(
    statement: &str,
    line: u64,
    wanted: fn(&str) -> bool,
) -> Option<(String, u64, usize)> {
    let (mut depth, mut in_string, mut start) = (0i32, false, None::<usize>);
    let end = std::iter::once((statement.len(), ' '));
    for (i, c) in statement.char_indices().chain(end) {
        let word_char = c.is_ascii_alphanumeric() || c == '_';
        if let (Some(s), false) = (start, word_char) {
            start = None;
            let word = &statement[s..i];
            // An instruction, not an operand of the condition (`IF moveCount > 3 ..`).
            let operand = statement[i..]
                .trim_start()
                .starts_with(['=', '<', '>', '+', '-', '*', '/', ',', ')', ':']);
            if depth == 0 && !operand && wanted(&word.to_ascii_lowercase()) {
                let on = line + statement[..s].matches('\n').count() as u64;
                return Some((word.to_string(), on, s));
            }
        }
        match c {
            '"' => in_string = !in_string,
            '(' | '[' if !in_string => depth += 1,
            ')' | ']' if !in_string => depth -= 1,
            _ if word_char && start.is_none() && !in_string => start = Some(i),
            _ => {}
        }
    }
    None
}

/// The byte in a compact `IF cond instruction;` (`statement`, from its `IF`) where its
/// instruction starts: the first word after a whole operand of the condition where an operator
/// would continue it (*RAPID kernel*: the compact IF, expressions). `IF ok Pick;` gives
/// `Pick`'s byte, `IF a > 1 AND NOT done Grip 2;` `Grip`'s; `None` where no instruction follows.
pub(super) fn compact_instruction(statement: &str) -> Option<usize> {
    let b = statement.as_bytes();
    let mut i = statement.len() - statement.trim_start().len();
    // Past the `IF`.
    i += b[i..]
        .iter()
        .take_while(|c| c.is_ascii_alphanumeric())
        .count();
    let mut operand = true;
    while i < b.len() {
        let c = b[i];
        let word = |k: usize| {
            b[k..]
                .iter()
                .take_while(|c| c.is_ascii_alphanumeric() || **c == b'_')
                .count()
        };
        match c {
            c if c.is_ascii_whitespace() => i += 1,
            b'+' | b'-' | b'*' | b'/' | b'=' | b'<' | b'>' => (operand, i) = (true, i + 1),
            b'(' | b'[' | b'"' if operand => (operand, i) = (false, group(b, i)?),
            // A string's doubled quote (`"say ""hi"""`) goes on with the string.
            b'"' if b[i - 1] == b'"' => i = group(b, i)?,
            b'0'..=b'9' | b'.' if operand => {
                // Digits and a point, then an exponent (`1.5E-3`).
                i += b[i..]
                    .iter()
                    .take_while(|c| c.is_ascii_digit() || **c == b'.')
                    .count();
                if matches!(b.get(i), Some(b'e' | b'E')) {
                    let sign = usize::from(matches!(b.get(i + 1), Some(b'+' | b'-')));
                    let k = (i + 1 + sign).min(b.len());
                    i = k + b[k..].iter().take_while(|c| c.is_ascii_digit()).count();
                }
                operand = false;
            }
            c if c.is_ascii_alphabetic() || c == b'_' || c == b'%' => {
                let n = word(i).max(1);
                let w = statement[i..i + n].to_ascii_lowercase();
                match (operand, w.as_str()) {
                    (_, "and" | "or" | "xor" | "div" | "mod") | (true, "not") => operand = true,
                    (false, _) => return Some(i),
                    (true, _) => {
                        operand = false;
                        i = selectors(b, i + n)?;
                        continue;
                    }
                }
                i += n;
            }
            _ => return None,
        }
    }
    None
}

/// The byte after the bracket, parenthesis or string opening at `b[i]` (`None`: it never
/// closes).
fn group(b: &[u8], i: usize) -> Option<usize> {
    if b[i] == b'"' {
        return b[i + 1..]
            .iter()
            .position(|c| *c == b'"')
            .map(|k| i + k + 2);
    }
    let mut depth = 0i64;
    let mut in_string = false;
    for (k, c) in b.iter().enumerate().skip(i) {
        match c {
            b'"' => in_string = !in_string,
            b'(' | b'[' | b'{' if !in_string => depth += 1,
            b')' | b']' | b'}' if !in_string => depth -= 1,
            _ => {}
        }
        if depth == 0 {
            return Some(k + 1);
        }
    }
    None
}

/// The byte after an operand's selectors from `i` (a call's `(..)`, an element's `{..}`, a
/// component's `.name`).
fn selectors(b: &[u8], mut i: usize) -> Option<usize> {
    loop {
        let k = i + b[i..]
            .iter()
            .take_while(|c| c.is_ascii_whitespace())
            .count();
        match b.get(k) {
            Some(b'(' | b'{') => i = group(b, k)?,
            Some(b'.') => {
                i = k
                    + 1
                    + b[k + 1..]
                        .iter()
                        .take_while(|c| c.is_ascii_alphanumeric() || **c == b'_')
                        .count();
            }
            _ => return Some(i),
        }
    }
}
