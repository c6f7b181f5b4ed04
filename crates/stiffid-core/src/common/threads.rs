//! The worker threads of the parallel jobs (rayon's global pool), as the user's environment asks
//! for them: `RAYON_NUM_THREADS`, capped at 256, started at once so that a count the machine cannot
//! start is an error naming the setting, not a panic in the middle of a job. The command and the
//! Python package call [`start`] before any job.

use crate::common::limits::short;

/// Most worker threads `RAYON_NUM_THREADS` may ask for: more only cost memory (each thread its
/// stack), and 5000 of them under a 4 GB memory cap could not start.
pub(crate) const MAX_THREADS: usize = 256;

/// Starts the worker threads `RAYON_NUM_THREADS` asks for (0 or unset: one per core, started by
/// the first parallel job). Once per process: a later call returns the first one's result (the
/// Python package starts them on import, and its `stiffid` script runs the command after it).
///
/// # Errors
/// A message naming the setting: a value that is not a number from 0 to 256, or threads that could
/// not start.
pub fn start() -> Result<(), String> {
    static STARTED: std::sync::OnceLock<Result<(), String>> = std::sync::OnceLock::new();
    STARTED.get_or_init(start_once).clone()
}

fn start_once() -> Result<(), String> {
    let Some(value) = std::env::var_os("RAYON_NUM_THREADS") else {
        return Ok(());
    };
    let text = value.to_string_lossy();
    let n = text
        .trim()
        .parse::<usize>()
        .ok()
        .filter(|&n| n <= MAX_THREADS)
        .ok_or_else(|| {
            format!(
                "RAYON_NUM_THREADS = '{}': expected a number of threads from 0 (one per core) to {MAX_THREADS}",
                short(&text)
            )
        })?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build_global()
        .map_err(|e| {
            format!("RAYON_NUM_THREADS = {n}: the threads could not start ({e}); give fewer")
        })
}
