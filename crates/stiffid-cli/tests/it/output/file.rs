//! One output file (`stiffid_cli::output::Writer`): its errors name the file.

use std::io::{BufWriter, Write};
use std::path::PathBuf;
use stiffid_cli::output::Writer;

/// A full device's error names the file being written (`/dev/full` answers every write with
/// "No space left on device").
#[test]
fn a_full_device_names_the_file() {
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full");
    let mut w = Writer::new(
        BufWriter::with_capacity(16, full.unwrap()),
        PathBuf::from("/nonexistent/stiffid-tmp"),
        PathBuf::from("o/PK.csv"),
        false,
    );
    let e = (0..100)
        .try_for_each(|_| writeln!(w, "1,2,3,4,5,6"))
        .unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::StorageFull);
    assert!(e.to_string().starts_with("o/PK.csv: cannot write: "), "{e}");
}
