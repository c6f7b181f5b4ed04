//! Every file of a run is staged (written whole to a temporary file) and put in place only when
//! the run has succeeded, its results printed: a run that fails at any point, writing stdout
//! included, leaves no output behind ([`commit`], [`discard`]).

use anyhow::{Context, Result};
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// What the end of the run does.
#[derive(Debug)]
pub enum Step {
    /// Success: rename `tmp` over `target`; failure: remove `tmp`.
    Replace { tmp: PathBuf, target: PathBuf },
    /// As `Replace`, but `target` must not exist (an atomic no-replace create).
    Create { tmp: PathBuf, target: PathBuf },
    /// Success: remove this file of an earlier report that this run did not write again.
    Stale(PathBuf),
    /// Success and failure: remove this temporary directory.
    TempDir(PathBuf),
    /// Failure: remove this directory the run created.
    Created(PathBuf),
    /// Success: remove the sub-programs of the split program `main` replaces (the files beside
    /// it named `STEM_NN.EXT` and their `.dat`, that the file at `main` calls when the commit
    /// starts) which this run did not write (`written`): a set is one run's whole set.
    Parts {
        main: PathBuf,
        written: Vec<PathBuf>,
    },
}

static STEPS: Mutex<Vec<Step>> = Mutex::new(Vec::new());

/// The report directories' temporary directories being written into (removed by [`interrupted`]).
static SCRATCH: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Held while [`commit`] puts the files in place.
static COMMITTING: Mutex<()> = Mutex::new(());

/// Records `dir`, a report directory's temporary directory, for [`interrupted`].
pub fn scratch(dir: PathBuf) {
    SCRATCH.lock().unwrap_or_else(|e| e.into_inner()).push(dir);
}

/// What a run interrupted by a signal leaves: nothing of its own. Every staged temporary file and
/// directory, the directories the run created, the report directories' temporary directories
/// and every temporary file the run made ([`stiffid::internal::io::output::remove_temporaries`]) are
/// removed; the files already there stay as they were.
pub fn interrupted() {
    // A commit under way finishes first: its files are all put in place, not some.
    let _committing = COMMITTING.lock().unwrap_or_else(|e| e.into_inner());
    discard();
    for dir in std::mem::take(&mut *SCRATCH.lock().unwrap_or_else(|e| e.into_inner())) {
        let _ = std::fs::remove_dir_all(dir);
    }
    stiffid::internal::io::output::remove_temporaries();
}

/// Handles held to the end of the run (report directories' locks).
static HELD: Mutex<Vec<std::fs::File>> = Mutex::new(Vec::new());

/// Holds `file` (a directory lock) until the run's files are committed or discarded.
pub fn hold(file: std::fs::File) {
    HELD.lock().unwrap_or_else(|e| e.into_inner()).push(file);
}

fn release() {
    HELD.lock().unwrap_or_else(|e| e.into_inner()).clear();
}

/// The outputs of the run so far (resolved paths) and the options that named them.
static CLAIMS: Mutex<Vec<(PathBuf, String)>> = Mutex::new(Vec::new());

/// Records that `option` writes `path` (resolved: a file, or a report directory), refusing a path
/// another output of the same run writes, contains or lies in (`--out X --report X`), before
/// anything is computed.
///
/// # Errors
/// Naming both options and the path.
pub fn claim(path: &Path, option: &str) -> Result<()> {
    let mut claims = CLAIMS.lock().unwrap_or_else(|e| e.into_inner());
    for (other, by) in claims.iter() {
        if path.starts_with(other) || other.starts_with(path) {
            anyhow::bail!(
                "{option} {}: the same place as {by} {} of this run; give them different paths",
                path.display(),
                other.display()
            );
        }
    }
    claims.push((path.to_path_buf(), option.to_string()));
    Ok(())
}

fn push(step: Step) {
    STEPS.lock().unwrap_or_else(|e| e.into_inner()).push(step);
}

fn take() -> Vec<Step> {
    std::mem::take(&mut *STEPS.lock().unwrap_or_else(|e| e.into_inner()))
}

/// Forgets the claim on `path` ([`claim`]): its writer is done with it.
pub fn unclaim(path: &Path) {
    CLAIMS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|(p, _)| p != path);
}

/// Stages the written temporary file `tmp` to replace `target` at [`commit`].
pub fn replace(tmp: PathBuf, target: PathBuf) {
    push(Step::Replace { tmp, target });
}

/// Stages the written temporary file `tmp` to become the new file `target` at [`commit`],
/// refusing (and removing `tmp`) if `target` exists by then.
pub fn create(tmp: PathBuf, target: PathBuf) {
    push(Step::Create { tmp, target });
}

/// Stages the removal of `path`, an earlier report's file this run did not write, at [`commit`].
pub fn stale(path: PathBuf) {
    push(Step::Stale(path));
}

/// Stages the removal, at [`commit`], of the sub-programs of the program at `main` that this
/// run replaces and does not write again (`written`: the sub-programs it writes, [`Step::Parts`]).
pub fn parts(main: PathBuf, written: Vec<PathBuf>) {
    push(Step::Parts { main, written });
}

