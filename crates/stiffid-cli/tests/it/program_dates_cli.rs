//! A generated program is reproducible: written twice from the same input it is the same bytes,
//! its dates (LS `CREATE`/`MODIFIED`, INFORM `///DATE`) `SOURCE_DATE_EPOCH`'s when the
//! environment sets it; a malformed value is refused before anything is written.

use crate::common::{assert_success, example, temp_dir};
use std::process::{Command, Output};

/// `compensate` of the milling pocket into `out` with `SOURCE_DATE_EPOCH` set to `epoch`.
fn written(out: &std::path::Path, epoch: Option<&str>) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_stiffid"));
    c.args([
        "compensate",
        "--setup",
        &example("milling/fanuc-milling.toml"),
        "--stiffness",
        &example("milling/stiffness.json"),
        "--program",
        &example("milling/pocket.nc"),
        "--process",
        &example("milling/aluminium.toml"),
        "--out",
        out.to_str().unwrap(),
    ]);
    c.env_remove("SOURCE_DATE_EPOCH");
    if let Some(e) = epoch {
        c.env("SOURCE_DATE_EPOCH", e);
    }
    c.output().expect("run stiffid")
}

#[test]
fn a_generated_program_is_the_same_bytes_dated_by_source_date_epoch() {
    let dir = temp_dir("dates");
    let (a, b) = (dir.join("a"), dir.join("b"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    let (a, b) = (a.join("POCKET.ls"), b.join("POCKET.ls"));
    assert_success(&written(&a, None));
    assert_success(&written(&b, None));
    let text = std::fs::read_to_string(&a).unwrap();
    assert!(text == std::fs::read_to_string(&b).unwrap());
    assert!(
        text.contains("CREATE\t\t= DATE 70-01-01  TIME 00:00:00;\n"),
        "{text}"
    );
    // 2025-11-27 00:31:01 UTC (Python's datetime.fromtimestamp(1764203461, UTC)).
    let dated = dir.join("C.ls");
    assert_success(&written(&dated, Some("1764203461")));
    let text = std::fs::read_to_string(&dated).unwrap();
    assert!(text.contains("CREATE\t\t= DATE 25-11-27  TIME 00:31:01;\nMODIFIED\t= DATE 25-11-27  TIME 00:31:01;\n"), "{text}");
    let bad = dir.join("D.ls");
    let o = written(&bad, Some("yesterday"));
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("SOURCE_DATE_EPOCH") && stderr.contains("yesterday"),
        "{stderr}"
    );
    assert!(!bad.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
