//! Expressions of parameters (LinuxCNC's manual, "Overview": "Expressions", "Binary
//! Operators", "Functions"; `interp_read.cc` and `interp_execute.cc`; FANUC macro B's
//! arithmetic): a real value is a number, a parameter `#n` / `#<name>` (its number itself a
//! value: `#[#1+1]`, `##1`), a bracketed expression `[..]`, or a function `SIN[..]`, with an
//! optional sign. Binary operators by precedence, each group left to right: `**`; `*` `/`
//! `MOD`; `+` `-`; `EQ NE GT GE LT LE`; `AND OR XOR`. Angles in degrees.
//!
//! Where controllers differ: LinuxCNC's `EQ`, `NE`, `LE`, `GE` take values within 0.0001 as
//! equal (`TOLERANCE_EQUAL`), FANUC compares exactly (values closer than 0.0001 and not equal are
//! refused without a dialect); `FIX`/`FUP` of a negative value are `floor`/`ceil` on LinuxCNC,
//! towards / away from zero on FANUC and Haas (refused without a dialect); `AND OR XOR` are
//! logical on LinuxCNC and bitwise on FANUC (FANUC and an unstated dialect refuse operands
//! other than 0 and 1).

/// Which controller's rules (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Flavour {
    /// LinuxCNC's interpreter.
    LinuxCnc,
    /// FANUC macro B (and Haas, which follows it).
    Fanuc,
    /// No dialect stated: what reads alike, else refused.
    Unstated,
}

/// A parameter named in the text.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Param {
    /// `#n`.
    Number(u32),
    /// `#<name>` (lower case, blanks removed, as LinuxCNC keeps it).
    Named(String),
}

impl std::fmt::Display for Param {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Param::Number(n) => write!(f, "#{n}"),
            Param::Named(n) => write!(f, "#<{n}>"),
        }
    }
}

/// Where parameters' values come from.
pub(super) trait Values {
    /// The value of `p`, or why it has none here.
    fn value(&self, p: &Param) -> Result<f64, String>;
}

/// A reading position in a line.
pub(super) struct Cursor<'a> {
    pub(super) text: &'a str,
    pub(super) at: usize,
}

/// LinuxCNC's `TOLERANCE_EQUAL` (`interp_internal.hh`).
const TOLERANCE_EQUAL: f64 = 0.0001;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Op {
    Pow,
    Times,
    Divide,
    Mod,
    Plus,
    Minus,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    And,
    Or,
    Xor,
}

impl Op {
    fn precedence(self) -> u8 {
        match self {
            Op::Pow => 6,
            Op::Times | Op::Divide | Op::Mod => 5,
            Op::Plus | Op::Minus => 4,
            Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le => 3,
            Op::And | Op::Or | Op::Xor => 2,
        }
    }
}

impl<'a> Cursor<'a> {
    pub(super) fn new(text: &'a str, at: usize) -> Self {
        Cursor { text, at }
    }

    /// Skips blanks; the next character.
    pub(super) fn peek(&mut self) -> Option<char> {
        let rest = &self.text[self.at..];
        let trimmed = rest.trim_start_matches([' ', '\t']);
        self.at += rest.len() - trimmed.len();
        trimmed.chars().next()
    }

    /// Takes `c` if it is next.
    pub(super) fn eat(&mut self, c: char) -> bool {
        let next = self.peek().map(|n| n.to_ascii_lowercase());
        if next == Some(c.to_ascii_lowercase()) {
            self.at += c.len_utf8();
            return true;
        }
        false
    }

    /// The letters next (a keyword), not taken.
    pub(super) fn keyword(&mut self) -> String {
        self.peek();
        self.text[self.at..]
            .chars()
            .take_while(char::is_ascii_alphabetic)
            .collect::<String>()
            .to_ascii_uppercase()
    }

    /// A number written with digits and a point (no sign).
    fn number(&mut self) -> Result<f64, String> {
        self.peek();
        let rest = &self.text[self.at..];
        let len = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(rest.len());
        let digits = &rest[..len];
        let value = match digits.parse::<f64>() {
            Ok(v) if digits.chars().any(|c| c.is_ascii_digit()) => v,
            _ => return Err(format!("expected a value at '{}'", short(rest))),
        };
        self.at += len;
        Ok(value)
    }
}

fn short(text: &str) -> String {
    stiffid_core::common::limits::short(text.trim())
}

/// A real value (module docs) at the cursor.
pub(super) fn real_value(c: &mut Cursor, v: &dyn Values, f: Flavour) -> Result<f64, String> {
    match c.peek() {
        Some('-') => {
            c.at += 1;
            Ok(-real_value(c, v, f)?)
        }
        Some('+') => {
            c.at += 1;
            real_value(c, v, f)
        }
        Some('[') => expression(c, v, f),
        Some('#') => {
            let p = param(c, v, f)?;
            v.value(&p)
        }
        Some(ch) if ch.is_ascii_alphabetic() => function(c, v, f),
        _ => c.number(),
    }
}

