//! The files `stiffid compensate` writes beside `--out`: a split program's sub-programs, and
//! the check that none of them would replace a file the program does not call.

use crate::output::OutFile;
use anyhow::{bail, Result};
use std::path::{Path, PathBuf};
use stiffid::app::compensate::ProgramReport;
use stiffid::internal::machining::program;

/// Refuses, before anything is computed, a file beside `out` named as one of the sub-programs a
/// split program writes there (`NAME_01.EXT`, ..: the stem upper case, `out`'s extension) that
/// `out` does not call: only an earlier run's sub-programs of the same `out` are replaced.
pub(super) fn check_subprogram_files(out: &Path) -> Result<()> {
    let name = |p: Option<&std::ffi::OsStr>| p.and_then(|s| s.to_str()).unwrap_or("").to_string();
    let (stem, extension) = (name(out.file_stem()), name(out.extension()));
    let dir = match out.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    let main = std::fs::read_to_string(out).unwrap_or_default();
    let prefix = format!("{}_", stem.to_ascii_uppercase());
    for entry in entries.flatten() {
        let file = name(Some(&entry.file_name()));
        let Some(sub) = file.strip_suffix(&format!(".{extension}")) else {
            continue;
        };
        let number = sub.strip_prefix(&prefix).unwrap_or("");
        let numbered = !number.is_empty() && number.bytes().all(|b| b.is_ascii_digit());
        if numbered && !main.contains(sub) {
            bail!(
                "--out {}: {file} beside it is named as one of its sub-programs (a program of more than --moves-per-file moves is split into {prefix}01.{extension}, ..), and {} does not call it as an earlier run's: move it away or choose another --out",
                out.display(),
                out.display()
            );
        }
    }
    Ok(())
}

/// A split program's sub-programs, each beside the main program in a file of its name with the
/// main program's extension (and a KRL sub-program's `.dat` beside it); the files written.
pub(super) fn write_subprograms(out: &Path, program: &ProgramReport) -> Result<Vec<PathBuf>> {
    let files = &program.subprograms;
    let extension = out.extension().and_then(|e| e.to_str()).unwrap_or("");
    let dir = out.parent().unwrap_or(Path::new(""));
    let prepared = files
        .iter()
        .map(|f| {
            let path = dir.join(format!("{}.{extension}", f.name));
            OutFile::prepare(&path, "--out").map(|o| (o, f))
        })
        .collect::<Result<Vec<_>>>()?;
    let data = files
        .iter()
        .filter_map(|f| {
            let path = program::data_out(&dir.join(format!("{}.{extension}", f.name)))?;
            Some((path, f.data.as_ref()?))
        })
        .map(|(path, d)| OutFile::prepare(&path, "--out").map(|o| (o, d)))
        .collect::<Result<Vec<_>>>()?;
    let mut written = Vec::new();
    for (o, f) in prepared {
        o.write(&program.bytes(&f.text))?;
        written.push(o.target().to_path_buf());
    }
    for (o, d) in data {
        o.write(&program.bytes(d))?;
        written.push(o.target().to_path_buf());
    }
    Ok(written)
}
