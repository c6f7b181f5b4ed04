//! What a program's statements set (its frames, tool, speed), followed along every path through
//! its branches and loops, so that each motion is read where it is, with what is in force there.
//!
//! A language's reader keeps its own state `S` (what is in force) and tells [`Paths`] where a
//! construct opens (`IF`, `FOR`: [`Paths::open`]), where one of its branches ends and the next
//! begins (`ELSE`, `CASE`: [`Paths::branch`]) and where it closes ([`Paths::close`]). Each branch
//! starts from the state before the construct; after it, the state is every path's joined
//! ([`Join`]): where two paths leave different values, the language's join states it (a frame
//! set in one branch only, naming both lines), and the motions that use it are refused there.
//! A loop's body may run any number of times, so the state after it is the entry's joined with
//! the body's end; a value the body changes reaches its own motions before the change on every
//! run after the first, which [`Closed::changed`] lets the reader check.

/// The most motions the unrolled loops of a module give (over every loop; RAPID's and KRL's
/// `FOR` loops whose motions read their variable).
pub(crate) const MOST: usize = 10_000;

/// The most statements the unrolled loops of a module give (motions or not).
pub(crate) const MOST_STEPS: usize = 200_000;

/// A state that joins another: the value after two paths that meet.
pub(crate) trait Join: Clone {
    /// `self`, the state at the end of one path, joined with `other`'s, the state at the end of
    /// another, where they meet after the construct `word` opened on `line`: a value both
    /// leave alike stays, one they leave differently becomes unknown, naming the lines.
    fn join(&mut self, other: &Self, construct: (&str, u64));
    /// Whether `other` holds the same values as `self` (the lines that set them aside).
    fn agrees(&self, other: &Self) -> bool;
}

/// What a construct is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Its body is its first branch (`IF .. THEN`): others follow ([`Paths::branch`]).
    Branches,
    /// Its branches start at the first branch word (`SWITCH` then `CASE`, `TEST` then
    /// `CASE`): the lines before it are no path.
    Cases,
    /// Its body runs any number of times (`FOR`, `WHILE`, `LOOP`, `REPEAT`).
    Loop,
}

/// A construct open: its word and line, the state before it, the ends of its branches so far,
/// whether a branch covers every case (`ELSE`, `DEFAULT`), whether it repeats, and the caller's
/// mark (where its motions begin).
#[derive(Debug, Clone)]
struct Open<S> {
    word: String,
    line: u64,
    entry: S,
    ends: Vec<S>,
    exhaustive: bool,
    kind: Kind,
    /// Whether a branch has begun (a [`Kind::Cases`] has none before its first case).
    started: bool,
    mark: usize,
}

/// A construct closed ([`Paths::close`]).
#[derive(Debug, Clone)]
pub(crate) struct Closed<S> {
    /// Its word and line.
    pub word: String,
    /// The line that opened it.
    pub line: u64,
    /// The caller's mark given to [`Paths::open`].
    pub mark: usize,
    /// For a loop whose body ends in another state than it began: the state it began in and the
    /// one it ended in (the motions of the body before the change see the latter on a repeat).
    pub changed: Option<(S, S)>,
}

/// The constructs open at a statement, outermost first (module docs).
#[derive(Debug, Clone)]
pub(crate) struct Paths<S> {
    open: Vec<Open<S>>,
}

impl<S> Default for Paths<S> {
    fn default() -> Self {
        Paths { open: Vec::new() }
    }
}

impl<S: Join> Paths<S> {
    /// A construct `word` of `kind` opens on `line` with `state` in force; `mark`: the
    /// caller's (the number of targets read so far), given back by [`Paths::close`].
    pub(crate) fn open(&mut self, (word, line): (&str, u64), state: &S, kind: Kind, mark: usize) {
        self.open.push(Open {
            word: word.to_string(),
            line,
            entry: state.clone(),
            ends: Vec::new(),
            exhaustive: false,
            kind,
            started: kind != Kind::Cases,
            mark,
        });
    }

    /// The branch before ends and another begins (`ELSEIF`, `ELSE`, `CASE`, `DEFAULT`) in the
    /// innermost construct: `state` becomes the construct's entry state; `exhaustive`: the new
    /// branch is taken when no other is (`ELSE`, `DEFAULT`). Outside a construct, nothing.
    pub(crate) fn branch(&mut self, state: &mut S, exhaustive: bool) {
        if let Some(o) = self.open.last_mut() {
            let end = std::mem::replace(state, o.entry.clone());
            if o.started {
                o.ends.push(end);
            }
            o.started = true;
            o.exhaustive |= exhaustive;
        }
    }