/// Stages the removal of the temporary directory `dir` at the end of the run.
pub fn temp_dir(dir: PathBuf) {
    push(Step::TempDir(dir));
}

/// Stages the removal of `dir`, created by this run, if the run fails.
pub fn created(dir: PathBuf) {
    push(Step::Created(dir));
}

/// Puts every staged file in place, in the order written, and removes the stale files and the
/// temporary directories.
///
/// # Errors
/// The first file that cannot be put in place (the others are still tried; temporary files of
/// the failed ones are removed).
pub fn commit() -> Result<()> {
    let _committing = COMMITTING.lock().unwrap_or_else(|e| e.into_inner());
    let steps = take();
    if let Some(e) = over_an_input(&steps) {
        put_back(steps);
        discard();
        return Err(e);
    }
    // The report directories' locks give way to the directories' own for the commit (one open
    // of a directory would wait for another of the same process).
    release();
    let done = put_in_place(steps);
    release();
    done
}

/// Puts the files of `steps` in place, in order, under exclusive locks on their directories
/// ([`lock_dirs`]), then removes the stale files and the temporary directories and, when every
/// file is in place, the earlier parts of a split program ([`Step::Parts`]): what [`commit`]
/// does with the run's steps once checked; concurrent calls (runs) into one directory each put
/// their whole set, one after the other.
///
/// # Errors
/// As [`commit`].
pub fn put_in_place(steps: Vec<Step>) -> Result<()> {
    let _dirs = lock_dirs(&steps);
    // Read under the locks, before the main programs are replaced: the parts they call now.
    let earlier = super::parts::earlier(&steps);
    let mut first: Option<anyhow::Error> = None;
    for step in steps {
        let done = match &step {
            Step::Replace { tmp, target } => place(tmp, target, false),
            Step::Create { tmp, target } => place(tmp, target, true),
            Step::Stale(path) => match std::fs::remove_file(path) {
                Err(e) if e.kind() != ErrorKind::NotFound => {
                    Err(e).with_context(|| format!("{}: cannot remove", path.display()))
                }
                _ => Ok(()),
            },
            Step::TempDir(dir) => {
                let _ = std::fs::remove_dir_all(dir);
                Ok(())
            }
            Step::Created(_) | Step::Parts { .. } => Ok(()),
        };
        if let Err(e) = done {
            first.get_or_insert(e);
        }
    }
    if first.is_none() {
        first = super::parts::remove(&earlier).err();
    }
    first.map_or(Ok(()), Err)
}

/// Exclusive locks on the directories the staged files of `steps` go into, taken in the
/// directories' order and waited for: runs that put files into one directory (a split program's
/// `P.src`, `P_01.src`, `P_01.dat`) do it one after the other, each its whole set, so the
/// directory never holds one run's file beside another's. Held as long as the handles; a
/// directory that cannot be opened is not locked (its files' own errors name it).
pub fn lock_dirs(steps: &[Step]) -> Vec<std::fs::File> {
    let mut dirs: Vec<PathBuf> = (steps.iter())
        .filter_map(|step| match step {
            Step::Replace { target, .. } | Step::Create { target, .. } => target.parent(),
            _ => None,
        })
        .map(|d| match d.as_os_str().is_empty() {
            true => PathBuf::from("."),
            false => d.to_path_buf(),
        })
        .collect();
    dirs.sort();
    dirs.dedup();
    dirs.iter().filter_map(|d| lock_dir(d)).collect()
}

/// An exclusive lock on the directory `dir` (`flock` on Unix), waited for.
fn lock_dir(dir: &Path) -> Option<std::fs::File> {
    let handle = std::fs::File::open(dir).ok()?;
    handle.lock().ok().map(|()| handle)
}

/// The last guard of "never write over an input": a staged file whose target is a file the run
/// read (whatever the order in which the command read its inputs and prepared its outputs).
pub fn over_an_input(steps: &[Step]) -> Option<anyhow::Error> {
    steps.iter().find_map(|step| match step {
        Step::Replace { target, .. } | Step::Create { target, .. } => crate::load::input_at(target)
            .map(|input| {
                anyhow::anyhow!(
                    "{}: refusing to write over the input file {}; nothing written",
                    target.display(),
                    input.display()
                )
            }),
        _ => None,
    })
}

fn put_back(steps: Vec<Step>) {
    STEPS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .extend(steps);
}

/// Removes every staged temporary file and directory, and the directories the run created.
pub fn discard() {
    for step in take() {
        match step {
            Step::Replace { tmp, .. } | Step::Create { tmp, .. } => {
                let _ = std::fs::remove_file(tmp);
            }
            Step::TempDir(dir) | Step::Created(dir) => {
                let _ = std::fs::remove_dir_all(dir);
            }
            Step::Stale(_) | Step::Parts { .. } => {}
        }
    }
    release();
}

/// Puts `tmp` in place as `target` ([`stiffid::internal::io::output::place`]), the error naming it.
fn place(tmp: &Path, target: &Path, new_only: bool) -> Result<()> {
    stiffid::internal::io::output::place(tmp, target, new_only)
        .with_context(|| format!("{}: cannot write", target.display()))
}
