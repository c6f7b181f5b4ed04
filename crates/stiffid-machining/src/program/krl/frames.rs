//! The tool and base each KRL motion moves with, as the controller sets them (module docs of
//! [`super`]): literal `$BASE`/`$TOOL` frames ([`super::cartesian::frame_set`]), frames selected
//! by number (`$TOOL = TOOL_DATA[n]`, `$BASE = BASE_DATA[n]`, `BAS(#TOOL, n)`, `BAS(#BASE, n)`),
//! the inline forms' frame data (`FDAT_ACT = FP1` or a literal `{TOOL_NO .., BASE_NO ..,
//! IPO_FRAME ..}`, applied by `BAS(#FRAMES)`, `BAS(#PTP_PARAMS, ..)` and `BAS(#CP_PARAMS, ..)`)
//! and a KSS 8 motion's own `WITH $TOOL = STOOL2(FP1), $BASE = SBASE(FP1.BASE_NO),
//! $IPO_MODE = SIPO_MODE(FP1.IPO_FRAME)`.
//!
//! The rules are those of the BAS package of KUKA System Software (`R1/System/bas.src`:
//! `FRAMES` runs `SET_IPO_MODE(FDAT_ACT.IPO_FRAME)`, `TOOL(FDAT_ACT.TOOL_NO)` and, for a base
//! number below 17, `BASE(FDAT_ACT.BASE_NO)`; `TOOL(n)` sets `$TOOL = TOOL_DATA[n]`, and
//! `$NULLFRAME` (the flange) for `n <= 0`; `BASE(n)` sets `$BASE = BASE_DATA[n]`, and `$WORLD`
//! for `n <= 0`) with their correction frames off (`TOOL_CORR_ON`, `BASE_CORR_ON` FALSE as
//! `$config.dat` delivers them). Anything stiffid cannot know is a frame
//! [`Frame::Unknown`] naming the line, which refuses the motions that use it: an external TCP
//! (`IPO_FRAME #TCP`, `$IPO_MODE = #TCP`), a base number of 17 or more (an external kinematic,
//! `EX_BASE`), a frame data record not declared in the `.src` or its `.dat`, a number that is not
//! a literal, a correction frame switched on, a frame set by `BAS(#INITMOV)` (its defaults
//! differ between BAS versions) or inside a loop or branch.

use crate::program::cartesian::Frame;
use std::collections::HashMap;
use stiffid_core::common::limits::short;

/// A frame data record (`FDAT`): the tool and base numbers and whether the TCP is external.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Fdat {
    /// `TOOL_NO`.
    tool: i64,
    /// `BASE_NO`.
    base: i64,
    /// `IPO_FRAME #TCP`: the tool is fixed in the cell and the part on the flange.
    external: bool,
}

/// A frame data record read, or why it cannot be.
pub(super) type FdatRead = Result<Fdat, String>;

/// The frame data records declared in the program and its `.dat` (`DECL FDAT FP1={..}`), by
/// upper-case name: the line and file they are declared on (words), and the record.
pub(super) type Fdats = HashMap<String, (String, FdatRead)>;

/// The highest base number `BASE(n)` reads as `BASE_DATA[n]`; above it `FRAMES` selects an
/// external kinematic (`EX_BASE`).
const MAX_BASE: i64 = 16;