/// A parameter named at the cursor (`#` next): `#n`, `#<name>`, `#[expr]`, `##n`.
pub(super) fn param(c: &mut Cursor, v: &dyn Values, f: Flavour) -> Result<Param, String> {
    if !c.eat('#') {
        return Err("expected a parameter #".into());
    }
    if c.peek() == Some('<') {
        let rest = &c.text[c.at + 1..];
        let end = rest
            .find('>')
            .ok_or_else(|| format!("#<{}: the name's closing '>' missing", short(rest)))?;
        let name: String = rest[..end]
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect::<String>()
            .to_ascii_lowercase();
        c.at += end + 2;
        return Ok(Param::Named(name));
    }
    let n = real_value(c, v, f)?;
    if n.fract() != 0.0 || !(0.0..=1e6).contains(&n) {
        return Err(format!(
            "#{}: a parameter's number is a whole number",
            stiffid_core::common::words::number(n)
        ));
    }
    Ok(Param::Number(n as u32))
}

/// The value assigned to a parameter (`#1 = ..`): an expression to the next word (FANUC writes
/// `#1 = #2 + 3` without brackets; LinuxCNC's `#1 = [#2 + 3]` reads alike).
pub(super) fn assigned(c: &mut Cursor, v: &dyn Values, f: Flavour) -> Result<f64, String> {
    Ok(binary(c, v, f, 0)?.0)
}

/// A bracketed expression at the cursor (`[` next).
pub(super) fn expression(c: &mut Cursor, v: &dyn Values, f: Flavour) -> Result<f64, String> {
    if !c.eat('[') {
        return Err("expected '['".into());
    }
    let value = binary(c, v, f, 0)?.0;
    if !c.eat(']') {
        let rest = &c.text[c.at..];
        return Err(format!("expected an operator or ']' at '{}'", short(rest)));
    }
    Ok(value)
}

/// Operands and operators of precedence at least `min`: the value and whether the last
/// operator applied was arithmetic.
fn binary(c: &mut Cursor, v: &dyn Values, f: Flavour, min: u8) -> Result<(f64, bool), String> {
    let mut left = (real_value(c, v, f)?, false);
    while let Some(op) = operator(c) {
        if op.precedence() < min {
            break;
        }
        take_operator(c, op);
        let right = binary(c, v, f, op.precedence() + 1)?;
        left = (apply(op, left, right, f)?, op.precedence() >= 4);
    }
    Ok(left)
}

/// The operator next, not taken.
fn operator(c: &mut Cursor) -> Option<Op> {
    let op = match c.peek()? {
        '*' if c.text[c.at..].starts_with("**") => Op::Pow,
        '*' => Op::Times,
        '/' => Op::Divide,
        '+' => Op::Plus,
        '-' => Op::Minus,
        _ => match c.keyword().as_str() {
            "MOD" => Op::Mod,
            "EQ" => Op::Eq,
            "NE" => Op::Ne,
            "GT" => Op::Gt,
            "GE" => Op::Ge,
            "LT" => Op::Lt,
            "LE" => Op::Le,
            "AND" => Op::And,
            "OR" => Op::Or,
            "XOR" => Op::Xor,
            _ => return None,
        },
    };
    Some(op)
}

fn take_operator(c: &mut Cursor, op: Op) {
    c.at += match op {
        Op::Pow | Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le | Op::Or => 2,
        Op::Times | Op::Divide | Op::Plus | Op::Minus => 1,
        Op::Mod | Op::And | Op::Xor => 3,
    };
}

