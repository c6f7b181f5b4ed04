//! Helpers shared by the command-line tests.
#![allow(dead_code)] // each test file uses its own subset

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Six spread postures within the paper's Table 1 bounds, as a postures file.
pub const GROUP: &str = "posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg
1,10,-20,-100,30,40,-60
2,-45,10,-70,-90,-30,120
3,60,-40,-130,150,60,10
4,-80,30,-50,-20,-70,-150
5,30,0,-160,100,20,80
6,-10,-55,-90,-160,80,-30
";

/// Runs the `stiffid` binary.
pub fn stiffid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stiffid"))
        .args(args)
        .output()
        .expect("run stiffid")
}

/// Asserts that the command succeeded, showing its stderr otherwise.
pub fn assert_success(out: &Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The JSON document a successful command printed on stdout.
pub fn json(out: &Output) -> Value {
    assert_success(out);
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Asserts that the command failed on bad input the documented way: exit code 2, nothing on stdout,
/// no panic, and one stderr line starting with `error: ` that contains every part of
/// `must_mention`. Returns that line.
pub fn assert_usage_error(out: &Output, must_mention: &[&str]) -> String {
    assert_error_line(out, 2, must_mention)
}

/// As [`assert_usage_error`] for a gate the result failed (`--max-error-mm`, a drifted check):
/// exit code 1.
pub fn assert_failed_gate(out: &Output, must_mention: &[&str]) -> String {
    assert_error_line(out, 1, must_mention)
}

/// One `error: ` line on stderr mentioning each of `must_mention`, nothing on stdout, exit code
/// `code`.
fn assert_error_line(out: &Output, code: i32, must_mention: &[&str]) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(code), "{stderr}");
    assert!(out.stdout.is_empty(), "printed {:?}", out.stdout);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "not one line: {stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    for part in must_mention {
        assert!(stderr.contains(part), "'{part}' missing from: {stderr}");
    }
    stderr
}

/// Asserts that a group's JSON (from `evaluate`, or `reproduce`'s summary) has every design
/// criterion, the test-pose deviation and cond(Psi) as positive numbers.
pub fn assert_criteria_positive(group: &Value) {
    for key in [
        "classical",
        "zhang2021",
        "scaled_cond",
        "d_optimal",
        "relative_a",
        "test_pose_mm",
        "cond_psi",
    ] {
        assert!(group[key].as_f64().is_some_and(|v| v > 0.0), "{key}");
    }
}

/// A fresh, not yet existing directory under the system's temporary directory, unique per test
/// process and `name`.
pub fn fresh_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stiffid-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// [`fresh_dir`], created empty.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = fresh_dir(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `text` to the file `name` in `dir`; returns its path.
pub fn write_file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Every file under `dir` (recursively, symlinks not followed) with its bytes, or its link
/// target for a symlink: to assert that a failed command wrote nothing and changed no input.
pub fn snapshot(dir: &Path) -> std::collections::BTreeMap<PathBuf, Vec<u8>> {
    let mut files = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            let meta = std::fs::symlink_metadata(&path).unwrap();
            if meta.is_dir() {
                stack.push(path.clone());
                files.insert(path, Vec::new());
            } else if meta.file_type().is_symlink() {
                let target = std::fs::read_link(&path).unwrap();
                files.insert(path, target.to_string_lossy().as_bytes().to_vec());
            } else if meta.is_file() {
                let bytes = std::fs::read(&path).unwrap();
                files.insert(path, bytes);
            }
        }
    }
    files
}

/// Runs `args` in the scratch directory `dir` (`{dir}` in an argument is replaced by its path)
/// and asserts the documented failure ([`assert_usage_error`] with `must_mention`) and that the
/// directory is byte for byte as before. Returns the error line.
pub fn refused(dir: &Path, args: &[&str], must_mention: &[&str]) -> String {
    let before = snapshot(dir);
    let d = dir.to_str().unwrap();
    let args: Vec<String> = args.iter().map(|a| a.replace("{dir}", d)).collect();
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    let line = assert_usage_error(&stiffid(&refs), must_mention);
    assert_eq!(snapshot(dir), before, "{args:?} changed {}", dir.display());
    line
}

/// The real FANUC R-2000iC/165F measurement file of the examples.
pub fn fanuc_csv() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/data/fanuc-r2000ic-165f/measurements.csv")
}

/// `stiffid identify --setup fanuc-r2000ic-165f --data <the FANUC file> --json`, then `extra`.
pub fn identify_fanuc(extra: &[&str]) -> Output {
    let data = fanuc_csv();
    let base = ["identify", "--setup", "fanuc-r2000ic-165f", "--data"];
    stiffid(&[&base[..], &[data.to_str().unwrap(), "--json"], extra].concat())
}

/// `stiffid validate --setup fanuc-r2000ic-165f --stiffness STIFFNESS --data <the FANUC file>`,
/// then `extra`.
pub fn validate_fanuc(stiffness: &Path, extra: &[&str]) -> Output {
    let (k, data) = (stiffness.to_str().unwrap(), fanuc_csv());
    let base = [
        "validate",
        "--setup",
        "fanuc-r2000ic-165f",
        "--stiffness",
        k,
        "--data",
    ];
    stiffid(&[&base[..], &[data.to_str().unwrap()], extra].concat())
}

/// The numbers of a JSON array.
pub fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The path of the shipped example `name` (under `examples/`).
pub fn example(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// A KRL `.src` with the points its `.dat` declares (`DECL E6POS XP1={..}`, `DECL E6AXIS
/// XP1={..}`) put back into its motions by name (`LIN XP1 C_DIS` becomes `LIN {E6POS: ..}
/// C_DIS`): the literal form KRL reads alone, for tests that edit one file. Read from the
/// `.dat`'s lines, not by stiffid; an `XPn` the `.dat` does not declare fails the test.
pub fn inlined(src: &str, dat: &str) -> String {
    let points: std::collections::HashMap<&str, String> = (dat.lines())
        .filter_map(|l| l.strip_prefix("DECL "))
        .filter_map(|l| {
            let (kind, rest) = l.split_once(' ')?;
            let (name, value) = rest.split_once('=')?;
            let members = value.strip_prefix('{')?.strip_suffix('}')?;
            Some(match kind {
                "E6POS" => (name, format!("{{E6POS: {members}}}")),
                _ => (name, format!("{{{members}}}")),
            })
        })
        .collect();
    let mut out = String::with_capacity(src.len() + dat.len());
    for line in src.split_inclusive('\n') {
        let keyword = ["PTP ", "LIN ", "CIRC "]
            .into_iter()
            .find(|k| line.starts_with(k) && line[k.len()..].starts_with("XP"));
        let Some(keyword) = keyword else {
            out += line;
            continue;
        };
        out += keyword;
        let mut rest = &line[keyword.len()..];
        let mut first = true;
        while let Some(tail) = rest.strip_prefix("XP") {
            let digits = tail
                .find(|c: char| !c.is_ascii_digit())
                .unwrap_or(tail.len());
            let name = &rest[..2 + digits];
            let value = points
                .get(name)
                .unwrap_or_else(|| panic!("{name} not in the .dat"));
            if !first {
                out += ",";
            }
            out += value;
            first = false;
            rest = tail[digits..].strip_prefix(", ").unwrap_or(&tail[digits..]);
        }
        out += rest;
    }
    out
}