/// The frame data record of an aggregate `{TOOL_NO 1, BASE_NO 0, IPO_FRAME #BASE, ..}`.
pub(super) fn fdat(value: &str) -> FdatRead {
    let inner = value
        .trim()
        .strip_prefix('{')
        .and_then(|v| v.split('}').next());
    let inner = inner.ok_or("expected an aggregate {TOOL_NO .., BASE_NO .., IPO_FRAME ..}")?;
    let inner = inner.split_once(':').map_or(inner, |(_, r)| r);
    let (mut tool, mut base, mut ipo) = (None, None, None);
    for item in inner.split(',') {
        let mut words = item.split_whitespace();
        let (Some(name), Some(v)) = (words.next(), words.next()) else {
            continue;
        };
        match name.to_ascii_uppercase().as_str() {
            "TOOL_NO" => tool = Some(whole(v, "TOOL_NO")?),
            "BASE_NO" => base = Some(whole(v, "BASE_NO")?),
            "IPO_FRAME" => ipo = Some(v.to_ascii_uppercase()),
            _ => {}
        }
    }
    let missing = |m: &str| {
        format!("its {m} is not given (KRL keeps the member of a partial aggregate the controller holds)")
    };
    Ok(Fdat {
        tool: tool.ok_or_else(|| missing("TOOL_NO"))?,
        base: base.ok_or_else(|| missing("BASE_NO"))?,
        external: match ipo.as_deref() {
            Some("#BASE") => false,
            Some("#TCP") => true,
            Some(other) => {
                return Err(format!(
                    "IPO_FRAME {}: expected #BASE or #TCP",
                    short(other)
                ))
            }
            None => return Err(missing("IPO_FRAME")),
        },
    })
}

/// The correction switch `c` (compact) sets: base (`true`) or tool, and on or off
/// (`BASE_CORR_ON=TRUE`); `None` for any other statement.
fn correction_switch(c: &str) -> Option<(bool, bool)> {
    let (base, value) = match (
        c.strip_prefix("TOOL_CORR_ON="),
        c.strip_prefix("BASE_CORR_ON="),
    ) {
        (Some(v), _) => (false, v),
        (_, Some(v)) => (true, v),
        _ => return None,
    };
    Some((base, value != "FALSE"))
}

/// A whole number written as a literal.
fn whole(v: &str, name: &str) -> Result<i64, String> {
    v.trim()
        .parse::<i64>()
        .map_err(|_| format!("{name} {}: expected a whole number", short(v)))
}

/// The frames in force while a program is read line by line (module docs).
#[derive(Debug, Clone)]
pub(super) struct Frames {
    /// `$BASE`.
    pub base: Frame,
    /// `$TOOL`.
    pub tool: Frame,
    /// `FDAT_ACT`: the line that set it and the record, `None` before any.
    pub(super) act: Option<(u64, FdatRead)>,
    /// The line of `$IPO_MODE = #TCP` in force (an external TCP).
    pub(super) external: Option<u64>,
    /// The entries of the controller's tables the program assigns (`BASE_DATA[n] = {..}`,
    /// `TOOL_DATA[n] = {..}`, or a member of one): by base (`true`) or tool and number, the
    /// frame a later selection of the number takes instead of the setup's.
    pub(super) table: HashMap<(bool, u32), Frame>,
    /// Per tool (0) and base (1), why every entry of its table is the controller's from a line
    /// on: an assignment to an entry whose index is not a number.
    pub(super) any_entry: [Option<Frame>; 2],
    /// Per tool (0) and base (1), why a frame selected now is the controller's: the BAS
    /// package's correction frame switched on (`TOOL_CORR_ON = TRUE`), which `TOOL(n)`,
    /// `BASE(n)` and the inline forms link to every frame they select until it is off again.
    pub(super) corrected: [Option<String>; 2],
}

/// `code` upper case without blanks.
pub(super) fn compact(code: &str) -> String {
    code.chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase()
}

/// The frame of a tool (`base` false) or base number `n` as `TOOL(n)`/`BASE(n)` set it.
fn numbered(line: u64, n: i64, base: bool) -> Frame {
    match (n, base) {
        (..=0, _) => Frame::World,
        (n, true) if n > MAX_BASE => Frame::Unknown(line, format!("base number {n} on line {line} selects an external kinematic (BAS EX_BASE: above {MAX_BASE}), whose frame moves with its axes: stiffid does not follow it")),
        (n, _) => match u32::try_from(n) {
            Ok(n) => Frame::Numbered(line, n),
            Err(_) => Frame::Unknown(line, format!("frame number {n} on line {line} is out of range")),
        },
    }
}

impl Frames {
    /// Before any line: neither frame set.
    pub(super) fn new(unset: impl Fn(&str) -> Frame) -> Self {
        Frames {
            base: unset("$BASE"),
            tool: unset("$TOOL"),
            act: None,
            external: None,
            table: HashMap::new(),
            any_entry: [None, None],
            corrected: [None, None],
        }
    }

