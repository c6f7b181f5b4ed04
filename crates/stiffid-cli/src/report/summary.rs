//! `summary.json` of `stiffid reproduce`: its document ([`stiffid::app::reproduce::document`]) as
//! text, and how a report directory is recognised as ours.

use anyhow::Result;
use serde_json::Value;
use std::path::Path;
use stiffid::app::reproduce::Report;

/// Whether `path` is a regular file `summary.json` (never waiting on a FIFO) whose `generator` is `generator` (e.g.
/// [`stiffid::app::reproduce::document::GENERATOR`]).
pub fn is_ours(path: &Path, generator: &str) -> bool {
    stiffid::internal::io::input::open(path)
        .ok()
        .and_then(|f| stiffid::internal::io::read_text("summary.json", f).ok())
        .and_then(|t| serde_json::from_str::<Value>(&t).ok())
        .is_some_and(|v| v["generator"] == generator)
}

/// The text of `summary.json`: the document `report` serialises to.
pub fn json(report: &Report) -> Result<String> {
    crate::output::json(report)
}
