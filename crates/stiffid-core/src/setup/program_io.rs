//! `[controller]`'s settings of generated programs: how they move between the path and the
//! cell (the rapid speeds `rapid_speed_mm_s`, `rapid_joint_pct` and the home posture
//! `home_deg`) and what they do at the G-code's process words (`[controller.io]`).
//!
//! ## `[controller.io]`
//! One key per process event of the G-code ([`ProcessEvent`]: `spindle_cw` for `M3`,
//! `tool_change` for `M6`, ...), its value one action or a list of actions, each in a
//! language-neutral form that every program language writes in its own way (as RoboDK's and the
//! CAM systems' robot posts map program events to a call or an output):
//! - a call of a routine the controller holds, `NAME` or `NAME(ARG, ..)`, each argument a number
//!   or the placeholder the event gives: `{rpm}` (the spindle speed `S` in force, rev/min) for
//!   the spindle events, `{tool}` (the tool number `T`) for the tool events:
//!   `spindle_cw = "SPINDLE_ON({rpm})"`;
//! - a digital output set on or off, by number or (RAPID, KRL) by its signal's name:
//!   `coolant_flood = "out[3] = on"`, `spindle_off = "out[doSpindle] = off"`.
//!
//! Every key, form, name and placeholder is checked on load, the error naming the key
//! (`controller.io.spindle_cw`); each language's rules (name lengths, outputs by number) are
//! checked when a program is written.

use crate::common::limits::{self, Range};
use crate::{Error, Result, Robot};
use std::collections::BTreeMap;

/// The range of `[controller] rapid_speed_mm_s`: the TCP speed of the joint motions to and
/// from the path (ABB `vrapid`), mm/s.
pub const RAPID_SPEED_MM_S: Range = Range::new(1.0, 10_000.0, "mm/s");
/// The range of `[controller] rapid_joint_pct`: the joint speed of rapid moves (KRL
/// `BAS(#VEL_PTP)`, FANUC `J .. %`, Yaskawa `VJ=`), percent of the axes' top speed.
pub const RAPID_JOINT_PCT: Range = Range::new(0.01, 100.0, "%");
/// The most actions of one `[controller.io]` event.
pub(crate) const MAX_ACTIONS: usize = 8;
/// The most arguments of one call.
pub(crate) const MAX_ARGUMENTS: usize = 8;
/// The longest routine or signal name accepted on load (each language's own limit is checked
/// when a program is written).
pub(crate) const MAX_NAME: usize = 64;

/// A process event of a G-code program: the words that raise it and the `[controller.io]` key
/// that maps it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ProcessEvent {
    /// An `S` word without `M3`/`M4` in its block: the spindle speed changes.
    SpindleSpeed,
    /// `M3`: the spindle turns clockwise (at the `S` in force).
    SpindleCw,
    /// `M4`: the spindle turns counter-clockwise.
    SpindleCcw,
    /// `M5`: the spindle stops.
    SpindleOff,
    /// `M7`: mist coolant on.
    CoolantMist,
    /// `M8`: flood coolant on.
    CoolantFlood,
    /// `M9`: coolant off.
    CoolantOff,
    /// A `T` word without `M6` in its block: the next tool is selected.
    ToolSelect,
    /// `M6`: the tool is changed (to the `T` in force).
    ToolChange,
    /// `M2` or `M30`: the program ends.
    ProgramEnd,
}

impl ProcessEvent {
    /// Every event, in the order of the reference's table.
    pub(crate) const ALL: [ProcessEvent; 10] = [
        ProcessEvent::SpindleSpeed,
        ProcessEvent::SpindleCw,
        ProcessEvent::SpindleCcw,
        ProcessEvent::SpindleOff,
        ProcessEvent::CoolantMist,
        ProcessEvent::CoolantFlood,
        ProcessEvent::CoolantOff,
        ProcessEvent::ToolSelect,
        ProcessEvent::ToolChange,
        ProcessEvent::ProgramEnd,
    ];

    /// Its `[controller.io]` key.
    pub fn key(self) -> &'static str {
        match self {
            ProcessEvent::SpindleSpeed => "spindle_speed",
            ProcessEvent::SpindleCw => "spindle_cw",
            ProcessEvent::SpindleCcw => "spindle_ccw",
            ProcessEvent::SpindleOff => "spindle_off",
            ProcessEvent::CoolantMist => "coolant_mist",
            ProcessEvent::CoolantFlood => "coolant_flood",
            ProcessEvent::CoolantOff => "coolant_off",
            ProcessEvent::ToolSelect => "tool_select",
            ProcessEvent::ToolChange => "tool_change",
            ProcessEvent::ProgramEnd => "program_end",
        }
    }

    /// The placeholder its actions may use: `{rpm}` for the spindle's speed and turning,
    /// `{tool}` for the tool events.
    pub(crate) fn placeholder(self) -> Option<Placeholder> {
        match self {
            ProcessEvent::SpindleSpeed | ProcessEvent::SpindleCw | ProcessEvent::SpindleCcw => {
                Some(Placeholder::Rpm)
            }
            ProcessEvent::ToolSelect | ProcessEvent::ToolChange => Some(Placeholder::Tool),
            _ => None,
        }
    }
}