    /// Reads the statement `code` (its comment removed) on `line` if it sets a frame or the
    /// frame data; whether it did (`BAS(#PTP_PARAMS)`/`#CP_PARAMS` also set the speed, which
    /// the caller reads too).
    pub(crate) fn set(&mut self, line: u64, code: &str, fdats: &Fdats) -> bool {
        let c = compact(code);
        if let Some((base, n, frame)) = table_entry(line, &c, code) {
            match n {
                Some(n) => _ = self.table.insert((base, n), frame),
                None => self.any_entry[usize::from(base)] = Some(frame),
            }
            return true;
        }
        if let Some(member) = ["$BASE.", "$TOOL."].iter().find(|m| c.starts_with(**m)) {
            let why = format!("a member of {} assigned ({}): stiffid reads a whole frame; set {} = {{X .., Y .., Z .., A .., B .., C ..}}", &member[..5], short(code.trim()), &member[..5]);
            *(if member.starts_with("$BASE") {
                &mut self.base
            } else {
                &mut self.tool
            }) = Frame::Unknown(line, why);
            return true;
        }
        let before = (self.base.clone(), self.tool.clone());
        let set = self.select(line, code, &c, fdats);
        // A number selected here takes the program's entry; one selected before keeps the
        // frame it copied then (KRL assigns frames by value).
        if self.base != before.0 {
            self.base = self.as_assigned(self.base.clone(), true);
        }
        if self.tool != before.1 {
            self.tool = self.as_assigned(self.tool.clone(), false);
        }
        self.base = self.corrected(line, self.base.clone(), before.0 != self.base, true);
        self.tool = self.corrected(line, self.tool.clone(), before.1 != self.tool, false);
        set
    }

    /// `frame`, newly selected (`changed`) on `line` as a tool or `base`, as the BAS package's
    /// correction frame in force leaves it: a frame selected by number or an inline form while
    /// `TOOL_CORR_ON`/`BASE_CORR_ON` is TRUE is linked to the correction, which stiffid does
    /// not apply (a literal frame assigned is not).
    fn corrected(&self, line: u64, frame: Frame, changed: bool, base: bool) -> Frame {
        match (&self.corrected[usize::from(base)], &frame) {
            (Some(why), Frame::Numbered(..) | Frame::World) if changed => {
                Frame::Unknown(line, why.clone())
            }
            _ => frame,
        }
    }

    /// A numbered frame (`base` or tool) as the program's own assignment of its table entry
    /// holds it, if it assigns one; `frame` otherwise.
    fn as_assigned(&self, frame: Frame, base: bool) -> Frame {
        match (frame, &self.any_entry[usize::from(base)]) {
            (Frame::Numbered(..), Some(any)) => any.clone(),
            (Frame::Numbered(l, n), None) => {
                (self.table.get(&(base, n)).cloned()).unwrap_or(Frame::Numbered(l, n))
            }
            (other, _) => other,
        }
    }

