//! The `//INST` section of a job: its motions, its `'stiffid:` comments, and every other
//! instruction accepted or refused as it can or cannot change the path (module docs of
//! [`super`]; the instructions as the YRC1000 and DX200 INFORM manuals name them).

use super::pulses::{directive, Directives};
use crate::program::at;
use crate::program::speed::Speed;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// A motion to a teaching position: its line, instruction, the positions it names, its speed
/// and the tool file a `TOOL#(n)` tag selects.
pub(super) struct Motion {
    pub line: u64,
    pub word: String,
    pub robot: u64,
    pub base: Option<u64>,
    pub station: Option<u64>,
    pub speed: Speed,
    pub tool: Option<u32>,
    /// The position variable it moves to (`MOVJ P016`: 16), read from the backup's `VAR.DAT`
    /// and copied into the job ([`super::variables`]); `robot` is then the copy's number.
    pub variable: Option<u64>,
    /// The shift in force (its index in [`Instructions::shifts`]).
    pub shift: Option<usize>,
}

/// A parallel shift, `SFTON P032` or `SFTON P001 UF#(2)` ([`super::shift`]): its line and text,
/// the position variable of its amount and the coordinates its tag names.
pub(super) struct Shift {
    pub line: u64,
    pub text: String,
    pub variable: u64,
    pub frame: ShiftFrame,
}

/// The coordinates an `SFTON` names: none, `BF`, `RF`, `UF#(n)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum ShiftFrame {
    Unsaid,
    Base,
    Robot,
    User(u32),
}

impl ShiftFrame {
    /// In words, for a message.
    pub(super) fn words(self) -> String {
        match self {
            ShiftFrame::Unsaid => "with no coordinates named".into(),
            ShiftFrame::Base => "in base coordinates (BF)".into(),
            ShiftFrame::Robot => "in robot coordinates (RF)".into(),
            ShiftFrame::User(n) => format!("in user frame {n} (UF#({n}))"),
        }
    }
}

/// What `//INST` holds: the `'stiffid:` comments, the motions, the jumps, calls, loops and
/// branches (each its line, word and text), the labels (`*NAME`, upper case, and line), the
/// first `WVON`'s line and the robots the `///GROUP` lines name.
pub(super) struct Instructions {
    pub directives: Directives,
    pub motions: Vec<Motion>,
    pub control: Vec<(u64, String, String)>,
    pub labels: Vec<(String, u64)>,
    pub weaves: Option<u64>,
    pub robots: Vec<Robot>,
    pub shifts: Vec<Shift>,
}

/// A robot a `///GROUP` line names (`RB2`): its line, the line and the robot's word.
pub(super) struct Robot {
    pub line: u64,
    pub text: String,
    pub name: String,
}

/// Instructions that cannot move the robot or change a frame: input and output, timers and
/// waits, arithmetic on B, I, D, R and S variables, messages, user alarms and dialogs,
/// arc-welding conditions, synchronisation with other tasks. Weaving (`WVON` .. `WVOF`) is read apart: refused where a
/// motion weaves.
const ACCEPTED: &[&str] = &[
    "NOP", "TIMER", "DOUT", "DIN", "AOUT", "WAIT", "PULSE", "SET", "SETE", "GETE", "GETS", "CLEAR",
    "INC", "DEC", "ADD", "SUB", "MUL", "DIV", "AND", "OR", "NOT", "XOR", "MSG", "ARCON", "ARCOF",
    "ARCSET", "ARCCTS", "ARCCTE", "AWELD", "VWELD", "SPEED", "TSYNC", "SKILLSND", "HPVELON",
    "HPVELOF", "PAUSE", "CWAIT", "ADVINIT", "ADVSTOP", "SETREG", "GETREG", "SYSTART", "SYEND",
    "HAND", "HSEN", "GETARG", "CNVRT", "GETPOS", "SETFILE", "GETFILE", "ARATION", "ARATIOF",
    "TOOLON", "TOOLOF", "SVSPOT", "SPOT", "GUNCHG", "SETUALM", "DIALOG", "CLS", "PRINT", "SQRT",
    "SIN", "COS", "ATAN",
];

