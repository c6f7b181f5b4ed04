//! Writing results: whole files only (temporary file, then rename), JSON, one-line errors.

use anyhow::{Context, Result};
use std::io::Write;
use std::path::Path;

/// Writes `bytes` to `path` whole: into a temporary file beside it, then renamed over it, so a
/// reader never sees half a file and a failure leaves nothing behind.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .with_context(|| format!("{}: not a file path", path.display()))?;
    let tmp = dir.join(format!(
        ".{}.tmp{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let written = std::fs::File::create(&tmp)
        .and_then(|mut f| f.write_all(bytes).and_then(|_| f.sync_all()))
        .and_then(|_| std::fs::rename(&tmp, path));
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written.with_context(|| format!("{}: cannot write", path.display()))
}

/// Refuses to write `out` over one of the `inputs` (the same file, by canonical path).
pub fn refuse_to_overwrite(out: &Path, inputs: &[&Path]) -> Result<()> {
    let Ok(target) = out.canonicalize() else {
        return Ok(());
    };
    if let Some(input) = inputs
        .iter()
        .find(|i| i.canonicalize().is_ok_and(|c| c == target))
    {
        anyhow::bail!(
            "{}: refusing to write the result over the input {}",
            out.display(),
            input.display()
        );
    }
    Ok(())
}

/// Writes `bytes` to standard output; a write error (a full disk, a closed pipe) is an error.
pub fn write_stdout(bytes: &[u8]) -> Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)?;
    Ok(out.flush()?)
}

/// Pretty JSON of `value`, with a final newline.
pub fn json<T: serde::Serialize>(value: &T) -> Result<String> {
    Ok(serde_json::to_string_pretty(value)? + "\n")
}

/// Prints `value` as pretty JSON if `as_json`, else the text `human` makes of it.
pub fn print_json_or<T: serde::Serialize>(
    as_json: bool,
    value: &T,
    human: impl FnOnce(&T) -> String,
) -> Result<()> {
    match as_json {
        true => print!("{}", json(value)?),
        false => print!("{}", human(value)),
    }
    Ok(())
}

/// An error and its causes on one line, outermost first.
pub fn one_line_chain(e: &anyhow::Error) -> String {
    e.chain()
        .map(|c| c.to_string())
        .collect::<Vec<_>>()
        .join(": ")
        .replace('\n', " ")
}