/// A value an action takes from the G-code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Placeholder {
    /// `{rpm}`: the spindle speed `S` in force, rev/min.
    Rpm,
    /// `{tool}`: the tool number `T` in force.
    Tool,
}

impl Placeholder {
    /// How it is written: `{rpm}`, `{tool}`.
    pub(crate) fn text(self) -> &'static str {
        match self {
            Placeholder::Rpm => "{rpm}",
            Placeholder::Tool => "{tool}",
        }
    }
}

/// An argument of a call.
#[derive(Debug, Clone, PartialEq)]
pub enum Argument {
    /// A number, as written in the setup.
    Number(String),
    /// The G-code's value.
    Value(Placeholder),
}

/// A digital output: by number or by its signal's name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Signal {
    /// `out[3]`.
    Number(u32),
    /// `out[doSpindle]`.
    Name(String),
}

/// One action of an event.
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    /// A call of a routine the controller holds.
    Call {
        /// The routine's name (an identifier).
        name: String,
        /// Its arguments.
        arguments: Vec<Argument>,
    },
    /// A digital output set on or off.
    Output {
        /// Which.
        signal: Signal,
        /// On (`true`) or off.
        on: bool,
    },
}

/// `[controller.io]`: the actions of each mapped event ([`ProcessEvent`]); an event not mapped
/// is written as a comment with a warning.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Io {
    actions: BTreeMap<ProcessEvent, Vec<Action>>,
}

impl Io {
    /// The actions of `event`; `None` when it is not mapped.
    pub fn get(&self, event: ProcessEvent) -> Option<&[Action]> {
        self.actions.get(&event).map(Vec::as_slice)
    }

    /// The names of the routines any event calls, as written in the setup.
    pub fn routines(&self) -> impl Iterator<Item = &str> {
        (self.actions.values().flatten()).filter_map(|a| match a {
            Action::Call { name, .. } => Some(name.as_str()),
            Action::Output { .. } => None,
        })
    }

    /// `io` with `event` mapped to `actions` (checked as on load).
    ///
    /// # Errors
    /// As `Io::read`.
    pub fn with(mut self, event: ProcessEvent, actions: &[&str]) -> Result<Self> {
        let texts: Vec<String> = actions.iter().map(|a| a.to_string()).collect();
        self.actions.insert(event, read_actions(event, &texts)?);
        Ok(self)
    }

    /// The setup file's `[controller.io]`: each key an event's, each value one action or a
    /// list (module docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming `controller.io.KEY` for an unknown key, no action or more
    /// than [`MAX_ACTIONS`], an action of neither form, a name that is no identifier or longer
    /// than [`MAX_NAME`], more than [`MAX_ARGUMENTS`] arguments, an argument neither a finite
    /// number nor the event's placeholder.
    pub(crate) fn read(table: &BTreeMap<String, IoValue>) -> Result<Self> {
        let mut actions = BTreeMap::new();
        for (key, value) in table {
            let Some(event) = ProcessEvent::ALL.into_iter().find(|e| e.key() == key) else {
                let keys: Vec<&str> = ProcessEvent::ALL.iter().map(|e| e.key()).collect();
                return Err(io_error(
                    key,
                    format!("unknown event (expected one of {})", keys.join(", ")),
                ));
            };
            let texts = match value {
                IoValue::One(s) => vec![s.clone()],
                IoValue::Many(v) => v.clone(),
            };
            actions.insert(event, read_actions(event, &texts)?);
        }
        Ok(Self { actions })
    }
}

/// A `[controller.io]` value as the file gives it: one action or a list.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(untagged)]
pub(crate) enum IoValue {
    /// One action.
    One(String),
    /// Several, in order.
    Many(Vec<String>),
}

fn io_error(key: &str, message: String) -> Error {
    Error::InvalidField {
        field: format!("controller.io.{key}"),
        message,
    }
}

fn read_actions(event: ProcessEvent, texts: &[String]) -> Result<Vec<Action>> {
    let key = event.key();
    if texts.is_empty() || texts.len() > MAX_ACTIONS {
        return Err(io_error(
            key,
            format!("expected 1 to {MAX_ACTIONS} actions, got {}", texts.len()),
        ));
    }
    texts.iter().map(|t| action(event, t)).collect()
}

const FORMS: &str = "expected a call NAME or NAME(ARG, ..) (each argument a number or the event's placeholder) or an output out[N] = on|off, out[NAME] = on|off";