    /// [`Frames::set`] past the table's entries: a statement `code` (`c` compact) that selects
    /// a frame, sets the frame data or applies them.
    fn select(&mut self, line: u64, code: &str, c: &str, fdats: &Fdats) -> bool {
        let held = |what: &str| Frame::Unknown(line, what.to_string());
        if let Some(v) = c.strip_prefix("$IPO_MODE=") {
            self.external = (v != "#BASE").then_some(line);
        } else if let Some(v) = c.strip_prefix("FDAT_ACT=") {
            self.act = Some((line, self.record(line, v, code, fdats)));
        } else if let Some(member) = c.strip_prefix("FDAT_ACT.") {
            let act = self.act.take().map(|(_, r)| r);
            let value = act.and_then(|r| r.ok()).map(|mut f| {
                let (name, v) = member.split_once('=').unwrap_or((member, ""));
                let n = whole(v, name).ok();
                match (name, n) {
                    ("TOOL_NO", Some(n)) => f.tool = n,
                    ("BASE_NO", Some(n)) => f.base = n,
                    ("IPO_FRAME", _) if v == "#BASE" || v == "#TCP" => f.external = v == "#TCP",
                    _ => {
                        return Err(format!(
                            "FDAT_ACT.{} on line {line} is not a literal stiffid reads",
                            short(member)
                        ))
                    }
                }
                Ok(f)
            });
            let why = format!(
                "FDAT_ACT.{} is set on line {line} before FDAT_ACT is",
                short(member)
            );
            self.act = Some((line, value.unwrap_or(Err(why))));
        } else if ["BAS(#FRAMES", "BAS(#PTP_PARAMS", "BAS(#CP_PARAMS"]
            .iter()
            .any(|b| c.starts_with(b))
        {
            self.apply(line);
        } else if c.starts_with("BAS(#INITMOV") {
            let why = format!("BAS(#INITMOV) on line {line} sets it to the BAS package's default, which differs between KUKA System Software versions; set it in the program (an inline form, $TOOL/$BASE = ..)");
            (self.base, self.tool) = (held(&why), held(&why));
        } else if let Some(n) = c
            .strip_prefix("BAS(#TOOL,")
            .or(c.strip_prefix("BAS(#BASE,"))
        {
            let base = c.starts_with("BAS(#BASE");
            let frame = match whole(n.trim_end_matches(')'), "the number") {
                Ok(n) => numbered(line, n, base),
                Err(why) => held(&format!(
                    "{} on line {line}: {why} (a variable is the controller's)",
                    short(code.trim())
                )),
            };
            *(if base { &mut self.base } else { &mut self.tool }) = frame;
        } else if let Some((base, on)) = correction_switch(c) {
            self.corrected[usize::from(base)] = on.then(|| format!("the BAS package's correction frame is switched on (line {line}: {}) and links {} selected after it to the correction, which stiffid does not apply; switch it off before the motions or apply the correction to the frames in the setup's [controller] tables", short(code.trim()), if base { "every base" } else { "every tool" }));
            let why = format!("line {line} sets a correction frame of the BAS package ({}), which stiffid does not apply", short(code.trim()));
            (self.base, self.tool) = (held(&why), held(&why));
        } else if c.starts_with("TOOL_CORR") || c.starts_with("BASE_CORR") {
            let why = format!("line {line} sets a correction frame of the BAS package ({}), which stiffid does not apply", short(code.trim()));
            (self.base, self.tool) = (held(&why), held(&why));
        } else if let Some((base, frame)) =
            assigned(line, c).or_else(|| super::cartesian::frame_set(line, code))
        {
            *(if base { &mut self.base } else { &mut self.tool }) = frame;
        } else {
            return false;
        }
        true
    }

    /// The record `FDAT_ACT` takes from `value` (compact) on `line`: a declared record's or a
    /// literal one.
    fn record(&self, line: u64, value: &str, code: &str, fdats: &Fdats) -> FdatRead {
        if value.starts_with('{') {
            let literal = code.split_once('=').map_or("", |(_, v)| v);
            return fdat(literal).map_err(|why| format!("FDAT_ACT on line {line}: {why}"));
        }
        match fdats.get(value) {
            Some((_, Ok(f))) => Ok(*f),
            Some((at, Err(why))) => Err(format!("FDAT_ACT = {value} on line {line}: {value}, declared {at}, {why}")),
            None => Err(format!("FDAT_ACT = {} on line {line}: not a frame data record declared in the .src or its .dat (one of $config.dat, such as FHOME, is the controller's); declare it there", short(value))),
        }
    }

    /// `FRAMES` of the BAS package on `line`: the tool, base and interpolation mode of
    /// `FDAT_ACT`.
    fn apply(&mut self, line: u64) {
        let record = match &self.act {
            None => Err(format!("line {line} applies FDAT_ACT (BAS FRAMES), which the program does not set before it")),
            Some((_, r)) => r.clone(),
        };
        (self.base, self.tool, self.external) = match record {
            Ok(f) => (
                numbered(line, f.base, true),
                numbered(line, f.tool, false),
                f.external.then_some(line),
            ),
            Err(why) => (
                Frame::Unknown(line, why.clone()),
                Frame::Unknown(line, why),
                None,
            ),
        };
    }

