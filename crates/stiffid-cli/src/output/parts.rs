//! A split program's sub-programs as one set ([`super::staged::Step::Parts`]): the parts of the
//! program a run replaces that it does not write again are removed when it commits, under the
//! directory's lock, so the folder holds one run's whole set (a run of fewer parts after, or
//! beside, one of more left `P_04.src` of the other beside its own `P.src`).

use super::staged::Step;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// The files beside each [`Step::Parts`]'s main program that it calls now (read when the commit
/// starts, before it is replaced), named as its sub-programs (`STEM_NN.EXT`, the stem upper case,
/// digits after it; with a KRL sub-program's `.dat`), regular files, that the run does not write.
pub(super) fn earlier(steps: &[Step]) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for step in steps {
        let Step::Parts { main, written } = step else {
            continue;
        };
        let Ok(text) = std::fs::read(main) else {
            continue;
        };
        let text = String::from_utf8_lossy(&text);
        let dir = match main.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let Ok(entries) = std::fs::read_dir(dir) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            let regular = entry.file_type().is_ok_and(|t| t.is_file());
            let called = part_name(main, &path).is_some_and(|sub| text.contains(&sub));
            if regular && called && !written.contains(&path) {
                found.push(path);
            }
        }
    }
    found.sort();
    found.dedup();
    found
}

/// The sub-program's name of `path` if it is named as one of `main`'s parts: `STEM_NN` with the
/// main program's extension or `.dat`.
fn part_name(main: &Path, path: &Path) -> Option<String> {
    let text = |p: Option<&std::ffi::OsStr>| p.and_then(|s| s.to_str()).map(str::to_string);
    let (stem, extension) = (text(main.file_stem())?, text(main.extension())?);
    let (sub, ext) = (text(path.file_stem())?, text(path.extension())?);
    let number = sub.strip_prefix(&format!("{}_", stem.to_ascii_uppercase()))?;
    let numbered = !number.is_empty() && number.bytes().all(|b| b.is_ascii_digit());
    (numbered && (ext == extension || ext.eq_ignore_ascii_case("dat"))).then_some(sub)
}

/// Removes the files `earlier` found.
///
/// # Errors
/// The first that cannot be removed (gone already is no error).
pub(super) fn remove(paths: &[PathBuf]) -> Result<()> {
    for path in paths {
        match std::fs::remove_file(path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(e).with_context(|| {
                    format!(
                        "{}: a sub-program of the program this run replaced, not written again: cannot remove",
                        path.display()
                    )
                });
            }
            _ => {}
        }
    }
    Ok(())
}