/// One action's text (module docs).
fn action(event: ProcessEvent, text: &str) -> Result<Action> {
    let key = event.key();
    let t = text.trim();
    let bad = |why: String| io_error(key, format!("{:?}: {why}", limits::short(t)));
    if let Some(rest) = t.strip_prefix("out[").or_else(|| t.strip_prefix("OUT[")) {
        let (signal, state) = rest.split_once(']').ok_or_else(|| bad(FORMS.into()))?;
        let state = state
            .trim()
            .strip_prefix('=')
            .ok_or_else(|| bad(FORMS.into()))?;
        let on = match state.trim().to_ascii_lowercase().as_str() {
            "on" => true,
            "off" => false,
            _ => return Err(bad("expected on or off after '='".into())),
        };
        let signal = signal.trim();
        let signal = match signal.parse::<u32>() {
            Ok(n) if n >= 1 => Signal::Number(n),
            Ok(_) => return Err(bad("output numbers start at 1".into())),
            Err(_) => Signal::Name(identifier(signal).map_err(bad)?),
        };
        return Ok(Action::Output { signal, on });
    }
    let (name, arguments) = match t.split_once('(') {
        None => (t, None),
        Some((name, rest)) => {
            let inner = rest.strip_suffix(')').ok_or_else(|| bad(FORMS.into()))?;
            (name.trim(), Some(inner))
        }
    };
    let name = identifier(name).map_err(|e| bad(format!("{e}; {FORMS}")))?;
    let arguments: Vec<Argument> = match arguments.map(str::trim) {
        None | Some("") => Vec::new(),
        Some(inner) => (inner.split(','))
            .map(|a| argument(event, a.trim()).map_err(&bad))
            .collect::<Result<_>>()?,
    };
    if arguments.len() > MAX_ARGUMENTS {
        return Err(bad(format!("at most {MAX_ARGUMENTS} arguments")));
    }
    Ok(Action::Call { name, arguments })
}

/// A routine's or signal's name: letters, digits and `_`, starting with a letter.
fn identifier(name: &str) -> std::result::Result<String, String> {
    let ok = name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    match (ok, name.len() <= MAX_NAME) {
        (true, true) => Ok(name.to_string()),
        (false, _) => Err(format!(
            "'{}' is no name (letters, digits and _, starting with a letter)",
            limits::short(name)
        )),
        (true, false) => Err(format!("a name of at most {MAX_NAME} characters")),
    }
}

fn argument(event: ProcessEvent, a: &str) -> std::result::Result<Argument, String> {
    if a.starts_with('{') {
        return match event.placeholder() {
            Some(p) if p.text() == a => Ok(Argument::Value(p)),
            Some(p) => Err(format!("'{a}': this event gives {} only", p.text())),
            None => Err(format!(
                "'{a}': this event gives no value (only the spindle events give {{rpm}}, the tool events {{tool}})"
            )),
        };
    }
    match a.parse::<f64>() {
        Ok(x) if x.is_finite() && !a.is_empty() => Ok(Argument::Number(a.to_string())),
        _ => Err(format!(
            "argument '{}': expected a number or the event's placeholder",
            limits::short(a)
        )),
    }
}

/// `[controller]`'s settings of generated programs (module docs).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ProgramSettings {
    /// `rapid_speed_mm_s`: the TCP speed of rapid moves where the language states one (ABB
    /// `vrapid`), m/s; `None`: the writer's default.
    pub rapid_speed: Option<f64>,
    /// `rapid_joint_pct`: the joint speed of rapid moves (KRL `BAS(#VEL_PTP)`, FANUC `J .. %`,
    /// Yaskawa `VJ=`), percent; `None`: the writer's default.
    pub rapid_joint_pct: Option<f64>,
    /// `home_deg`: the axis angles (deg) a program moves to before its first target and after
    /// its last; `None`: none.
    pub home_deg: Option<[f64; 6]>,
    /// `[controller.io]`.
    pub io: Io,
}

impl ProgramSettings {
    /// The setup file's fields, ranges checked ([`RAPID_SPEED_MM_S`], [`RAPID_JOINT_PCT`],
    /// [`limits::ANGLE_DEG`]).
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming the field; those of [`Io::read`].
    pub(crate) fn read(
        rapid_speed_mm_s: Option<f64>,
        rapid_joint_pct: Option<f64>,
        home_deg: Option<[f64; 6]>,
        io: &BTreeMap<String, IoValue>,
    ) -> Result<Self> {
        if let Some(v) = rapid_speed_mm_s {
            limits::check("controller.rapid_speed_mm_s", &[v], &RAPID_SPEED_MM_S)?;
        }
        if let Some(v) = rapid_joint_pct {
            limits::check("controller.rapid_joint_pct", &[v], &RAPID_JOINT_PCT)?;
        }
        if let Some(h) = &home_deg {
            limits::check("controller.home_deg", h, &limits::ANGLE_DEG)?;
        }
        Ok(Self {
            rapid_speed: rapid_speed_mm_s.map(|v| v * 1e-3),
            rapid_joint_pct,
            home_deg,
            io: Io::read(io)?,
        })
    }

    /// Checks the home posture against `robot`'s joint limits.
    ///
    /// # Errors
    /// [`Error::OutsideBox`] naming `controller.home_deg[i]`, the value and the axis's range.
    pub(crate) fn check(&self, robot: &Robot) -> Result<()> {
        let Some(h) = self.home_deg else {
            return Ok(());
        };
        let q = nalgebra::Vector6::from(h).map(f64::to_radians);
        let field = |a: usize| format!("controller.home_deg[{}]", a + 1);
        robot.limits().check(&q, "the robot's limits", field)
    }
}
