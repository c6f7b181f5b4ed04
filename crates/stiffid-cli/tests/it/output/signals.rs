//! A run interrupted by SIGINT, SIGTERM or SIGHUP while it writes a large program leaves the
//! folder as it was (its temporary files removed, the file it would replace untouched) and exits
//! 128 + the signal's number; a later run removes the temporaries of a process that is gone and
//! keeps those of a live one.

use crate::common::{example, temp_dir};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A long pocket: the milling example's passes 20 times over (about 3,600 points, a program
/// split into files of a few MB).
fn long_pocket(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(example("milling/pocket.nc")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let (head, body, end) = (
        &lines[..6],
        &lines[6..lines.len() - 2],
        &lines[lines.len() - 2..],
    );
    let mut out: Vec<&str> = head.to_vec();
    (0..20).for_each(|_| out.extend_from_slice(body));
    out.extend_from_slice(end);
    let path = dir.join("long.nc");
    std::fs::write(&path, out.join("\n") + "\n").unwrap();
    path
}

fn compensate(program: &Path, out: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_stiffid"));
    c.args([
        "compensate",
        "--setup",
        &example("milling/fanuc-milling.toml"),
    ])
    .args(["--stiffness", &example("milling/stiffness.json")])
    .args(["--process", &example("milling/aluminium.toml")])
    .arg("--program")
    .arg(program)
    .arg("--out")
    .arg(out.join("LONG.ls"))
    .arg("--csv")
    .arg(out.join("points.csv"))
    .stdout(Stdio::null())
    .stderr(Stdio::null());
    c
}

/// Every file of `dir` with its bytes.
fn contents(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    (std::fs::read_dir(dir).unwrap().flatten())
        .map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(e.path()).unwrap_or_default())
        })
        .collect()
}

/// Whether `dir` holds a temporary file of the command (`.stiffid-PID-N.tmp`).
fn writing(dir: &Path) -> bool {
    (std::fs::read_dir(dir).unwrap().flatten())
        .any(|e| e.file_name().to_string_lossy().starts_with(".stiffid-"))
}

#[test]
fn a_signal_while_writing_leaves_the_folder_as_it_was() {
    let dir = temp_dir("signals");
    let program = long_pocket(&dir);
    let out = dir.join("out");
    std::fs::create_dir(&out).unwrap();
    // A program of an earlier run the new one would replace, and a file of the user's.
    std::fs::write(out.join("LONG.ls"), "earlier program\n").unwrap();
    std::fs::write(out.join("notes.txt"), "mine\n").unwrap();
    let before = contents(&out);
    for (signal, delay_ms) in [
        (libc::SIGTERM, 0),
        (libc::SIGINT, 0),
        (libc::SIGHUP, 0),
        (libc::SIGTERM, 3),
        (libc::SIGINT, 10),
    ] {
        let mut child = compensate(&program, &out).spawn().unwrap();
        let start = Instant::now();
        while !writing(&out) {
            assert!(
                child.try_wait().unwrap().is_none(),
                "the run ended before it wrote"
            );
            assert!(
                start.elapsed() < Duration::from_secs(120),
                "no temporary file after 2 min"
            );
            std::thread::sleep(Duration::from_micros(200));
        }
        std::thread::sleep(Duration::from_millis(delay_ms));
        // SAFETY: sends a signal to the child this test spawned.
        assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, signal) }, 0);
        let status = child.wait().unwrap();
        assert_eq!(
            status.code(),
            Some(128 + signal),
            "signal {signal} after {delay_ms} ms"
        );
        assert_eq!(
            contents(&out),
            before,
            "signal {signal} after {delay_ms} ms"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_run_removes_the_temporaries_of_a_process_that_is_gone() {
    let dir = temp_dir("stale-temporaries");
    let program = long_pocket(&dir);
    // A process that has ended: its id names no process any more (unless the system reused it
    // at once, which this test would then see as a kept file).
    let mut gone = Command::new("true").spawn().unwrap();
    gone.wait().unwrap();
    let stale = dir.join(format!(".stiffid-{}-0.tmp", gone.id()));
    let live = dir.join(format!(".stiffid-{}-0.tmp", std::process::id()));
    let other = dir.join(".stiffid-notes.tmp");
    for f in [&stale, &live, &other] {
        std::fs::write(f, "left behind").unwrap();
    }
    let status = compensate(&program, &dir).status().unwrap();
    assert!(status.success());
    assert!(dir.join("LONG.ls").exists());
    assert!(
        !stale.exists(),
        "the temporary of a process that is gone is removed"
    );
    assert!(live.exists(), "a live process's temporary is kept");
    assert!(other.exists(), "a file of another naming is kept");
    std::fs::remove_dir_all(&dir).unwrap();
}
