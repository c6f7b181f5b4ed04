//! The run's staged outputs (`stiffid_cli::output::staged`): the commit's guard.

use std::path::Path;
use stiffid_cli::output::staged::{lock_dirs, over_an_input, put_in_place, Step};

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

/// Run `k`'s staged split program in `dir`: a main `P.src` calling `parts` sub-programs, each
/// with its `.dat`, every file naming the run.
fn split_run(dir: &Path, k: usize, parts: usize) -> Vec<Step> {
    let mut steps = Vec::new();
    let mut stage = |name: String, text: String| {
        let tmp = dir.join(format!(".run-{k}-{name}.tmp"));
        std::fs::write(&tmp, text).unwrap();
        steps.push(Step::Replace {
            tmp,
            target: dir.join(name),
        });
    };
    let calls: String = (1..=parts).map(|i| format!("P_{i:02}( )\n")).collect();
    stage("P.src".into(), format!("DEF P( )\n; run {k}\n{calls}END\n"));
    let mut written = Vec::new();
    for i in 1..=parts {
        for ext in ["src", "dat"] {
            stage(format!("P_{i:02}.{ext}"), format!("; run {k}\n"));
            written.push(dir.join(format!("P_{i:02}.{ext}")));
        }
    }
    steps.push(Step::Parts {
        main: dir.join("P.src"),
        written,
    });
    steps
}

/// Six runs of one split program, of 2 to 7 parts, put in place at once from six threads: the
/// folder holds one run's whole set (the main program, every part it calls with its `.dat`,
/// nothing of another run), and a user's file named like a part that no main program calls
/// stays.
#[test]
fn concurrent_writers_of_a_split_program_leave_one_runs_whole_set() {
    let dir = std::env::temp_dir().join(format!("stiffid-split-{}", std::process::id()));
    for trial in 0..4 {
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("P_09.src"), "mine\n").unwrap();
        let runs: Vec<Vec<Step>> = (0..6)
            .map(|k| split_run(&dir, k, 2 + (k + trial) % 6))
            .collect();
        std::thread::scope(|s| {
            for steps in runs {
                s.spawn(move || put_in_place(steps).unwrap());
            }
        });
        let main = std::fs::read_to_string(dir.join("P.src")).unwrap();
        let run = main.lines().nth(1).unwrap().to_string();
        let parts = main.matches("( )\n").count() - 1;
        let mut names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(names.len(), 2 + 2 * parts, "trial {trial}: {names:?}");
        for name in names
            .iter()
            .filter(|n| n.starts_with("P_") && *n != "P_09.src")
        {
            let text = std::fs::read_to_string(dir.join(name)).unwrap();
            assert_eq!(text.trim_end(), run, "trial {trial}: {name}");
        }
        assert_eq!(
            std::fs::read_to_string(dir.join("P_09.src")).unwrap(),
            "mine\n"
        );
    }
    // One after the other: a run of 2 parts after one of 5 leaves no part of the first.
    put_in_place(split_run(&dir, 7, 5)).unwrap();
    put_in_place(split_run(&dir, 8, 2)).unwrap();
    assert!(!dir.join("P_03.src").exists() && !dir.join("P_05.dat").exists());
    assert_eq!(
        std::fs::read_to_string(dir.join("P_02.dat")).unwrap(),
        "; run 8\n"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
