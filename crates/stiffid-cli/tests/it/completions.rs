//! `stiffid completions` and `stiffid man`: generated from the command's definition, complete,
//! and write errors are an error exit.

use crate::common;
use common::{assert_success, assert_usage_error, stiffid};

const SUBCOMMANDS: [&str; 5] = ["reproduce", "select", "identify", "evaluate", "simulate"];

#[test]
fn completions_for_bash_zsh_and_fish_name_every_subcommand_and_option() {
    for shell in ["bash", "zsh", "fish"] {
        let out = stiffid(&["completions", shell]);
        assert_success(&out);
        let script = String::from_utf8(out.stdout).unwrap();
        for word in SUBCOMMANDS.iter().chain(&["criterion", "postures"]) {
            assert!(script.contains(word), "{shell}: {word} missing");
        }
    }
}

#[test]
fn the_bash_completion_script_is_valid_bash() {
    let out = stiffid(&["completions", "bash"]);
    let dir = common::temp_dir("completions-bash");
    let path = common::write_file(
        &dir,
        "stiffid.bash",
        &String::from_utf8(out.stdout).unwrap(),
    );
    let check = std::process::Command::new("bash")
        .arg("-n")
        .arg(&path)
        .output()
        .expect("bash");
    assert!(
        check.status.success(),
        "{}",
        String::from_utf8_lossy(&check.stderr)
    );
}

#[test]
fn man_pages_document_the_command_and_each_subcommand() {
    let out = stiffid(&["man"]);
    assert_success(&out);
    let page = String::from_utf8(out.stdout).unwrap();
    assert!(
        page.starts_with(".ie") && page.contains(".TH stiffid 1"),
        "{page}"
    );
    for sub in SUBCOMMANDS {
        assert!(page.contains(sub), "{sub} missing from the main page");
    }
    let out = stiffid(&["man", "select"]);
    assert_success(&out);
    let page = String::from_utf8(out.stdout).unwrap();
    assert!(page.contains(".TH stiffid-select 1"), "{page}");
    assert!(page.contains("\\-\\-criterion"), "{page}");
}

#[test]
fn an_unknown_man_page_names_the_subcommands() {
    let out = stiffid(&["man", "nope"]);
    assert_usage_error(&out, &["nope", "select", "reproduce"]);
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_device_is_an_error_exit_not_a_panic() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stiffid"))
        .args(["completions", "zsh"])
        .stdout(std::fs::File::create("/dev/full").unwrap())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.starts_with("error: ") && !stderr.contains("panicked"),
        "{stderr}"
    );
}