    /// The base and tool of the motion on `line` whose code `code` may have its own
    /// `WITH $TOOL = .., $BASE = .., $IPO_MODE = ..`; refused frames as [`Frame::Unknown`].
    /// With a frame of its own, the frames in force after the motion are the controller's
    /// (`WITH` holds for the motion): both become unknown.
    pub(crate) fn motion(&mut self, line: u64, code: &str, fdats: &Fdats) -> (Frame, Frame) {
        let c = compact(code);
        let with = c.split_once("WITH").map_or("", |(_, w)| w);
        let items = split_top(with, ',');
        let (mut base, mut tool, mut external) =
            (self.base.clone(), self.tool.clone(), self.external);
        let mut own = false;
        for item in &items {
            let Some((name, value)) = item.split_once('=') else {
                continue;
            };
            match name {
                "$TOOL" => {
                    let t = self.as_assigned(self.with_frame(line, value, false, fdats), false);
                    tool = self.corrected(line, t, true, false);
                }
                "$BASE" => {
                    let b = self.as_assigned(self.with_frame(line, value, true, fdats), true);
                    base = self.corrected(line, b, true, true);
                }
                "$IPO_MODE" => {
                    external = match with_ipo(value, fdats) {
                        Some(false) => None,
                        _ => Some(line),
                    }
                }
                _ => continue,
            }
            own = true;
        }
        if let Some(l) = external {
            let why = format!("an external TCP (IPO_FRAME #TCP or $IPO_MODE other than #BASE, line {l}): the tool is fixed in the cell and the part on the flange, which stiffid does not compensate");
            (base, tool) = (Frame::Unknown(line, why.clone()), Frame::Unknown(line, why));
        }
        if own {
            let why = format!("the motion on line {line} sets its frames in its WITH, for that motion only: the ones in force after it are the controller's; set them again");
            (self.base, self.tool) = (Frame::Unknown(line, why.clone()), Frame::Unknown(line, why));
        }
        (base, tool)
    }

    /// A `WITH $TOOL =` (`base` false) or `$BASE =` value (compact) on `line`.
    fn with_frame(&self, line: u64, value: &str, base: bool, fdats: &Fdats) -> Frame {
        let name = if base { "$BASE" } else { "$TOOL" };
        if let Some((_, f)) = assigned(line, &format!("{name}={value}")) {
            return f;
        }
        // STOOL2(FP1), SBASE(FP1.BASE_NO): the record's number.
        let record = value
            .strip_prefix("STOOL2(")
            .or_else(|| value.strip_prefix("SBASE("))
            .and_then(|r| r.strip_suffix(')'))
            .map(|r| r.split('.').next().unwrap_or(r));
        let found = record.map(|r| match fdats.get(r) {
            Some((_, Ok(f))) => Ok(if base { f.base } else { f.tool }),
            Some((at, Err(why))) => Err(format!("{r}, declared {at}, {why}")),
            None => Err(format!(
                "{r} is not a frame data record declared in the .src or its .dat"
            )),
        });
        match found {
            Some(Ok(n)) => numbered(line, n, base),
            Some(Err(why)) => Frame::Unknown(line, format!("WITH {name} on line {line}: {why}")),
            None => Frame::Unknown(line, format!("WITH {name} = {} on line {line}: a frame stiffid cannot know (expected STOOL2(FP..), SBASE(FP...BASE_NO), {}_DATA[n] or a literal frame)", short(value), if base { "BASE" } else { "TOOL" })),
        }
    }

    /// Every frame and the frame data become the controller's from `line`, for the reason
    /// `why` (a frame set inside a loop or branch, a call of a routine that sets one).
    pub(crate) fn unsettle(&mut self, line: u64, why: String) {
        self.act = Some((line, Err(why.clone())));
        (self.base, self.tool) = (Frame::Unknown(line, why.clone()), Frame::Unknown(line, why));
    }
}