    /// The innermost construct closes: `state` becomes every path's joined (the branches' ends,
    /// and the entry where no branch may be taken or the body may not run); `None` outside one.
    pub(crate) fn close(&mut self, state: &mut S) -> Option<Closed<S>> {
        let o = self.open.pop()?;
        let end = state.clone();
        let mut paths = o.ends;
        if o.started {
            paths.push(end.clone());
        }
        let repeats = o.kind == Kind::Loop;
        if !o.exhaustive || repeats {
            paths.push(o.entry.clone());
        }
        let mut joined = paths[0].clone();
        for p in &paths[1..] {
            joined.join(p, (&o.word, o.line));
        }
        *state = joined;
        let changed = (repeats && !end.agrees(&o.entry)).then_some((o.entry, end));
        Some(Closed {
            word: o.word,
            line: o.line,
            mark: o.mark,
            changed,
        })
    }

    /// The outermost construct open, if any: its word and line.
    #[cfg(test)]
    pub(crate) fn inside(&self) -> Option<(&str, u64)> {
        self.open.first().map(|o| (o.word.as_str(), o.line))
    }

    /// Every construct closes (a routine ends): nothing open.
    pub(crate) fn clear(&mut self) {
        self.open.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A value set on a line, or unknown naming the lines of the paths that disagree.
    #[derive(Debug, Clone, PartialEq)]
    enum V {
        Set(u64, i32),
        Unknown(Vec<u64>),
    }

    impl Join for V {
        fn join(&mut self, other: &Self, _: (&str, u64)) {
            match (&*self, other) {
                (V::Set(_, a), V::Set(_, b)) if a == b => {}
                (V::Set(l, _), V::Set(m, _)) => *self = V::Unknown(vec![*l, *m]),
                _ => *self = V::Unknown(vec![]),
            }
        }
        fn agrees(&self, other: &Self) -> bool {
            match (self, other) {
                (V::Set(_, a), V::Set(_, b)) => a == b,
                _ => false,
            }
        }
    }

    #[test]
    fn a_value_set_in_one_branch_only_is_unknown_after_it_naming_both_lines() {
        let mut p = Paths::default();
        let mut s = V::Set(1, 0);
        p.open(("IF", 2), &s, Kind::Branches, 0);
        s = V::Set(3, 7);
        let closed = p.close(&mut s).unwrap();
        assert_eq!(s, V::Unknown(vec![3, 1]));
        assert_eq!((closed.word.as_str(), closed.line), ("IF", 2));
        assert!(closed.changed.is_none());
    }

    #[test]
    fn branches_that_agree_keep_the_value_and_else_excludes_the_entry() {
        let mut p = Paths::default();
        let mut s = V::Set(1, 0);
        p.open(("IF", 2), &s, Kind::Branches, 0);
        s = V::Set(3, 7);
        p.branch(&mut s, true);
        assert_eq!(s, V::Set(1, 0), "the ELSE branch starts from the entry");
        s = V::Set(5, 7);
        p.close(&mut s).unwrap();
        assert_eq!(s, V::Set(3, 7));
    }

    #[test]
    fn a_loop_that_changes_a_value_says_so_with_its_mark() {
        let mut p = Paths::default();
        let mut s = V::Set(1, 0);
        p.open(("LOOP", 2), &s, Kind::Loop, 4);
        assert_eq!(p.inside(), Some(("LOOP", 2)));
        s = V::Set(3, 7);
        let closed = p.close(&mut s).unwrap();
        assert_eq!(closed.mark, 4);
        assert_eq!(closed.changed, Some((V::Set(1, 0), V::Set(3, 7))));
        assert_eq!(s, V::Unknown(vec![3, 1]));
        assert!(p.close(&mut s).is_none());
    }

    #[test]
    fn cases_with_a_default_that_all_set_one_value_keep_it() {
        let mut p = Paths::default();
        let mut s = V::Set(1, 0);
        p.open(("SWITCH", 2), &s, Kind::Cases, 0);
        p.branch(&mut s, false);
        s = V::Set(4, 7);
        p.branch(&mut s, true);
        s = V::Set(6, 7);
        p.close(&mut s).unwrap();
        assert_eq!(s, V::Set(4, 7));
    }
}
