//! The run's staged outputs (`stiffid_cli::output::staged`): the commit's guard.

use std::path::Path;
use stiffid_cli::output::staged::{lock_dirs, over_an_input, Step};

/// A staged replacement of a file the run read is caught by the commit's guard, even when the
/// output was staged before the input was read. (The guard is tested on its own: `commit`
/// works on the process's staged steps, which other tests of this binary use in parallel.)
#[test]
fn the_commit_guard_catches_a_staged_input() {
    // A file that outlives the test (a removed one's inode could be taken by another test's
    // directory, which would then look like this input).
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml");
    let input = input.canonicalize().unwrap();
    let other = std::env::temp_dir().join("stiffid-no-such-output.csv");
    let step = |target: &Path| Step::Replace {
        tmp: other.with_extension("tmp"),
        target: target.to_path_buf(),
    };
    let steps = [step(&other), step(&input)];
    assert!(over_an_input(&steps).is_none(), "not read yet");
    stiffid_cli::load::open(&input).unwrap();
    let error = over_an_input(&steps).unwrap().to_string();
    assert!(
        error.contains("input file") && error.contains("Cargo.toml"),
        "{error}"
    );
    assert!(over_an_input(&steps[..1]).is_none(), "another file");
}

/// Whether another open of `dir` gets its lock without waiting.
fn free(dir: &Path) -> bool {
    let other = std::fs::File::open(dir).unwrap();
    other.try_lock().is_ok()
}

/// The directories a commit puts files into are locked while it does (another run's commit into
/// one of them waits, so a split program's files are one run's set), and free again after.
#[test]
fn a_commit_locks_the_directories_it_writes_into() {
    let dir = std::env::temp_dir().join(format!("stiffid-lock-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let steps = vec![
        Step::Replace {
            tmp: dir.join("a.tmp"),
            target: dir.join("P.src"),
        },
        Step::Create {
            tmp: dir.join("b.tmp"),
            target: dir.join("P_01.src"),
        },
    ];
    let held = lock_dirs(&steps);
    assert_eq!(held.len(), 1);
    assert!(!free(&dir));
    drop(held);
    assert!(free(&dir));
    std::fs::remove_dir_all(&dir).unwrap();
}