/// An assignment to an entry of the controller's base or tool table on `line` (`c` compact,
/// `code` as written): whether a base (`true`) or a tool, the entry's number (`None` for an
/// index that is not a literal number: any entry), and the frame it holds from then on: the
/// literal frame of `BASE_DATA[n] = {..}` as `$BASE = {..}` reads it, or a frame refused naming
/// the line (a member assigned, `BASE_DATA[n].X = ..`; a value or index the program does not
/// state).
pub(super) fn table_entry(line: u64, c: &str, code: &str) -> Option<(bool, Option<u32>, Frame)> {
    let (base, rest) = match c {
        _ if c.starts_with("BASE_DATA[") => (true, &c["BASE_DATA[".len()..]),
        _ if c.starts_with("TOOL_DATA[") => (false, &c["TOOL_DATA[".len()..]),
        _ => return None,
    };
    let table = if base { "BASE_DATA" } else { "TOOL_DATA" };
    let (index, after) = rest.split_once(']').unwrap_or((rest, ""));
    let n = index.parse::<u32>().ok();
    let refused = |what: String| {
        Frame::Unknown(line, format!("{what} assigned ({}), which stiffid does not follow; assign {table}[n] = {{X .., Y .., Z .., A .., B .., C ..}} with n a number", short(code.trim())))
    };
    let frame = match (n, after.strip_prefix('=')) {
        (None, _) => refused(format!("an entry of {table} whose index is not a number")),
        (Some(_), None) => refused(format!("a member of an entry of {table}")),
        (Some(_), Some(_)) => {
            let name = if base { "$BASE" } else { "$TOOL" };
            let value = code.split_once('=').map_or("", |(_, v)| v);
            match super::cartesian::frame_set(line, &format!("{name} = {value}")) {
                Some((_, frame)) => frame,
                None => refused(format!("an entry of {table}")),
            }
        }
    };
    Some((base, n, frame))
}

/// `$TOOL = TOOL_DATA[n]` or `$BASE = BASE_DATA[n]` (compact, `n` a literal): the frame.
fn assigned(line: u64, c: &str) -> Option<(bool, Frame)> {
    let (base, rest) = match c {
        _ if c.starts_with("$TOOL=TOOL_DATA[") => (false, &c["$TOOL=TOOL_DATA[".len()..]),
        _ if c.starts_with("$BASE=BASE_DATA[") => (true, &c["$BASE=BASE_DATA[".len()..]),
        _ => return None,
    };
    let frame = match rest.strip_suffix(']').map(|n| n.parse::<u32>()) {
        Some(Ok(n)) if n >= 1 => Frame::Numbered(line, n),
        _ => Frame::Unknown(line, format!("{} on line {line}: a frame stiffid cannot know (the index is not a literal number from 1, or an operator follows)", short(c))),
    };
    Some((base, frame))
}

/// The value of `WITH $IPO_MODE =` (compact): `Some(false)` for the base (`#BASE`, or
/// `SIPO_MODE(FP1.IPO_FRAME)` of a record with `#BASE`), `Some(true)` for an external TCP,
/// `None` when it cannot be known.
fn with_ipo(value: &str, fdats: &Fdats) -> Option<bool> {
    match value {
        "#BASE" => Some(false),
        "#TCP" => Some(true),
        _ => {
            let r = value.strip_prefix("SIPO_MODE(")?.split(['.', ')']).next()?;
            fdats
                .get(r)
                .and_then(|(_, f)| f.as_ref().ok())
                .map(|f| f.external)
        }
    }
}

/// The items of a `WITH` list (compact) split at the commas outside brackets, or of any text at
/// another separator `sep` (the operands of a geometric operator, `:`).
pub(super) fn split_top(with: &str, sep: char) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut depth = 0i32;
    for ch in with.chars() {
        match ch {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            c if c == sep && depth == 0 => {
                out.push(String::new());
                continue;
            }
            _ => {}
        }
        if let Some(last) = out.last_mut() {
            last.push(ch);
        }
    }
    out
}