/// Instructions that change the order the controller runs (a jump, a call, a loop, a branch).
const CONTROL: &[&str] = &[
    "JUMP",
    "CALL",
    "IF",
    "IFTHEN",
    "IFTHENEXP",
    "ELSEIF",
    "ELSEIFEXP",
    "ELSE",
    "ENDIF",
    "FOR",
    "NEXT",
    "WHILE",
    "WHILEEXP",
    "ENDWHILE",
    "SWITCH",
    "CASE",
    "DEFAULT",
    "ENDSWITCH",
    "RET",
];

/// The `//INST` section of `text`: its directives and motions, every other instruction checked
/// (module docs of [`super`]).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of an instruction refused, or of a job that
/// does not end with `END` (cut off). Jumps and calls are the caller's ([`super::calls`]).
pub(super) fn instructions(text: &str) -> Result<Instructions> {
    let mut out = Instructions {
        directives: Directives::default(),
        motions: Vec::new(),
        control: Vec::new(),
        labels: Vec::new(),
        weaves: None,
        robots: Vec::new(),
        shifts: Vec::new(),
    };
    let mut shifting: Option<usize> = None;
    let (mut in_inst, mut last) = (false, None::<(u64, String)>);
    let mut weaving: Option<(u64, String)> = None;
    let mut groups: Vec<Robot> = Vec::new();
    for (line, _, l) in crate::program::lines(text) {
        let t = l.trim();
        if let Some(section) = t.strip_prefix("//").filter(|s| !s.starts_with('/')) {
            in_inst = section.starts_with("INST");
            continue;
        }
        if in_inst && t.starts_with("///GROUP") {
            if let Some((first, _)) = &last {
                return Err(at(line, format!("{}: a control group line after an instruction (line {first}): a job states its groups before its instructions; which groups it moves is not certain", short(t))));
            }
            let words = t.split_whitespace().skip(1).flat_map(|w| w.split(','));
            for name in words.map(str::trim).filter(|w| !w.is_empty()) {
                let (text, name) = (t.to_string(), name.to_string());
                match name.starts_with("RB") {
                    true => out.robots.push(Robot { line, text, name }),
                    false => groups.push(Robot { line, text, name }),
                }
            }
        }
        if !in_inst || t.starts_with("///") || t.is_empty() {
            continue;
        }
        if last.is_none() {
            no_robot(&out.robots, &groups)?;
        }
        last = Some((line, t.to_string()));
        if let Some(comment) = t.strip_prefix('\'') {
            directive(line, comment, &mut out.directives)?;
            continue;
        }
        let t = without_comment(t);
        let words: Vec<&str> = t.split_whitespace().collect();
        let first = words[0].to_ascii_uppercase();
        if first == "COMM" {
            // A line commented out on the pendant: the controller skips it.
            continue;
        }
        let control = CONTROL.contains(&first.as_str()) || first.starts_with("MACRO");
        if let Some(s) = shifting.filter(|_| control || first.starts_with('*')) {
            let s = &out.shifts[s];
            return Err(at(line, format!("{}: a jump, call, branch or label while the shift of line {} ({}) is in force: which motions it shifts is decided as the job runs; end the shift (SFTOF) before it", short(t), s.line, short(&s.text))));
        }
        if first.starts_with('*') {
            // A label: where a JUMP goes ([`super::calls`]).
            out.labels.push((first, line));
            continue;
        }
        if control {
            out.control.push((line, first, t.to_string()));
            continue;
        }
        match first.as_str() {
            "MOVJ" | "MOVL" | "MOVC" | "SMOVL" | "SMOVC" => {
                if let Some((w, text)) = &weaving {
                    return Err(at(*w, format!("{}: weaving (WVON) moves the tool across the path in the motions after it, up to WVOF, so the path the controller runs is not the job's: remove it or compensate the job without it", short(text))));
                }
                let mut m = match first.starts_with('S') {
                    true => coordinated(line, &first, &words[1..])?,
                    false => motion(line, &first, &words[1..])?,
                };
                m.shift = shifting;
                out.motions.push(m);
            }
            "SFTON" => {
                if let Some(s) = shifting {
                    let s = &out.shifts[s];
                    return Err(at(line, format!("{}: a second shift while the shift of line {} is in force (the two add up); end the first (SFTOF) before it", short(t), s.line)));
                }
                out.shifts.push(shift(line, t, &words[1..])?);
                shifting = Some(out.shifts.len() - 1);
            }
            "SFTOF" => shifting = None,
            "WVON" => {
                out.weaves.get_or_insert(line);
                weaving.get_or_insert((line, t.to_string()));
            }
            "WVOF" => weaving = None,
            "END" => {}
            w if ACCEPTED.contains(&w) => {}
            _ => return Err(refused(line, &first, t)),
        }
    }
    if let Some(s) = shifting.map(|s| &out.shifts[s]) {
        return Err(at(s.line, format!("{}: a shift with no SFTOF after it: it would hold in the job that called this one; end it (SFTOF) before END", short(&s.text))));
    }
    check_end(last)?;
    Ok(out)
}

