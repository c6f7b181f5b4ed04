//! Progress reports of long computations (the posture search, the simulation study), for a front
//! end to show: a stage begins with its units of work, advances, ends.

use std::sync::atomic::{AtomicUsize, Ordering};

/// Receives the progress of a long computation. Every method does nothing by default; `()`
/// reports nowhere, and a closure `|done: usize| ...` receives [`Progress::advance`] only.
///
/// Calls may come from worker threads (hence `Sync`); `advance` counts are increasing within a
/// stage but may arrive out of order across threads.
pub trait Progress: Sync {
    /// A stage (`what`, e.g. `searches`) with `total` units of work begins.
    fn begin(&self, _what: &str, _total: usize) {}
    /// `done` units of the current stage are finished.
    fn advance(&self, _done: usize) {}
    /// The current stage is finished.
    fn end(&self) {}
}

impl Progress for () {}

impl<F: Fn(usize) + Sync> Progress for F {
    fn advance(&self, done: usize) {
        self(done)
    }
}

/// One stage whose work runs as several parts at once: each part adds its units, or reports its
/// own increasing count through a [`Part`]; the stage hears the sum.
pub struct Tally<'a> {
    to: &'a dyn Progress,
    done: AtomicUsize,
}

impl<'a> Tally<'a> {
    /// A tally of the current stage of `to`, at 0.
    pub fn new(to: &'a dyn Progress) -> Self {
        Self {
            to,
            done: AtomicUsize::new(0),
        }
    }

    /// `units` more are finished.
    pub fn add(&self, units: usize) {
        self.to
            .advance(self.done.fetch_add(units, Ordering::Relaxed) + units);
    }

    /// A part that reports its own count (for example a global search's starts).
    pub fn part(&self) -> Part<'_> {
        Part {
            tally: self,
            seen: AtomicUsize::new(0),
        }
    }
}

/// A part of a [`Tally`]: its `advance(done)` adds what is new since its last report.
pub struct Part<'a> {
    tally: &'a Tally<'a>,
    seen: AtomicUsize,
}

impl Progress for Part<'_> {
    fn advance(&self, done: usize) {
        let before = self.seen.fetch_max(done, Ordering::Relaxed);
        if done > before {
            self.tally.add(done - before);
        }
    }
}