/// `left op right` (module docs, LinuxCNC's `execute_binary1`/`2`).
fn apply(
    op: Op,
    (a, a_arith): (f64, bool),
    (b, b_arith): (f64, bool),
    f: Flavour,
) -> Result<f64, String> {
    let truth = |t: bool| if t { 1.0 } else { 0.0 };
    let close = (a - b).abs() < TOLERANCE_EQUAL;
    if matches!(op, Op::Eq | Op::Ne | Op::Le | Op::Ge) && close && a != b && f != Flavour::LinuxCnc
    {
        return Err(format!("{a} and {b} compared: LinuxCNC takes values within {TOLERANCE_EQUAL} as equal, FANUC and Haas compare them exactly; state [controller] dialect, or compare values further apart"));
    }
    let equal = match f {
        Flavour::LinuxCnc => close,
        _ => a == b,
    };
    let value = match op {
        Op::Pow if a < 0.0 && b.floor() != b => {
            return Err(format!(
                "{a} ** {b}: a negative number to a power that is not whole"
            ))
        }
        Op::Pow => a.powf(b),
        Op::Times => a * b,
        Op::Divide if b == 0.0 => return Err("a division by zero".into()),
        Op::Divide => a / b,
        Op::Mod if b == 0.0 => return Err("MOD by zero".into()),
        Op::Mod => {
            let m = a % b;
            if m < 0.0 {
                m + b.abs()
            } else {
                m
            }
        }
        Op::Plus => a + b,
        Op::Minus => a - b,
        Op::Eq => truth(equal),
        Op::Ne => truth(!equal),
        Op::Gt => truth(a > b),
        Op::Ge => truth(equal || a >= b),
        Op::Lt => truth(a < b),
        Op::Le => truth(equal || a <= b),
        Op::And | Op::Or | Op::Xor => logical(op, (a, a_arith), (b, b_arith), f)?,
    };
    if !value.is_finite() {
        return Err(format!("{a} {op:?} {b} is not a finite number"));
    }
    Ok(value)
}

/// `AND OR XOR` (module docs).
fn logical(
    op: Op,
    (a, a_arith): (f64, bool),
    (b, b_arith): (f64, bool),
    f: Flavour,
) -> Result<f64, String> {
    let boolean = |x: f64| x == 0.0 || x == 1.0;
    if f != Flavour::LinuxCnc && (!boolean(a) || !boolean(b) || a_arith || b_arith) {
        return Err(format!("{op:?} of {a} and {b}: logical on LinuxCNC, bitwise on FANUC and Haas, and bound differently to + - * /; bracket each side and give it 0 or 1 (a comparison), or state [controller] dialect = \"linuxcnc\""));
    }
    let (p, q) = (a != 0.0, b != 0.0);
    let t = match op {
        Op::And => p && q,
        Op::Or => p || q,
        _ => p != q,
    };
    Ok(if t { 1.0 } else { 0.0 })
}

/// A function `NAME[..]` (`ATAN[..]/[..]`) at the cursor.
fn function(c: &mut Cursor, v: &dyn Values, f: Flavour) -> Result<f64, String> {
    let name = c.keyword();
    c.at += name.len();
    if c.peek() != Some('[') {
        return Err(format!(
            "'{name}': expected a number, a parameter, '[' or a function"
        ));
    }
    let x = expression(c, v, f)?;
    let deg = |r: f64| r.to_degrees();
    let value = match name.as_str() {
        "ATAN" => {
            if !c.eat('/') {
                return Err("ATAN: expected ATAN[y]/[x]".into());
            }
            let d = expression(c, v, f)?;
            x.atan2(d).to_degrees()
        }
        "SIN" => x.to_radians().sin(),
        "COS" => x.to_radians().cos(),
        "TAN" => x.to_radians().tan(),
        "ASIN" | "ACOS" if !(-1.0..=1.0).contains(&x) => return Err(format!("{name}[{x}]: outside -1..1")),
        "ASIN" => deg(x.asin()),
        "ACOS" => deg(x.acos()),
        "SQRT" if x < 0.0 => return Err(format!("SQRT[{x}] of a negative number")),
        "SQRT" => x.sqrt(),
        "ABS" => x.abs(),
        "EXP" => x.exp(),
        "LN" if x <= 0.0 => return Err(format!("LN[{x}] of a number not positive")),
        "LN" => x.ln(),
        "ROUND" => (x + if x < 0.0 { -0.5 } else { 0.5 }).trunc(),
        "FIX" | "FUP" => fix_fup(&name, x, f)?,
        other => return Err(format!("'{other}': not a function read here (SIN COS TAN ASIN ACOS ATAN[y]/[x] SQRT ABS ROUND FIX FUP EXP LN)")),
    };
    if !value.is_finite() {
        return Err(format!("{name}[{x}] is not a finite number"));
    }
    Ok(value)
}

/// `FIX`/`FUP` (module docs).
fn fix_fup(name: &str, x: f64, f: Flavour) -> Result<f64, String> {
    let fix = name == "FIX";
    Ok(match f {
        Flavour::LinuxCnc if fix => x.floor(),
        Flavour::LinuxCnc => x.ceil(),
        _ if x >= 0.0 => if fix { x.floor() } else { x.ceil() },
        Flavour::Fanuc if fix => x.trunc(),
        Flavour::Fanuc => -(-x).ceil(),
        Flavour::Unstated => return Err(format!("{name}[{x}]: of a negative number LinuxCNC rounds down ({}) and FANUC and Haas towards {} ({}); state [controller] dialect", if fix { x.floor() } else { x.ceil() }, if fix { "zero" } else { "away from zero" }, if fix { x.trunc() } else { -(-x).ceil() })),
    })
}