/// Refuses a job whose `///GROUP` lines name no robot but a station or base axes alone
/// (`///GROUP1 ST1`: a positioner's own job), naming the line: it moves no robot, and its
/// motions name the station's positions (`EC`) only.
fn no_robot(robots: &[Robot], groups: &[Robot]) -> Result<()> {
    match (robots.is_empty(), groups.first()) {
        (true, Some(g)) => Err(at(g.line, format!("{}: a job of {} alone, no robot (RB) among its control groups: it moves the station or base axes, not a robot, so it holds no robot target to compensate; compensate the jobs of the robot (RB1..), where the station's positions beside the robot's (+MOVJ EC..) are read as the cell's positioner axes", short(&g.text), short(&g.name)))),
        _ => Ok(()),
    }
}

/// The shift `SFTON` on `line` (`t`, `words` after its word): a position variable `P000` and
/// the coordinates `BF`, `RF` or `UF#(n)`, if named.
fn shift(line: u64, t: &str, words: &[&str]) -> Result<Shift> {
    let refuse = |why: &str| Err(at(line, format!("{}: {why}", short(t))));
    let upper: Vec<String> = words.iter().map(|w| w.to_ascii_uppercase()).collect();
    let Some(variable) = upper.first().and_then(|w| index(w, "P")) else {
        return refuse("a shift whose amount is not a position variable P000.. by its number (a local, indexed, base or station variable, set as the job runs or held in another group): not computed");
    };
    let frame = match upper.get(1).map(String::as_str) {
        None => ShiftFrame::Unsaid,
        Some("BF") => ShiftFrame::Base,
        Some("RF") => ShiftFrame::Robot,
        Some(w) => match w.strip_prefix("UF#(").and_then(|r| r.strip_suffix(')')).map(str::parse::<u32>) {
            Some(Ok(n)) => ShiftFrame::User(n),
            _ => return refuse("a shift in tool coordinates (TF), a user frame from a variable or another tag: relative to where the tool is, or decided as the job runs; stiffid computes a shift in base (BF), robot (RF) or user coordinates (UF#(n))"),
        },
    };
    if upper.len() > 2 {
        return refuse("a word after the shift's coordinates stiffid does not follow");
    }
    Ok(Shift {
        line,
        text: t.to_string(),
        variable,
        frame,
    })
}

/// The instruction `t` without its instruction comment: the text from a `//` that follows a
/// space outside a quoted string to the line's end (`MOVJ C00000 VJ=65.00  //FROM LEFT`, as
/// the YRC1000 and DX200 store a comment given to an instruction on the pendant), trimmed.
pub(super) fn without_comment(t: &str) -> &str {
    let mut quoted = false;
    let bytes = t.as_bytes();
    for (i, b) in bytes.iter().enumerate() {
        match b {
            b'"' => quoted = !quoted,
            b'/' if !quoted && bytes.get(i + 1) == Some(&b'/') && i > 0 && bytes[i - 1] == b' ' => {
                return t[..i].trim_end();
            }
            _ => {}
        }
    }
    t
}

/// Refuses a job whose last instruction is not `END`: the controller loads no job without it,
/// and a file cut off mid-line reads as one.
fn check_end(last: Option<(u64, String)>) -> Result<()> {
    match last {
        Some((_, t)) if t.eq_ignore_ascii_case("END") => Ok(()),
        Some((line, t)) => Err(at(line, format!("the job ends on '{}' without END: a job the controller stores ends with END (is the file cut off?)", short(&t)))),
        None => Err(at(1, "no //INST section ending with END: not a whole INFORM job (is the file cut off?)".into())),
    }
}

