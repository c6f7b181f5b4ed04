//! Progress reports of long computations (the posture search, the simulation study), for a front
//! end to show: a stage begins with its units of work, advances, ends.

/// Receives the progress of a long computation. Every method does nothing by default; `()`
/// reports nowhere, and a closure `|done: usize| ...` receives [`Progress::advance`] only.
///
/// Calls may come from worker threads (hence `Sync`); `advance` counts are increasing within a
/// stage but may arrive out of order across threads.
pub trait Progress: Sync {
    /// A stage (`what`, e.g. `local search on zhang2021`) with `total` units of work begins.
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
