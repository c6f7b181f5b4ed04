//! What is in force while a KRL program is read (its frames and path speed), joined where the
//! paths through a branch or a loop meet ([`crate::program::paths`]): a frame, a frame data
//! record or a speed that two paths leave differently is unknown after them, naming the lines
//! that set each, so the motions that use it are refused there (or left as found).

use super::frames::Frames;
use super::speed;
use crate::program::cartesian::Frame;
use crate::program::paths::Join;
use crate::program::speed::Speed;

/// The frames and path speed in force.
#[derive(Debug, Clone)]
pub(super) struct State {
    /// `$BASE`, `$TOOL`, `FDAT_ACT` and the program's entries of the frame tables.
    pub frames: Frames,
    /// `$VEL.CP`.
    pub speed: speed::Krl,
    /// The points the program assigns, as the path read leaves them ([`super::assign`]).
    pub points: super::assign::Values,
}

/// Where a frame's value was set, in words (`line 5`, `the world`).
fn set_on(f: &Frame) -> String {
    match f {
        Frame::World => "the world frame".into(),
        Frame::Stated(l, _)
        | Frame::Numbered(l, _)
        | Frame::Declared(l, _)
        | Frame::Held(l, ..) => {
            format!("line {l}")
        }
        Frame::Unknown(0, _) => "none set".into(),
        Frame::Unknown(l, _) => format!("the controller's from line {l}"),
    }
}

/// Whether two frames are one value (the lines that set them aside).
pub(super) fn same(a: &Frame, b: &Frame) -> bool {
    match (a, b) {
        (Frame::World, Frame::World) => true,
        (Frame::Stated(_, x), Frame::Stated(_, y)) => x == y,
        (Frame::Numbered(_, m), Frame::Numbered(_, n)) => m == n,
        (Frame::Held(_, m, x, _), Frame::Held(_, n, y, _)) => m == n && x == y,
        (Frame::Declared(_, m), Frame::Declared(_, n)) => m == n,
        (Frame::Unknown(l, x), Frame::Unknown(m, y)) => l == m && x == y,
        _ => false,
    }
}

/// `a` joined with `b` after the construct `(word, line)`, for the frame `name` (`$BASE`).
fn join_frame(a: &Frame, b: &Frame, name: &str, (word, line): (&str, u64)) -> Frame {
    if same(a, b) {
        return a.clone();
    }
    if let Frame::Unknown(..) = a {
        return a.clone();
    }
    if let Frame::Unknown(..) = b {
        return b.clone();
    }
    Frame::Unknown(0, format!("the {name} in force here depends on the path taken through {word} (line {line}): one path leaves {} ({}), another {} ({}); set it alike on every path, or before {word}", describe(a), set_on(a), describe(b), set_on(b)))
}

/// A frame's value in words.
fn describe(f: &Frame) -> String {
    match f {
        Frame::World => "$WORLD".into(),
        Frame::Stated(..) => "a literal frame".into(),
        Frame::Numbered(_, n) | Frame::Held(_, n, ..) => format!("number {n}"),
        Frame::Declared(..) => "the setup's".into(),
        Frame::Unknown(..) => "an unknown frame".into(),
    }
}

impl Join for State {
    fn join(&mut self, other: &Self, construct: (&str, u64)) {
        let (a, b) = (&mut self.frames, &other.frames);
        a.base = join_frame(&a.base, &b.base, "$BASE", construct);
        a.tool = join_frame(&a.tool, &b.tool, "$TOOL", construct);
        if a.act.as_ref().map(|x| &x.1) != b.act.as_ref().map(|x| &x.1) {
            let (word, line) = construct;
            let set = |act: &Option<(u64, _)>| match act {
                Some((l, _)) if *l > 0 => format!("sets it on line {l}"),
                _ => "does not set it".to_string(),
            };
            let why = format!("FDAT_ACT depends on the path taken through {word} (line {line}): one path {}, another {}; set it alike on every path, or before {word}", set(&a.act), set(&b.act));
            a.act = Some((0, Err(why)));
        }
        if a.external.is_some() != b.external.is_some() {
            a.external = a.external.or(b.external);
        }
        let (word, line) = construct;
        let keys: Vec<(bool, u32)> = a.table.keys().chain(b.table.keys()).copied().collect();
        for k in keys {
            let name = format!("{}_DATA[{}]", if k.0 { "BASE" } else { "TOOL" }, k.1);
            let joined = match (a.table.get(&k), b.table.get(&k)) {
                (Some(e), Some(f)) => join_frame(e, f, &name, construct),
                _ => Frame::Unknown(0, format!("{name} is assigned on one path through {word} (line {line}) only; assign it alike on every path, or before {word}")),
            };
            a.table.insert(k, joined);
        }
        for k in 0..2 {
            if a.corrected[k] != b.corrected[k] {
                let (word, line) = construct;
                a.corrected[k] = Some(format!("the BAS correction frame depends on the path taken through {word} (line {line}): switch it alike on every path, or before {word}"));
            }
        }
        for (k, e) in b.any_entry.iter().enumerate() {
            if a.any_entry[k].is_none() {
                a.any_entry[k] = e.clone();
            }
        }
        super::assign::join(&mut self.points, &other.points, construct);
        if self.speed.in_force != other.speed.in_force {
            self.speed.in_force = Speed::Unread(format!(
                "the path speed depends on the path taken through {word} (line {line})"
            ));
        }
    }

    fn agrees(&self, other: &Self) -> bool {
        let (a, b) = (&self.frames, &other.frames);
        same(&a.base, &b.base)
            && same(&a.tool, &b.tool)
            && a.act.as_ref().map(|x| &x.1) == b.act.as_ref().map(|x| &x.1)
            && a.external.is_some() == b.external.is_some()
            && a.corrected == b.corrected
            && self.speed.in_force == other.speed.in_force
    }
}
