//! The documents of the shipped examples, as the command wrote them before every document said
//! its `kind` and every percentage's key ended in `_pct` (`tests/data/documents/*.json`): today's
//! are those texts byte for byte with `kind` added first and the keys renamed, nothing else (the
//! options renamed too: `--postures N` of `select` and `register` is `--count N`).

use std::path::Path;
use std::process::Command;

/// Each key renamed: the former spelling and today's.
const RENAMED: [(&str, &str); 14] = [
    ("cost_percent", "cost_pct"),
    ("coverage_percent", "coverage_pct"),
    ("explained_percent", "explained_pct"),
    ("explained_std_error_percent", "explained_std_error_pct"),
    ("gain_vs_own_percent", "gain_vs_own_pct"),
    ("gain_vs_reach_only_percent", "gain_vs_reach_only_pct"),
    ("mean_change_percent", "mean_change_pct"),
    ("model_error_percent", "model_error_pct"),
    ("nearest_harmonic_percent", "nearest_harmonic_pct"),
    (
        "poorly_determined_above_percent",
        "poorly_determined_above_pct",
    ),
    (
        "predicted_average_change_percent",
        "predicted_average_change_pct",
    ),
    ("score_q95_percent", "score_q95_pct"),
    ("std_error_percent", "std_error_pct"),
    ("stiffness_std_percent", "stiffness_std_pct"),
];

const FANUC: &str = "examples/data/fanuc-r2000ic-165f/measurements.csv";
const STIFFNESS: &str = "examples/milling/stiffness.json";
const CELL: &str = "examples/cell/zhang2021-tracker.toml";
const GROUP: &str = "examples/cell/feasible-relative-a.csv";

/// Each document: its file in `tests/data/documents`, its kind and today's command line (run in
/// the repository, so the paths it records are the same).
const DOCUMENTS: [(&str, &str, &[&str]); 6] = [
    (
        "kinematics",
        "kinematics",
        &[
            "kinematics",
            "--robot",
            "comau-smart5-nj165-3.0",
            "--q-deg",
            "10,20,-100,30,40,50",
            "--characteristic-length-mm",
            "1200",
        ],
    ),
    (
        "predict",
        "predict",
        &[
            "predict",
            "--setup",
            "fanuc-r2000ic-165f",
            "--q-deg",
            "0,10,-20,0,30,0",
            "--wrench",
            "100,-50,200,1,2,3",
            "--stiffness",
            STIFFNESS,
        ],
    ),
    (
        "identify-cv",
        "identify-drives",
        &[
            "identify",
            "--setup",
            "fanuc-r2000ic-165f",
            "--data",
            FANUC,
            "--cross-validate",
        ],
    ),
    (
        "validate",
        "validate",
        &[
            "validate",
            "--setup",
            "fanuc-r2000ic-165f",
            "--data",
            FANUC,
            "--stiffness",
            STIFFNESS,
        ],
    ),
    (
        "evaluate",
        "evaluate",
        &["evaluate", "--setup", CELL, "--postures", GROUP],
    ),
    (
        "register-postures",
        "register-postures",
        &[
            "register",
            "--setup",
            CELL,
            "--count",
            "3",
            "--candidates",
            "500",
        ],
    ),
];

/// `before` as today's command writes it: `kind` first, the keys renamed.
fn renamed(before: &str, kind: &str) -> String {
    let mut text = before.replacen("{\n", &format!("{{\n  \"kind\": \"{kind}\",\n"), 1);
    for (former, today) in RENAMED {
        text = text.replace(&format!("\"{former}\":"), &format!("\"{today}\":"));
    }
    text
}

#[test]
fn the_examples_documents_changed_only_by_kind_and_the_renamed_keys() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/documents");
    let mut renames = 0;
    for (file, kind, args) in DOCUMENTS {
        let before = std::fs::read_to_string(data.join(format!("{file}.json"))).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_stiffid"))
            .current_dir(&repo)
            .args(args)
            .arg("--json")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{file}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let today = String::from_utf8(out.stdout).unwrap();
        assert_eq!(today, renamed(&before, kind), "{file}");
        renames += RENAMED.iter().filter(|(f, _)| before.contains(f)).count();
    }
    // A comparison that can fail: the documents hold renamed keys.
    assert!(renames >= 4, "{renames}");
}

/// The options renamed: the old spelling is refused (exit code 2, one line) naming the new one,
/// where `--postures` still means a postures file it is read as one.
#[test]
fn the_old_spellings_are_refused_naming_the_new_ones() {
    let cell = crate::common::example("cell/zhang2021-tracker.toml");
    let milling = crate::common::example("milling/fanuc-milling.toml");
    let cases: [(&[&str], &str); 4] = [
        (
            &[
                "select",
                "--setup",
                &cell,
                "--start-random",
                "--postures",
                "6",
                "--out",
                "x.csv",
            ],
            "--postures: renamed --count in `stiffid select`",
        ),
        (
            &["register", "--setup", &cell, "--postures=3"],
            "--postures: renamed --count in `stiffid register`",
        ),
        (
            &[
                "compensate",
                "--setup",
                &milling,
                "--force-tolerance-percent",
                "10",
            ],
            "--force-tolerance-percent: renamed --force-tolerance-pct in `stiffid compensate`",
        ),
        (
            &[
                "place",
                "--setup",
                &milling,
                "--force-tolerance-percent",
                "10",
            ],
            "--force-tolerance-percent: renamed --force-tolerance-pct in `stiffid place`",
        ),
    ];
    for (args, message) in cases {
        crate::common::assert_usage_error(&crate::common::stiffid(args), &[message]);
    }
    let group = crate::common::example("cell/feasible-relative-a.csv");
    let evaluate = crate::common::stiffid(&["evaluate", "--setup", &cell, "--postures", &group]);
    crate::common::assert_success(&evaluate);
}
