//! What every condition and data file of a controller's backup (`TOOL.CND`, `UFRAME.CND`,
//! `VAR.DAT`) must be to be read: whole (the controller ends each line, the last too, with a
//! line end), and giving each number once.

use nalgebra::Isometry3;
use std::collections::BTreeMap;
use stiffid_core::{Error, Result};

/// Refuses the backup file `name` (`text`) when it ends inside a line: a file cut off there
/// reads as whole lines up to a number cut short (`30.0000` as `30.00`, or `3`).
///
/// # Errors
/// [`Error::Parse`] naming the file and its last line.
pub(super) fn whole(name: &str, text: &str) -> Result<()> {
    if text.is_empty() || text.ends_with(['\n', '\r']) {
        return Ok(());
    }
    let line = crate::program::lines(text).count();
    Err(Error::Parse {
        source_name: name.to_string(),
        message: format!("line {line}: the file ends inside this line, with no line end after it, as a file cut off does (the controller ends every line): give the whole file"),
    })
}

/// Refuses the backup file `name` when it holds no block of the frames it is read for
/// (`blocks` 0: an empty file, or one of headers and comments only), saying what a block of
/// `what` holds (`block`): a file given holds what the job is read with, and one that holds none was
/// cut off or is another file.
///
/// # Errors
/// [`Error::Parse`] naming the file.
pub(super) fn some(name: &str, blocks: usize, (what, block): (&str, &str)) -> Result<()> {
    match blocks {
        0 => Err(Error::Parse {
            source_name: name.to_string(),
            message: format!("no {what}: the file is empty or holds no block (a file cut off, or another file); expected per {what} {block}: give the file as the controller's backup holds it, or leave it out"),
        }),
        _ => Ok(()),
    }
}

/// Adds frame `n` read on `line` of `name` to `out`, refused where the file gave `n` another
/// frame before (one controller holds one frame per number; a file edited or two joined).
///
/// # Errors
/// [`Error::Parse`] naming the file and both lines.
pub(super) fn insert(
    out: &mut BTreeMap<u32, (Isometry3<f64>, String)>,
    (name, line, what): (&str, u64, &str),
    (n, frame, source): (u32, Isometry3<f64>, String),
) -> Result<()> {
    let other = |(f, _): &&(Isometry3<f64>, String)| !crate::program::cartesian::same(f, &frame);
    if let Some((_, said)) = out.get(&n).filter(other) {
        return Err(Error::Parse {
            source_name: name.to_string(),
            message: format!("line {line}: {what} {n} again, another frame than {said}: one controller holds one {what} per number; give the file as the controller wrote it"),
        });
    }
    out.entry(n).or_insert((frame, source));
    Ok(())
}
