//! The study's report directory (`stiffid_cli::report`): which directories it writes into.

mod markdown;

use std::path::Path;
use stiffid::app::reproduce::document::GENERATOR;
use stiffid_cli::report::{self, holds};

fn open(dir: &Path, force: bool) -> anyhow::Result<stiffid_cli::output::ReportDir> {
    report::open(dir, "--out", Some(force), GENERATOR, &holds)
}

#[test]
fn only_empty_missing_or_own_directories_are_written_without_force() {
    let dir = std::env::temp_dir().join(format!("stiffid-target-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    drop(open(&dir, false).expect("missing"));
    assert!(
        !dir.exists(),
        "a directory it created and did not finish is removed"
    );
    std::fs::create_dir_all(&dir).unwrap();
    drop(open(&dir, false).expect("empty"));
    assert!(dir.exists(), "a directory it did not create stays");
    std::fs::write(dir.join("summary.json"), r#"{"generator": "someone else"}"#).unwrap();
    assert!(open(&dir, false).is_err(), "foreign summary.json");
    assert!(open(&dir, true).is_ok(), "forced");
    std::fs::write(
        dir.join("summary.json"),
        r#"{"generator": "stiffid reproduce"}"#,
    )
    .unwrap();
    assert!(open(&dir, false).is_ok(), "own report");
    let file = dir.join("summary.json");
    assert!(open(&file, false).is_err(), "a file");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_directory_being_written_is_refused_until_its_writer_ends() {
    let dir = std::env::temp_dir().join(format!("stiffid-locked-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let writer = open(&dir, false).expect("first");
    // In one process the run's own claim refuses it; in another, the directory's lock.
    let Err(refused) = open(&dir, true) else {
        panic!("a second writer is accepted");
    };
    assert!(
        format!("{refused:#}").contains("the same place"),
        "{refused:#}"
    );
    drop(writer);
    drop(open(&dir, false).expect("after the first ends"));
    std::fs::remove_dir_all(&dir).unwrap();
}