/// The error of the instruction `word` on `line` (`t`), which stiffid does not accept.
fn refused(line: u64, word: &str, t: &str) -> stiffid_core::Error {
    let why = match word {
        "MOVS" => "a spline; its path bends through all its points, not along the compensated ones: write it as MOVL or MOVJ motions".to_string(),
        "IMOV" => "an increment from where the robot is, which the job does not say: write the absolute position".to_string(),
        "FORMCUT" => "a form cut: the controller moves the tool around a circle or a rectangle its condition file (FORMCUT.CND) gives, not through the job's positions: write the cut as MOVL and MOVC motions".to_string(),
        "MSHIFT" => "a shift computed as the job runs, from positions the job does not say: compensate the path without it (teach or post the shifted positions)".to_string(),
        w if w.starts_with("SMOV") || w.starts_with("SYMOV") => {
            "a coordinated motion stiffid does not read (on a conveyor, or other than SMOVL and SMOVC to a robot position with the station's, +MOVJ EC..): write the path as MOVL and MOVC with the station's values in the motion (EC, or +MOVJ EC)".to_string()
        }
        w if w.starts_with("+MOV") => {
            "a motion of another group alone, at its own speed; write the path as MOVJ, MOVL and MOVC to C positions".to_string()
        }
        _ => format!("an instruction stiffid does not know ('{}'); it may move the robot or change a frame, so the job is not compensated: remove it or write the path without it", short(t)),
    };
    at(line, format!("{}: {why}", short(word)))
}

/// The positions and tags of a `MOVJ`, `MOVL` or `MOVC` line after its word.
fn motion(line: u64, word: &str, words: &[&str]) -> Result<Motion> {
    let target = words.first().copied().unwrap_or("");
    let variable = index(&target.to_ascii_uppercase(), "P");
    let robot = index(target, "C").or(variable.map(|_| 0)).ok_or_else(|| {
        let why = match target.chars().next() {
            Some('P') => "a position variable chosen by an index the job computes as it runs, which the job does not say: move to P000.. by its number",
            Some('L') => "a local position variable, which the job sets as it runs: teach the position in the job (C)",
            Some('B' | 'E') if index(target, "BC").or(index(target, "EC")).is_some() => "a motion of the base axes or the station alone, without the robot's position C: the robot holds its posture while the part or the carriage moves, so this job's robot motions are the others' (stiffid compensates the robot's positions C; a job that moves only the station has none to compensate)",
            _ => "expected a teaching position C00000",
        };
        at(line, format!("{word} {}: {why}", short(target)))
    })?;
    let mut m = Motion {
        line,
        word: word.to_string(),
        robot,
        base: None,
        station: None,
        speed: Speed::Joint,
        tool: None,
        variable,
        shift: None,
    };
    let split = (words.iter())
        .position(|w| w.to_ascii_uppercase().starts_with("+MOV"))
        .unwrap_or(words.len());
    let (own, station) = words.split_at(split);
    for w in &own[1..] {
        tag(line, word, w, &mut m)?;
    }
    if !station.is_empty() {
        station_motion(line, word, station, &mut m)?;
    }
    m.speed = super::speed::speed(line, word, &own[1..])?;
    Ok(m)
}

/// The station group's own motion on the line of a robot's motion `word` (`MOVL C00003 BC00003
/// V=5.0  +MOVJ EC00003 VJ=80.00`, `words` from `+MOVJ`): the two start together and the next
/// line runs when both have arrived, so the station's position is the target's, as `EC` in the
/// robot's motion; its speed and level tags are the station's own.
fn station_motion(line: u64, word: &str, words: &[&str], m: &mut Motion) -> Result<()> {
    let refuse = |what: &str| {
        Err(at(line, format!("{word} .. {}: {what}; stiffid reads a station's own motion as +MOVJ EC00000 and its tags VJ=, PL=, ACC=, DEC=", words.join(" "))))
    };
    let position = words
        .get(1)
        .and_then(|w| index(&w.to_ascii_uppercase(), "EC"));
    let (true, Some(index)) = (words[0].eq_ignore_ascii_case("+MOVJ"), position) else {
        return refuse("another group's own motion stiffid does not follow");
    };
    if m.station.is_some() {
        return refuse("a second station position in one motion");
    }
    m.station = Some(index);
    for w in &words[2..] {
        let upper = w.to_ascii_uppercase();
        match upper.split_once('=') {
            Some((name, value)) if ["VJ", "PL", "ACC", "DEC"].contains(&name) => {
                value_tag(line, "+MOVJ", (name, value), w)?;
            }
            _ if upper == "NWAIT" => {}
            _ => {
                return refuse(&format!(
                    "{}: a tag of the station's motion stiffid does not follow",
                    short(w)
                ))
            }
        }
    }
    Ok(())
}

