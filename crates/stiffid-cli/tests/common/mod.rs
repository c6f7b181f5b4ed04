//! Helpers shared by the command-line tests.
#![allow(dead_code)] // each test file uses its own subset

use std::path::PathBuf;
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
        .unwrap()
}

/// A fresh, not yet existing directory under the system's temporary directory, unique per test
/// process and `name`.
pub fn fresh_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stiffid-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}
