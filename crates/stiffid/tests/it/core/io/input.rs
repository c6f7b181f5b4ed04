//! Opening an input: a FIFO without a writer refused at once (Unix only).
#![cfg(unix)]

use std::io::ErrorKind;
use stiffid_core::io::input::open;

#[test]
fn a_fifo_without_writer_is_refused_at_once_and_a_file_is_read() {
    let dir = std::env::temp_dir().join(format!("stiffid-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("fifo");
    let _ = std::fs::remove_file(&fifo);
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        let e = open(&fifo).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidInput);
        assert_eq!(e.to_string(), "is a FIFO, not a regular file; give a file");
    }
    let e = open(&dir).unwrap_err();
    assert_eq!(e.to_string(), "is a directory, expected a file");
    let file = dir.join("a.csv");
    std::fs::write(&file, "q1_deg\n").unwrap();
    let mut text = String::new();
    std::io::Read::read_to_string(&mut open(&file).unwrap(), &mut text).unwrap();
    assert_eq!(text, "q1_deg\n");
    std::fs::remove_dir_all(&dir).unwrap();
}
