//! The `//POS` section of a job: its teaching positions, the form and tool file each was taught
//! in, and `///NPOS` (module docs of [`super`]).

use super::rconf::Rconf;
use crate::program::{at, number_at};
use std::collections::HashMap;
use std::ops::Range;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// How a block of positions is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Form {
    Pulse,
    Angle,
    Rectan,
}

/// The three kinds of teaching positions a motion names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Kind {
    Robot,
    Base,
    Station,
}

impl Kind {
    pub(super) fn prefix(self) -> &'static str {
        match self {
            Kind::Robot => "C",
            Kind::Base => "BC",
            Kind::Station => "EC",
        }
    }
}

/// A teaching position: its line, form, values with their spans, the tool file it was taught
/// with (`///TOOL n` before it, with its line) and, in Cartesian form, the frame it names
/// (`///POSTYPE`), its user frame (`///USER n`, with its line) and its manipulator type
/// (`///RCONF`, with its line).
pub(super) struct Position {
    pub line: u64,
    pub form: Form,
    pub values: Vec<(f64, Range<usize>)>,
    pub tool: Option<(u64, u32)>,
    pub frame: String,
    pub user: Option<(u64, u32)>,
    pub rconf: Option<(u64, Rconf)>,
}

/// The positions by kind and number, `///NPOS`'s line and counts, and the robot position
/// variables the job lists (`P00016=..`: their values when it was saved) by number.
pub(super) struct Section {
    pub positions: HashMap<(Kind, u64), Position>,
    pub npos: Option<(u64, Vec<usize>)>,
    pub variables: HashMap<u64, Listed>,
}

/// A position variable as the job lists it: its line, form, tool file and values as written,
/// and in Cartesian form its frame (`///POSTYPE`), user frame and manipulator type.
pub(super) struct Listed {
    pub line: u64,
    pub form: Form,
    pub tool: Option<u32>,
    pub values: Vec<String>,
    pub frame: String,
    pub user: Option<u32>,
    pub rconf: Option<Rconf>,
}

/// The state of the `//POS` lines read so far: the form, tool file, frame, user frame and
/// manipulator type in force.
struct Block {
    form: Form,
    tool: Option<(u64, u32)>,
    frame: String,
    user: Option<(u64, u32)>,
    rconf: Option<(u64, Rconf)>,
}

/// The `//POS` section of `text`. A block with no `///POSTYPE` and form line holds pulses, the
/// form the controllers store a job in by default (YRC1000 and DX200 jobs load so).
pub(super) fn section(text: &str) -> Result<Section> {
    let mut out = Section {
        positions: HashMap::new(),
        npos: None,
        variables: HashMap::new(),
    };
    let mut in_pos = false;
    let mut block = Block {
        form: Form::Pulse,
        tool: None,
        frame: "PULSE".into(),
        user: None,
        rconf: None,
    };
    for (line, start, l) in crate::program::lines(text) {
        let t = l.trim();
        if let Some(section) = t.strip_prefix("//").filter(|s| !s.starts_with('/')) {
            in_pos = section.starts_with("POS");
            continue;
        }
        if !in_pos {
            continue;
        }
        if let Some(pseudo) = t.strip_prefix("///") {
            pseudo_line(line, pseudo, &mut block, &mut out)?;
            continue;
        }
        let Some((name, _)) = t.split_once('=') else {
            continue;
        };
        position(line, (start, l), name.trim(), &block, &mut out)?;
    }
    Ok(out)
}

/// Reads one `///` line of `//POS` into `block` (form, tool, frame) or `out` (`///NPOS`).
fn pseudo_line(line: u64, pseudo: &str, block: &mut Block, out: &mut Section) -> Result<()> {
    let mut words = pseudo.split_whitespace();
    let word = words.next().unwrap_or("");
    let rest: Vec<&str> = words.collect();
    match word {
        "PULSE" => block.form = Form::Pulse,
        "ANGLE" => block.form = Form::Angle,
        "RECTAN" => block.form = Form::Rectan,
        "POSTYPE" => block.frame = rest.join(" "),
        "TOOL" | "USER" => {
            let n = rest.first().and_then(|n| n.parse::<u32>().ok());
            let n = n.ok_or_else(|| at(line, format!("///{word}: expected a number")))?;
            match word {
                "TOOL" => block.tool = Some((line, n)),
                _ => block.user = Some((line, n)),
            }
        }
        "RCONF" => {
            let r = Rconf::parse(&rest.join(" ")).map_err(|why| at(line, why))?;
            block.rconf = Some((line, r));
        }
        "NPOS" => {
            let counts = pseudo[4..]
                .split(',')
                .map(|n| n.trim().parse::<usize>())
                .collect::<std::result::Result<Vec<_>, _>>()
                .map_err(|_| at(line, "///NPOS: expected six counts C,BC,EC,P,BP,EX".into()))?;
            out.npos = Some((line, counts));
        }
        _ => {}
    }
    Ok(())
}

/// Reads the position `name` on `line` (`l`, starting at byte `start` of the text) into `out`.
fn position(
    line: u64,
    (start, l): (usize, &str),
    name: &str,
    block: &Block,
    out: &mut Section,
) -> Result<()> {
    let (kind, digits) = match name {
        n if n.starts_with("BC") => (Kind::Base, &n[2..]),
        n if n.starts_with("EC") => (Kind::Station, &n[2..]),
        n if n.starts_with('C') => (Kind::Robot, &n[1..]),
        // A robot position variable's value when the job was saved: the controller holds it.
        n if n.starts_with('P') && n[1..].bytes().all(|b| b.is_ascii_digit()) => {
            if let Ok(index) = n[1..].parse::<u64>() {
                let values = l.split_once('=').map_or("", |(_, v)| v).split(',');
                let listed = Listed {
                    line,
                    form: block.form,
                    tool: block.tool.map(|(_, n)| n),
                    values: values.map(|v| v.trim().to_string()).collect(),
                    frame: block.frame.clone(),
                    user: block.user.map(|(_, n)| n),
                    rconf: block.rconf.map(|(_, r)| r),
                };
                out.variables.insert(index, listed);
            }
            return Ok(());
        }
        // Base and station variables' values: held on the controller.
        _ => return Ok(()),
    };
    let index: u64 = digits
        .parse()
        .map_err(|_| at(line, format!("{}: expected a position number", short(name))))?;
    let mut values = Vec::new();
    let mut from = l.find('=').map_or(l.len(), |e| e + 1);
    loop {
        let (v, span) = number_at(l, from)
            .ok_or_else(|| at(line, format!("{name}: expected numbers separated by ','")))?;
        if block.form == Form::Pulse && l[span.clone()].contains(['.', 'e', 'E']) {
            let what = &l[span.clone()];
            return Err(at(
                line,
                format!("{name}: {what} is not a whole number of pulses"),
            ));
        }
        values.push((v, start + span.start..start + span.end));
        let rest = l[span.end..].trim_start();
        match rest.strip_prefix(',') {
            Some(_) => from = l.len() - rest.len() + 1,
            None if rest.is_empty() => break,
            None => {
                let after = short(rest);
                return Err(at(line, format!("{name}: '{after}' after its values")));
            }
        }
    }
    let position = Position {
        line,
        form: block.form,
        values,
        tool: block.tool,
        frame: block.frame.clone(),
        user: block.user,
        rconf: block.rconf,
    };
    if let Some(first) = out.positions.insert((kind, index), position) {
        let first = first.line;
        return Err(at(
            line,
            format!("{name} defined twice in //POS (lines {first} and {line})"),
        ));
    }
    Ok(())
}
