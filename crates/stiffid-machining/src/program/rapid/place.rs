//! Where a statement of a RAPID module sits among the motions the robot makes (module `calls`'s
//! rule): after a motion, before one, or both (between two). Within its routine, in the order
//! of the text, a statement of a `WHILE` or `FOR` loop that moves is between two of its
//! motions; a routine's statements sit, besides, where its calls in the module sit (a routine
//! called between two motions runs between them), and the routine the task calls (`entry`)
//! where its call sits.

use std::collections::HashMap;

/// Where a statement runs among the motions: after one on some path, before one on some path.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Place {
    /// A motion may run before it.
    pub after_first: bool,
    /// A motion may run after it.
    pub before_last: bool,
}

impl Place {
    /// Both: the statement runs between two motions.
    pub(super) fn between(self) -> bool {
        self.after_first && self.before_last
    }

    fn or(self, other: Place) -> Place {
        Place {
            after_first: self.after_first || other.after_first,
            before_last: self.before_last || other.before_last,
        }
    }
}

/// One statement as [`places`] sees it.
#[derive(Debug, Clone, Default)]
pub(super) struct Seen {
    /// The routine it is in (an index into the module's routines), none outside one.
    pub routine: Option<usize>,
    /// It moves the robot: a motion, or a call of a procedure that may.
    pub moving: bool,
    /// It opens (`1`) or closes (`-1`) a `WHILE` or `FOR` loop.
    pub loop_step: i8,
    /// The routine of the module it calls, if any.
    pub calls: Option<usize>,
}

/// How deep calls of the module's routines are followed to place a routine's statements; a
/// longer chain (or a routine that calls itself) is taken to run between two motions.
const DEPTH: usize = 16;

/// Each statement's place (module docs): `seen` the statements, `entry` the place of each
/// routine the task calls from outside the module (by index).
pub(super) fn places(seen: &[Seen], entry: &HashMap<usize, Place>) -> Vec<Place> {
    let own = own_places(seen);
    let mut memo: HashMap<usize, Place> = HashMap::new();
    (0..seen.len())
        .map(|k| match seen[k].routine {
            Some(r) => own[k].or(routine_entry(r, seen, &own, entry, &mut memo, 0)),
            None => own[k],
        })
        .collect()
}

/// Each statement's place within its routine and loops alone.
fn own_places(seen: &[Seen]) -> Vec<Place> {
    let mut out = vec![Place::default(); seen.len()];
    // Per routine, the first and last moving statements.
    let mut ends: HashMap<usize, (usize, usize)> = HashMap::new();
    for (k, s) in seen.iter().enumerate().filter(|(_, s)| s.moving) {
        if let Some(r) = s.routine {
            ends.entry(r).and_modify(|e| e.1 = k).or_insert((k, k));
        }
    }
    for (k, s) in seen.iter().enumerate() {
        if let Some(&(first, last)) = s.routine.and_then(|r| ends.get(&r)) {
            out[k].after_first = first < k;
            out[k].before_last = k < last;
        }
    }
    // A loop that moves: each of its statements between two of its motions.
    let mut open: Vec<usize> = Vec::new();
    for (k, s) in seen.iter().enumerate() {
        match s.loop_step {
            1 => open.push(k),
            -1 => {
                if let Some(start) = open.pop()
                    && seen[start..=k].iter().any(|s| s.moving)
                {
                    let both = Place {
                        after_first: true,
                        before_last: true,
                    };
                    out[start..=k].iter_mut().for_each(|p| *p = both);
                }
            }
            _ => {}
        }
    }
    out
}

/// Where routine `r` runs: the places of its calls in the module, joined (`entry` for one the
/// task calls).
fn routine_entry(
    r: usize,
    seen: &[Seen],
    own: &[Place],
    entry: &HashMap<usize, Place>,
    memo: &mut HashMap<usize, Place>,
    depth: usize,
) -> Place {
    if let Some(p) = memo.get(&r) {
        return *p;
    }
    let both = Place {
        after_first: true,
        before_last: true,
    };
    if depth >= DEPTH {
        return both;
    }
    // A routine that calls itself: between, until its calls are known.
    memo.insert(r, both);
    let mut place = entry.get(&r).copied().unwrap_or_default();
    for (k, s) in seen.iter().enumerate().filter(|(_, s)| s.calls == Some(r)) {
        let caller = match s.routine {
            Some(c) if c != r => routine_entry(c, seen, own, entry, memo, depth + 1),
            Some(_) => both,
            None => Place::default(),
        };
        place = place.or(own[k]).or(caller);
    }
    memo.insert(r, place);
    place
}