/// A coordinated motion `SMOVL` or `SMOVC` (`word`, `words` after it; read as `MOVL`, `MOVC`,
/// as a circle's point there): the
/// robot moves relative to the part on the moving station, at the speed `V=` relative to it,
/// and both groups end together at their positions (`SMOVL C00008 BC00008 V=166.7  +MOVJ
/// EC00008`, as RoboDK's Motoman post writes it); read as the motion `word` to the robot's
/// position with the station's values, the feed along the part (as every target with the
/// cell's positioner axes is fed). Refused naming the line without the station's position.
fn coordinated(line: u64, word: &str, words: &[&str]) -> Result<Motion> {
    let m = motion(line, word, words)?;
    match m.station {
        Some(_) => Ok(m),
        None => Err(at(line, format!("{word} {}: a coordinated motion without the station's position (+MOVJ EC00000 or EC00000 on the line): where the part is when the robot arrives is the controller's, which the job does not say", short(&words.join(" "))))),
    }
}

/// The number of a position named `prefix` then digits (`C00001`), if `w` is one.
fn index(w: &str, prefix: &str) -> Option<u64> {
    w.strip_prefix(prefix)
        .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
        .and_then(|d| d.parse().ok())
}

/// Reads one word `w` after a motion's position into `m`, refusing what stiffid does not follow.
fn tag(line: u64, word: &str, w: &str, m: &mut Motion) -> Result<()> {
    let upper = w.to_ascii_uppercase();
    if let Some(i) = index(&upper, "BC") {
        m.base = Some(i);
    } else if let Some(i) = index(&upper, "EC") {
        m.station = Some(i);
    } else if upper.starts_with("BP") || upper.starts_with("EX") {
        return Err(at(line, format!("{word} .. {}: a position variable holds its value on the controller, not in this job; teach the position in the job (BC, EC)", short(w))));
    } else if upper == "UNTIL" {
        return Err(at(line, format!("{word} .. UNTIL: a search stops where a signal comes, which the job does not say; not compensated")));
    } else if upper.starts_with("+MOV") {
        return Err(at(line, format!("{word} .. {}: another group's own motion (a station moving at its own speed beside the robot); stiffid follows one motion per line: write the station's values in the robot's motion (C.. EC..)", short(w))));
    } else if let Some(n) = upper
        .strip_prefix("TOOL#(")
        .and_then(|r| r.strip_suffix(')'))
    {
        let n = n.parse::<u32>().map_err(|_| {
            at(line, format!("{word} .. {}: a tool file selected by a variable; the job does not say which: write its number", short(w)))
        })?;
        m.tool = Some(n);
    } else if let Some((name, value)) = upper.split_once('=') {
        value_tag(line, word, (name, value), w)?;
    } else if upper != "NWAIT" {
        return Err(at(line, format!("{word} .. {}: a tag stiffid does not follow (the path or its end would not be the job's); remove it or compensate the job without it", short(w))));
    }
    Ok(())
}

/// Checks a tag `name=value` (`w` as written): a speed, position level or acceleration tag with
/// a finite number or a variable (`I000`, `LD001`, `B[1]`).
fn value_tag(line: u64, word: &str, (name, value): (&str, &str), w: &str) -> Result<()> {
    if !["VJ", "V", "VR", "VE", "PL", "CR", "ACC", "DEC"].contains(&name) {
        return Err(at(line, format!("{word} .. {}: a tag stiffid does not follow (the path or its end would not be the job's); remove it or compensate the job without it", short(w))));
    }
    let number = crate::program::speed::literal(value).is_some();
    let variable = value
        .strip_prefix('L')
        .unwrap_or(value)
        .strip_prefix(['B', 'I', 'D', 'R'])
        .is_some_and(|r| {
            (!r.is_empty() && r.bytes().all(|b| b.is_ascii_digit()))
                || (r.starts_with('[') && r.ends_with(']'))
        });
    match number || variable {
        true => Ok(()),
        false => Err(at(
            line,
            format!(
                "{word} .. {}: expected a number or a B, I, D or R variable after {name}=",
                short(w)
            ),
        )),
    }
}
