//! Options renamed or removed (`stiffid_cli::renamed`): refused in their command only.

use stiffid_cli::renamed::refused;

#[test]
fn the_old_spelling_is_refused_in_its_command_only() {
    let message = refused(&["select", "--setup", "s", "--postures", "6"]).unwrap();
    assert_eq!(
        message,
        "--postures: renamed --count in `stiffid select` (the number of postures; --postures is a postures file in evaluate, plot and simulate)"
    );
    let at = ["--package-path", "select", "register", "--postures=4"];
    assert!(refused(&at).unwrap().contains("`stiffid register`"));
    let tolerance = ["compensate", "--force-tolerance-percent", "20"];
    assert!(refused(&tolerance)
        .unwrap()
        .starts_with("--force-tolerance-percent: renamed --force-tolerance-pct"));
    // A postures file where --postures means one, and the new spellings, pass.
    assert_eq!(refused(&["evaluate", "--postures", "p.csv"]), None);
    assert_eq!(refused(&["select", "--count", "6"]), None);
    assert_eq!(refused(&["select", "--postures-file"]), None);
    assert_eq!(refused(&["--package-path", "select"]), None);
    // compensate's options retired for --free, in compensate only.
    let free = ["compensate", "--setup", "s", "--free-tool-axis"];
    assert_eq!(
        refused(&free).unwrap(),
        "--free-tool-axis: removed; write --free tool-rotation=-90..90/2"
    );
    assert_eq!(refused(&["place", "--free-tool-axis"]), None);
}
