//! What one command writes, the next one reads: `identify --out` writes a stiffness file only
//! when `validate`, `predict` and `compensate` read it; a fit they would refuse (a negative
//! compliance) is refused at once, naming the way out (`--nonnegative`, `--compare-models`).

use crate::common::{fanuc_csv, stiffid, temp_dir, validate_fanuc, write_file};

/// The FANUC data's header and the rows of `postures` (1-based, in the file's order).
fn fanuc_subset(postures: &[usize]) -> String {
    let text = std::fs::read_to_string(fanuc_csv()).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let mut out = format!("{}\n", lines.next().unwrap());
    for (k, line) in lines.enumerate() {
        if postures.contains(&(k + 1)) {
            out += &format!("{line}\n");
        }
    }
    out
}

/// `identify --setup fanuc-r2000ic-165f --data DATA --out OUT`, then `extra`.
fn identify(data: &str, out: &str, extra: &[&str]) -> std::process::Output {
    let args = ["identify", "--setup", "fanuc-r2000ic-165f", "--data", data];
    stiffid(&[&args[..], &["--out", out], extra].concat())
}

/// Exit code 2 and an `error:` last line (after the fit's warnings) holding every `part`.
fn refused(o: &std::process::Output, parts: &[&str]) -> String {
    let stderr = String::from_utf8_lossy(&o.stderr);
    let line = stderr.lines().last().unwrap_or_default().to_string();
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(line.starts_with("error: "), "{stderr}");
    for part in parts {
        assert!(line.contains(part), "{part}: {line}");
    }
    line
}

/// `predict` with the stiffness file `k` in one of the data's postures.
fn predict(k: &str) -> std::process::Output {
    stiffid(&[
        "predict",
        "--setup",
        "fanuc-r2000ic-165f",
        "--q-deg",
        "-60,-17,-29,4,-63,145",
        "--wrench",
        "-120,-78,-14",
        "--stiffness",
        k,
    ])
}

/// The first four FANUC postures give k4 < 0 by the drives alone: no file is written, and the
/// refusal names the way out; the non-negative fit's file is read by the next steps.
#[test]
fn identify_writes_no_stiffness_file_the_next_step_refuses() {
    let d = temp_dir("readable-negative");
    let data = write_file(&d, "four.csv", &fanuc_subset(&[1, 2, 3, 4]));
    let (data, k) = (data.to_str().unwrap(), d.join("k.json"));
    let o = identify(data, k.to_str().unwrap(), &[]);
    let line = refused(
        &o,
        &["--out", "not written", "--nonnegative", "--compare-models"],
    );
    assert!(line.contains("stiffness"), "{line}");
    assert!(!k.exists());
    let o = identify(data, k.to_str().unwrap(), &["--nonnegative"]);
    match o.status.success() {
        true => {
            assert!(validate_fanuc(&k, &[]).status.success());
            assert!(predict(k.to_str().unwrap()).status.success());
        }
        false => {
            refused(&o, &["--out", "not written"]);
            assert!(!k.exists());
        }
    }
}

/// Drives-only fits of 20 seeded subsets of the FANUC postures (a real robot: compliances the
/// six drives lack): every file `identify --out` writes, `validate` and `predict` read; every
/// fit it refuses names the way out and writes nothing.
#[test]
fn every_stiffness_file_identify_writes_the_next_steps_read() {
    let d = temp_dir("readable-seeds");
    let (mut written, mut refusals) = (0, 0);
    for seed in 1..=20u64 {
        let mut state = seed;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) as usize
        };
        let mut postures = Vec::new();
        while postures.len() < 5 + seed as usize % 4 {
            let p = 1 + next() % 43;
            if !postures.contains(&p) {
                postures.push(p);
            }
        }
        let data = write_file(&d, &format!("seed{seed}.csv"), &fanuc_subset(&postures));
        let k = d.join(format!("k{seed}.json"));
        let o = identify(data.to_str().unwrap(), k.to_str().unwrap(), &[]);
        if o.status.success() {
            written += 1;
            let v = validate_fanuc(&k, &[]);
            let stderr = String::from_utf8_lossy(&v.stderr);
            assert!(v.status.success(), "seed {seed}: validate: {stderr}");
            let p = predict(k.to_str().unwrap());
            let stderr = String::from_utf8_lossy(&p.stderr);
            assert!(p.status.success(), "seed {seed}: predict: {stderr}");
        } else {
            refusals += 1;
            refused(&o, &["--out", "--nonnegative", "--compare-models"]);
            assert!(!k.exists(), "seed {seed}");
        }
    }
    assert_eq!(written + refusals, 20);
}
