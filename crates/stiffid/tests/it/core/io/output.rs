use std::path::{Path, PathBuf};
use stiffid_core::io::output::*;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stiffid-output-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d.canonicalize().unwrap()
}

#[test]
fn the_rules_refuse_what_must_not_be_written() {
    let d = dir("rules");
    let none = |_: &Path| None;
    let new = d.join("new.toml");
    assert_eq!(resolve(&new, "out", none).unwrap(), new);
    let e = resolve(&d, "out", none).unwrap_err().to_string();
    assert!(
        e.ends_with("exists and is not a regular file (a directory); refusing to replace it"),
        "{e}"
    );
    let e = resolve(&d.join("no/x.toml"), "--out", none)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("--out ") && e.contains(": no directory "),
        "{e}"
    );
    for spelt_as_directory in ["new/", "new/.", "new/.."] {
        let e = resolve(&d.join(spelt_as_directory), "--out", none).unwrap_err();
        assert!(
            e.to_string().ends_with("a directory, expected a file name"),
            "{e}"
        );
        assert!(!d.join("new").exists());
    }
    let input = d.join("in.csv");
    std::fs::write(&input, "x").unwrap();
    let is_input = |p: &Path| (p == input).then(|| input.clone());
    let e = resolve(&input, "out", is_input).unwrap_err().to_string();
    assert!(e.contains("refusing to write over the input file"), "{e}");
    #[cfg(unix)]
    {
        let link = d.join("link.csv");
        std::os::unix::fs::symlink(&input, &link).unwrap();
        assert!(
            resolve(&link, "out", is_input).is_err(),
            "through a symlink to an input"
        );
        assert_eq!(resolve(&link, "out", none).unwrap(), input, "to its target");
        let dangling = d.join("dangling.csv");
        std::os::unix::fs::symlink(d.join("gone"), &dangling).unwrap();
        let e = resolve(&dangling, "out", none).unwrap_err().to_string();
        assert!(e.contains("a symlink to nothing"), "{e}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn files_are_placed_whole_and_new_files_never_replace_one() {
    let d = dir("place");
    let target = d.join("out.txt");
    let tmp = write_temporary(&d, b"first").unwrap();
    place(&tmp, &target, true).unwrap();
    assert_eq!(std::fs::read(&target).unwrap(), b"first");
    let tmp = write_temporary(&d, b"second").unwrap();
    let e = place(&tmp, &target, true).unwrap_err().to_string();
    assert!(e.contains("exists"), "{e}");
    assert_eq!(std::fs::read(&target).unwrap(), b"first");
    let tmp = write_temporary(&d, b"third").unwrap();
    place(&tmp, &target, false).unwrap();
    assert_eq!(std::fs::read(&target).unwrap(), b"third");
    let left: Vec<_> = std::fs::read_dir(&d).unwrap().collect();
    assert_eq!(left.len(), 1, "no temporary file left behind");
    std::fs::remove_dir_all(&d).unwrap();
}
